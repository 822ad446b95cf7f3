#include "aggregator/mcmcda_association.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <set>
#include <vector>

#include "aggregator/association.hpp"
#include "aggregator/track_merger.hpp"

using wsn::aggregator::makeAssociator;
using wsn::aggregator::McmcdaAssociator;
using wsn::aggregator::resolveAssociationParams;
using wsn::aggregator::SupernodeTracks;
using wsn::aggregator::TrackMerger;
using wsn::common::Scenario;
using wsn::common::ScenarioError;
using wsn::common::TrackEstimate;
using wsn::common::TrackId;

namespace {

/// A supernode's track id, as common/messages.hpp defines it.
TrackId id(std::uint32_t supernode, std::uint64_t serial) { return (TrackId{supernode} + 1) << 48 | serial; }

/// The association context of a scenario with two supernodes, parameters resolved.
wsn::aggregator::AssociationContext twoSupernodes(const std::string& association = "mcmcda") {
  Scenario s;
  s.source_path = "test.yaml";
  s.supernodes = {{25.0, 50.0}, {75.0, 50.0}};
  s.aggregator.association = association;
  resolveAssociationParams(s);
  return wsn::aggregator::associationContext(s);
}

/// A target moving along x at 1 separation per tick: x = 40 + t, y = 50.
double targetX(std::int32_t t) { return 40.0 + t; }

/// A supernode track observed at `seen` and reported at `tick`: its state at `seen` predicted on.
TrackEstimate observedAt(TrackId track, std::int32_t tick, std::int32_t seen) {
  TrackEstimate e{track, targetX(seen) + (tick - seen), 50.0, 1.0, 0.0, {}, seen, {}, {}};
  return e;
}

}  // namespace

TEST_CASE("A target whose track breaks at a boundary keeps one global id", "[aggregator][mcmcda_association]") {
  // Supernode 0 tracks the target up to tick 8 (x = 48, at the boundary x = 50 the handoff is lost);
  // supernode 1 starts a track of its own at tick 11 after two unreported ticks. The gated merge
  // has nothing to merge at any tick, so the target changes id; Yc links the two fragments.
  const TrackId a = id(0, 1);
  const TrackId b = id(1, 7);
  const auto inputs = [&](std::int32_t t) {
    std::vector<SupernodeTracks> in{{0, {}}, {1, {}}};
    if (t <= 8) in[0].tracks.push_back(observedAt(a, t, t));
    if (t >= 11) in[1].tracks.push_back(observedAt(b, t, t));
    return in;
  };
  auto mcmcda = makeAssociator(twoSupernodes());
  TrackMerger gated;
  std::set<TrackId> mcmcda_ids;
  std::set<TrackId> gated_ids;
  for (std::int32_t t = 1; t <= 20; ++t) {
    const auto global = mcmcda->associate(t, inputs(t));
    INFO("tick " << t);
    if (t <= 8 || t >= 11) {
      REQUIRE(global.size() == 1);
      CHECK(std::abs(global[0].x - targetX(t)) < 0.5);
    }
    for (const auto& g : global) mcmcda_ids.insert(g.track);
    for (const auto& g : gated.merge(t, inputs(t))) gated_ids.insert(g.track);
  }
  CHECK(gated_ids.size() == 2);
  // The first supernode track names the target (ω̂ takes the id of its first element's track).
  CHECK(mcmcda_ids == std::set<TrackId>{a});
}

TEST_CASE("A handed-over track reported by both supernodes is one element per tick",
          "[aggregator][mcmcda_association]") {
  // During a handoff the sender and the receiver may both report the track under its id for a
  // tick, with the same last observation: one observation, so one global track, not two.
  const TrackId a = id(0, 1);
  McmcdaAssociator associator(twoSupernodes());
  for (std::int32_t t = 1; t <= 12; ++t) {
    std::vector<SupernodeTracks> in{{0, {}}, {1, {}}};
    if (t <= 7) in[0].tracks.push_back(observedAt(a, t, t));
    if (t >= 6) in[1].tracks.push_back(observedAt(a, t, t == 6 ? 5 : t));  // the anchor, then its own
    const auto global = associator.associate(t, in);
    INFO("tick " << t);
    REQUIRE(global.size() == 1);
    CHECK(global[0].track == a);
  }
  CHECK(associator.engine().lastStep().tracks == 1);
}

TEST_CASE("A new supernode track is reported from its first tick and keeps its id", "[aggregator][mcmcda_association]") {
  // One element cannot form an MCMCDA track, so the first tick passes the supernode's estimate
  // through; the global track that grows from it takes the same id.
  const TrackId a = id(1, 3);
  McmcdaAssociator associator(twoSupernodes());
  CHECK(associator.associate(1, {{0, {}}, {1, {}}}).empty());
  for (std::int32_t t = 2; t <= 10; ++t) {
    const auto global = associator.associate(t, {{0, {}}, {1, {observedAt(a, t, t)}}});
    INFO("tick " << t);
    REQUIRE(global.size() == 1);
    CHECK(global[0].track == a);
    if (t == 2) CHECK(global[0] == observedAt(a, t, t));  // passed through as reported
  }
}

TEST_CASE("Coasted estimates are not elements, and a late observation goes into its own slot",
          "[aggregator][mcmcda_association]") {
  const TrackId a = id(0, 1);
  McmcdaAssociator associator(twoSupernodes());
  std::int32_t elements = 0;
  for (std::int32_t t = 1; t <= 10; ++t) {
    // Observed at 1..4, coasting (last seen 4) at 5..7, then the report of tick 7 arrives at 9.
    const std::int32_t seen = t <= 4 ? t : (t <= 8 ? 4 : 7);
    associator.associate(t, {{0, {observedAt(a, t, seen)}}, {1, {}}});
    elements = associator.engine().lastStep().observations;
  }
  // Elements at ticks 1, 2, 3, 4 and 7 (no anchor yet: nothing left the 10-tick window).
  CHECK(elements == 5);
  CHECK(associator.droppedStale() == 0);
}

TEST_CASE("Track-level association does not depend on input order", "[aggregator][mcmcda_association]") {
  std::mt19937 shuffle_rng(7);
  const auto run = [&](bool shuffled) {
    McmcdaAssociator associator(twoSupernodes());
    std::vector<std::vector<TrackEstimate>> out;
    for (std::int32_t t = 1; t <= 15; ++t) {
      std::vector<SupernodeTracks> in{{0, {}}, {1, {}}};
      for (std::uint64_t k = 1; k <= 4; ++k) {
        const auto kk = static_cast<double>(k);
        TrackEstimate e{id(k % 2, k), 10.0 * kk + t, 20.0 + 5.0 * kk, 1.0, 0.0, {}, t, {}, {}};
        in[k % 2].tracks.push_back(e);
      }
      if (shuffled) {
        std::shuffle(in.begin(), in.end(), shuffle_rng);
        for (auto& s : in) std::shuffle(s.tracks.begin(), s.tracks.end(), shuffle_rng);
      }
      out.push_back(associator.associate(t, in));
    }
    return out;
  };
  CHECK(run(false) == run(true));
}

TEST_CASE("Track-level association drops and counts non-finite tracks", "[aggregator][mcmcda_association]") {
  McmcdaAssociator associator(twoSupernodes());
  TrackEstimate bad = observedAt(id(0, 1), 1, 1);
  bad.vx = NAN;
  const auto global = associator.associate(1, {{0, {bad, observedAt(id(0, 2), 1, 1)}}});
  CHECK(associator.droppedNonFinite() == 1);
  REQUIRE(global.size() == 1);
  CHECK(global[0].track == id(0, 2));
}

TEST_CASE("The association registry names its methods and checks their parameters",
          "[aggregator][mcmcda_association]") {
  CHECK(dynamic_cast<McmcdaAssociator*>(makeAssociator(twoSupernodes("mcmcda")).get()) != nullptr);
  CHECK(dynamic_cast<TrackMerger*>(makeAssociator(twoSupernodes("gated")).get()) != nullptr);

  const auto context = twoSupernodes();
  CHECK(context.supernode_count == 2);
  CHECK(context.params.at("confirm_observations").value == 2);
  CHECK(context.params.at("false_alarm_density").value == 1e-5);
  CHECK(context.params.at("window_size").value == 10);

  Scenario unknown;
  unknown.source_path = "s.yaml";
  unknown.aggregator.association = "hungarian";
  unknown.aggregator.association_line = 4;
  REQUIRE_THROWS_MATCHES(resolveAssociationParams(unknown), ScenarioError,
                         Catch::Message("s.yaml:4: unknown aggregator association 'hungarian'; expected one of: "
                                        "mcmcda, gated"));
  Scenario bad;
  bad.source_path = "s.yaml";
  bad.aggregator.association = "gated";
  bad.aggregator.params["window_size"] = {10, 6};
  REQUIRE_THROWS_MATCHES(resolveAssociationParams(bad), ScenarioError,
                         Catch::Message("s.yaml:6: unknown parameter 'window_size' for association 'gated'; expected "
                                        "one of: gate_distance, memory_ticks"));
  Scenario range;
  range.source_path = "s.yaml";
  range.aggregator.params["confirm_observations"] = {2.5, 7};
  REQUIRE_THROWS_MATCHES(resolveAssociationParams(range), ScenarioError,
                         Catch::Message("s.yaml:7: 'aggregator.params.confirm_observations' must be a whole number, "
                                        "got 2.5"));
}

TEST_CASE("The track-level association derives the targets' model and keeps the supernode-track defaults",
          "[aggregator][mcmcda_association]") {
  // Fast targets (speed bound 9.917 per tick): with the fixed link speed of 3 per tick the
  // association could not join a fast target's consecutive supernode tracks at all.
  wsn::common::ObservationStatistics stats;
  stats.max_speed = {9.917, "speed bound"};
  stats.velocity_sigma = {3.606, "fast class"};
  stats.termination_probability = {0.065, "lifetimes"};
  stats.birth_density = {2e-5, "10 drawn targets"};
  stats.process_noise_sigma = 0.15;
  stats.delta = 1.0;
  Scenario s;
  s.source_path = "test.yaml";
  resolveAssociationParams(s, [&]() -> const wsn::common::ObservationStatistics& { return stats; });
  const auto& p = s.aggregator.params;
  // v-bar = 9.917 + 3 sqrt 2 x 0.2 (measurement_sigma, a fixed default here) = 10.766.
  CHECK(p.at("max_speed").value == Approx(9.917 + 3.0 * std::sqrt(2.0) * 0.2));
  CHECK(p.at("initial_velocity_sigma").value == Approx(std::hypot(3.606, 0.15)));
  CHECK(p.at("termination_probability").value == 0.065);
  CHECK(p.at("birth_density").value == 2e-5);
  CHECK(s.derived.contains("aggregator.params.max_speed"));
  CHECK(p.at("measurement_sigma").value == 0.2);
  CHECK(p.at("confirm_observations").value == 2);
  CHECK(p.at("false_alarm_density").value == 1e-5);
}

TEST_CASE("A track the chain re-forms under a new id is reported under its old one", "[aggregator][mcmcda_association]") {
  using wsn::aggregator::ReportedIds;
  ReportedIds ids;
  // Tick 1: engine track 100 holds supernode track 7.
  auto a = ids.assign({{100, {7}}}, {}, {100});
  CHECK(a.global == std::vector<TrackId>{100});
  // Tick 2: the chain split the target's newest elements off into engine track 200 (100 lives on
  // unreported): 200 is new to the output and its supernode track was reported as 100.
  a = ids.assign({{200, {7}}}, {}, {100, 200});
  CHECK(a.global == std::vector<TrackId>{100});
  // Tick 3: still 200 in the engine; the alias holds.
  a = ids.assign({{200, {7, 7}}}, {}, {200});
  CHECK(a.global == std::vector<TrackId>{100});
  // Tick 4: the chain merged back into 100 while 200 lives: the previous output's id goes to
  // the first claimant in input order, the other is reported under its engine id.
  a = ids.assign({{100, {7}}, {200, {8}}}, {}, {100, 200});
  CHECK(a.global == std::vector<TrackId>{100, 200});
}

TEST_CASE("A new track takes the free id most of its supernode tracks had", "[aggregator][mcmcda_association]") {
  using wsn::aggregator::ReportedIds;
  ReportedIds ids;
  auto a = ids.assign({{100, {7}}, {101, {8}}}, {9}, {100, 101});
  CHECK(a.global == std::vector<TrackId>{100, 101});
  CHECK(a.passed == std::vector<TrackId>{9});  // passed through under its own id
  // Engine track 300 holds two elements of supernode track 8 and one of 9 (passed through as 9):
  // 101 has two votes, 9 one; 101 wins. 100 is reported as before.
  a = ids.assign({{100, {7}}, {300, {8, 8, 9}}}, {}, {100, 300});
  CHECK(a.global == std::vector<TrackId>{100, 101});
  // A passed-through supernode track whose id is taken is dropped (0).
  a = ids.assign({{100, {7}}}, {100}, {100});
  CHECK(a.passed == std::vector<TrackId>{0});
}

TEST_CASE("A track both supernodes pass through is the lower supernode's, whatever the input order",
          "[aggregator][mcmcda_association]") {
  const TrackId a = id(0, 1);
  const TrackEstimate from_sender{a, 10.0, 10.0, 1.0, 0.0, {}, 1, {}, {}};
  const TrackEstimate from_receiver{a, 10.5, 10.0, 1.0, 0.0, {}, 1, {}, {}};
  McmcdaAssociator in_order(twoSupernodes());
  McmcdaAssociator reversed(twoSupernodes());
  const auto first = in_order.associate(1, {{0, {from_sender}}, {1, {from_receiver}}});
  const auto second = reversed.associate(1, {{1, {from_receiver}}, {0, {from_sender}}});
  REQUIRE(first.size() == 1);
  CHECK(first[0] == from_sender);
  CHECK(second == first);
}

TEST_CASE("A track-level global track carries the class and stop probability of the supernode tracks it holds",
          "[aggregator][mcmcda_association]") {
  // The boundary case above: supernode 0's track (class evidence .8 / .2) to tick 8, supernode 1's
  // (.3 / .7) from tick 11, linked into one global track. Each tick the global track's class is
  // that of the supernode track reported for it, the newer evidence winning once it takes over.
  const TrackId a = id(0, 1);
  const TrackId b = id(1, 7);
  McmcdaAssociator associator(twoSupernodes());
  for (std::int32_t t = 1; t <= 20; ++t) {
    std::vector<SupernodeTracks> in{{0, {}}, {1, {}}};
    if (t <= 8) in[0].tracks.push_back(observedAt(a, t, t));
    if (t >= 11) in[1].tracks.push_back(observedAt(b, t, t));
    for (auto& track : in[0].tracks) track.class_probabilities = {0.8, 0.2};
    for (auto& track : in[1].tracks) track.class_probabilities = {0.3, 0.7};
    for (auto& track : in[1].tracks) track.stop_probability = 0.25;
    const auto global = associator.associate(t, in);
    INFO("tick " << t);
    if (global.empty()) continue;
    REQUIRE(global.size() == 1);
    if (t <= 8) CHECK(global[0].class_probabilities == std::vector<double>{0.8, 0.2});
    if (t >= 11) CHECK(global[0].class_probabilities == std::vector<double>{0.3, 0.7});
    if (t == 9 || t == 10) CHECK(global[0].class_probabilities.empty());  // coasting, nothing reported
    // The stop probability likewise: supernode 1's, and none while supernode 0's track has none.
    CHECK(global[0].stop_probability == (t >= 11 ? std::optional<double>(0.25) : std::nullopt));
  }
}

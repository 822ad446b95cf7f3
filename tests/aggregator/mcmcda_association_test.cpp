#include "aggregator/mcmcda_association.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <set>
#include <vector>

#include "aggregator/association.hpp"
#include "aggregator/track_fusion.hpp"
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
  // Without the scenario's statistics, the engine's fixed default.
  CHECK(context.params.at("false_alarm_density").value ==
        wsn::supernode::mcmcda::McmcdaParams{}.model.false_alarm_density);
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

TEST_CASE("The track-level association derives its model as the supernodes do and keeps two elements to confirm",
          "[aggregator][mcmcda_association]") {
  // Fast targets (speed bound 9.917 per tick): with the fixed link speed of 3 per tick the
  // association could not join a fast target's consecutive supernode tracks at all.
  wsn::common::ObservationStatistics stats;
  stats.max_speed = {9.917, "speed bound"};
  stats.velocity_sigma = {3.606, "fast class"};
  stats.termination_probability = {0.065, "lifetimes"};
  stats.birth_density = {2e-5, "10 drawn targets"};
  stats.position_sigma = {0.0826, "probe"};
  stats.sensing_probability = {0.9, "probe"};
  stats.delivery_probability = {0.5, "topology"};
  stats.on_time_probability = {0.5, "topology"};
  stats.arrival_by_lag = {0.5};
  stats.false_report_density = {6.25e-6, "probe"};
  stats.process_noise_sigma = 0.15;
  stats.delta = 1.0;
  Scenario s;
  s.source_path = "test.yaml";
  resolveAssociationParams(s, [&]() -> const wsn::common::ObservationStatistics& { return stats; });
  const auto& p = s.aggregator.params;
  // An element errs by at most a report's error: sigma 0.0826, and v-bar = 9.917 + 3 sqrt 2 x 0.0826.
  CHECK(p.at("measurement_sigma").value == Approx(0.0826));
  CHECK(p.at("max_speed").value == Approx(9.917 + 3.0 * std::sqrt(2.0) * 0.0826));
  CHECK(p.at("initial_velocity_sigma").value == Approx(std::hypot(3.606, 0.15)));
  CHECK(p.at("termination_probability").value == 0.065);
  CHECK(p.at("birth_density").value == 2e-5);
  // Observed when a report reached its supernode: pd = 0.9 sensed x 0.5 arrived = 0.45, and a run
  // of misses ends a track once 0.55^k <= 0.01: k = 8 (0.55^7 = 0.0152, 0.55^8 = 0.0084).
  CHECK(p.at("detection_probability").value == Approx(0.45));
  CHECK(p.at("max_gap").value == 8);
  // A false element is a delivered false report a supernode confirmed: at most 6.25e-6 x 0.5.
  CHECK(p.at("false_alarm_density").value == Approx(3.125e-6));
  for (const char* key : {"measurement_sigma", "max_speed", "detection_probability", "max_gap", "false_alarm_density"})
    CHECK(s.derived.contains(std::string("aggregator.params.") + key));
  // The elements are confirmed tracks already, and one per supernode track and tick.
  CHECK(p.at("confirm_observations").value == 2);
  CHECK(p.at("merge_radius").value == 0);
  CHECK_FALSE(s.derived.contains("aggregator.params.confirm_observations"));
}

TEST_CASE("A track the chain re-forms under a new id is reported under its old one", "[aggregator][mcmcda_association]") {
  using wsn::aggregator::ReportedIds;
  ReportedIds ids;
  TrackId next = 1000;
  const auto mint = [&] { return next++; };
  // Tick 1: engine track 100 holds supernode track 7.
  auto a = ids.assign({{100, {7}}}, {}, {100}, mint);
  CHECK(a.global == std::vector<TrackId>{100});
  // Tick 2: the chain split the target's newest elements off into engine track 200 (100 lives on
  // unreported): 200 is new to the output and its supernode track was reported as 100.
  a = ids.assign({{200, {7}}}, {}, {100, 200}, mint);
  CHECK(a.global == std::vector<TrackId>{100});
  // Tick 3: still 200 in the engine; its supernode track's id holds.
  a = ids.assign({{200, {7}}}, {}, {200}, mint);
  CHECK(a.global == std::vector<TrackId>{100});
  // Tick 4: the chain merged back into 100 while 200 lives on with a new target's track 8: 7 keeps
  // its global id, and 200, reported as 100 before, finds it taken and is reported under its own.
  a = ids.assign({{100, {7}}, {200, {8}}}, {}, {100, 200}, mint);
  CHECK(a.global == std::vector<TrackId>{100, 200});
  CHECK(next == 1000);
}

TEST_CASE("A global track takes the free id most of its supernode tracks had", "[aggregator][mcmcda_association]") {
  using wsn::aggregator::ReportedIds;
  ReportedIds ids;
  TrackId next = 1000;
  const auto mint = [&] { return next++; };
  auto a = ids.assign({{100, {7}}, {101, {8}}}, {9}, {100, 101}, mint);
  CHECK(a.global == std::vector<TrackId>{100, 101});
  CHECK(a.passed == std::vector<TrackId>{9});  // passed through under its own id
  // Engine track 300 holds supernode tracks 8 and 9 now (a handoff: 8 coasting, 9 new at the
  // receiver); 101 and 9 have one vote each and the smaller id wins. 100 is reported as before.
  a = ids.assign({{100, {7}}, {300, {8, 9}}}, {}, {100, 300}, mint);
  CHECK(a.global == std::vector<TrackId>{100, 9});
  // Identity follows the supernode track: engine track 100 now holds supernode track 8, last
  // reported in 9, and track 7, passed through, keeps 100, its global id of the previous tick.
  a = ids.assign({{100, {8}}}, {7}, {100}, mint);
  CHECK(a.global == std::vector<TrackId>{9});
  CHECK(a.passed == std::vector<TrackId>{100});
  // A passed-through supernode track whose ids are both taken is reported under a fresh one.
  a = ids.assign({{100, {7}}, {101, {8}}}, {100}, {100, 101}, mint);
  CHECK(a.global == std::vector<TrackId>{100, 9});
  CHECK(a.passed == std::vector<TrackId>{1000});
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

TEST_CASE("A global track reports its one supernode track as published and ends when it ends",
          "[aggregator][mcmcda_association]") {
  // The supernode's estimate is already filtered: the aggregator passes it through (state and
  // covariance), and it stops the tick the supernode stops, whatever its own engine thinks.
  const TrackId a = id(0, 1);
  auto associator = makeAssociator(twoSupernodes());
  for (std::int32_t t = 1; t <= 12; ++t) {
    std::vector<SupernodeTracks> in{{0, {}}, {1, {}}};
    if (t <= 8) {
      TrackEstimate e = observedAt(a, t, t);
      e.y = 50.0 + 0.05 * (t % 3);  // not a straight line: a re-filtered state would differ
      e.covariance = {0.01, 0, 0, 0, 0, 0.01, 0, 0, 0, 0, 0.02, 0, 0, 0, 0, 0.02};
      in[0].tracks.push_back(e);
    }
    const auto global = associator->associate(t, in);
    INFO("tick " << t);
    if (t > 8) {
      CHECK(global.empty());
      continue;
    }
    REQUIRE(global.size() == 1);
    TrackEstimate expected = in[0].tracks[0];
    CHECK(global[0] == expected);
  }
}

TEST_CASE("A handed-over target's two supernode tracks are fused while both are reported",
          "[aggregator][mcmcda_association]") {
  // Supernode 0 observes the target up to tick 8 and reports its track coasting (larger position
  // covariance, a well-learnt velocity) at ticks 9 and 10; supernode 1 observes it from tick 9 under
  // a new id (a sharp position, a poor velocity). Over those two ticks one global track holds both,
  // and its state is their covariance intersection, nearer the observed position.
  const TrackId a = id(0, 1);
  const TrackId b = id(1, 7);
  auto associator = makeAssociator(twoSupernodes());
  for (std::int32_t t = 1; t <= 14; ++t) {
    std::vector<SupernodeTracks> in{{0, {}}, {1, {}}};
    if (t <= 10) {
      TrackEstimate e = observedAt(a, t, std::min(t, 8));
      const double grow = t <= 8 ? 1.0 : 4.0 * (t - 8);
      e.covariance = {0.01 * grow, 0, 0, 0, 0, 0.01 * grow, 0, 0, 0, 0, 0.005, 0, 0, 0, 0, 0.005};
      in[0].tracks.push_back(e);
    }
    if (t >= 9) {
      TrackEstimate e = observedAt(b, t, t);
      e.y = 50.3;
      e.covariance = {0.01, 0, 0, 0, 0, 0.01, 0, 0, 0, 0, 0.05, 0, 0, 0, 0, 0.05};  // a new track's velocity is poor
      in[1].tracks.push_back(e);
    }
    const auto global = associator->associate(t, in);
    INFO("tick " << t);
    REQUIRE(global.size() == 1);
    CHECK(global[0].track == a);
    if (t == 9 || t == 10) {
      const TrackEstimate* members[] = {&in[0].tracks[0], &in[1].tracks[0]};
      const auto fused = wsn::aggregator::fuseTrackEstimates(a, members);
      CHECK(global[0] == fused);
      CHECK(global[0].y > 50.15);  // nearer supernode 1's observed track than the coasting one
      CHECK(global[0].y < 50.3);
    }
  }
}

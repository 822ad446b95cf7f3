// Known answers of the online MCMCDA engine (Oh §VI) driven through SupernodeTracker: crossing
// targets with and without clutter and misses, a late observation filling a gap, identities across
// windows and a handed-over track continued under its id.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <vector>

#include <catch2/catch.hpp>

#include "common/rng.hpp"
#include "supernode/mcmcda/mcmcda_engine.hpp"
#include "supernode/supernode_tracker.hpp"
#include "tests/supernode/test_support.hpp"

namespace wsn::supernode::mcmcda {
namespace {

using common::Observation;
using test::observation;

common::Scenario mcmcdaScenario(std::int32_t window_size = 10, double max_gap = 5) {
  common::Scenario s;
  s.source_path = "test.yaml";
  s.supernodes = {{50.0, 50.0}};
  s.tracker.engine = "mcmcda";
  s.tracker.window_size = window_size;
  s.tracker.params["measurement_sigma"] = {0.2, 0};
  s.tracker.params["false_alarm_density"] = {1e-3, 0};
  s.tracker.params["max_gap"] = {max_gap, 0};
  resolveEngineParams(s, wsn::common::kNoStatistics);
  return s;
}

/// Heavy loss: pd 0.1, pz 0.02, confirmation at one report, next to no clutter, a window of 4 ticks
/// and max_gap 8.
common::Scenario heavyLossScenario() {
  common::Scenario scenario = mcmcdaScenario(4, 8);
  scenario.tracker.params["confirm_observations"] = {1, 0};
  scenario.tracker.params["false_alarm_density"] = {1e-9, 0};
  scenario.tracker.params["detection_probability"] = {0.1, 0};
  scenario.tracker.params["termination_probability"] = {0.02, 0};
  resolveEngineParams(scenario, wsn::common::kNoStatistics);
  return scenario;
}

struct Target {
  double x0, y0, vx, vy;
  double x(std::int32_t t) const { return x0 + vx * (t - 1); }
  double y(std::int32_t t) const { return y0 + vy * (t - 1); }
};

/// Noise of std. deviation sigma, deterministic per (target, tick).
double jitter(std::uint64_t key, std::int32_t tick, double sigma) {
  common::Stream s(99, common::Purpose::kSensorNoise, key, tick);
  return sigma * s.normal();
}

/// Runs ticks 1..T through one supernode; `observations_at(t)` gives what is delivered at t.
template <class Deliver>
std::vector<SupernodeTracker::TickOutput> run(const common::Scenario& scenario, std::int32_t ticks, Deliver deliver) {
  auto tracker = test::trackerFor(scenario, 0);
  std::vector<SupernodeTracker::TickOutput> outputs;
  for (std::int32_t t = 1; t <= ticks; ++t) outputs.push_back(tracker.step(t, deliver(t), {}));
  return outputs;
}

/// For each target, the ids of the tracks nearest to it (within `radius`) from tick `from` on,
/// except within 2 ticks of `crossing`, where targets sit on top of each other and "nearest" means
/// nothing.
std::map<int, std::set<common::TrackId>> idsPerTarget(const std::vector<SupernodeTracker::TickOutput>& outputs,
                                                      const std::vector<Target>& targets, std::int32_t from,
                                                      double radius, std::int32_t crossing = -100) {
  std::map<int, std::set<common::TrackId>> ids;
  for (const auto& out : outputs) {
    if (out.tick < from || std::abs(out.tick - crossing) <= 2) continue;
    for (std::size_t k = 0; k < targets.size(); ++k) {
      const common::TrackEstimate* nearest = nullptr;
      double best = radius;
      for (const auto& track : out.tracks) {
        const double d = std::hypot(track.x - targets[k].x(out.tick), track.y - targets[k].y(out.tick));
        if (d < best) {
          best = d;
          nearest = &track;
        }
      }
      if (nearest != nullptr) ids[static_cast<int>(k)].insert(nearest->track);
    }
  }
  return ids;
}

}  // namespace

TEST_CASE("mcmcda follows two crossing targets without clutter and keeps their identities", "[mcmcda]") {
  const std::vector<Target> targets = {{40, 40, 1.0, 0.5}, {40, 50, 1.0, -0.5}};  // cross at t = 11
  const auto outputs = run(mcmcdaScenario(), 25, [&](std::int32_t t) {
    std::vector<Observation> obs;
    for (std::size_t k = 0; k < targets.size(); ++k)
      obs.push_back(observation(t, t, targets[k].x(t) + jitter(k, t, 0.1), targets[k].y(t) + jitter(k + 7, t, 0.1),
                                static_cast<int>(k)));
    return obs;
  });
  for (const auto& out : outputs)
    if (out.tick >= 3) {
      INFO("tick " << out.tick);
      CHECK(out.tracks.size() == 2);
    }
  const auto ids = idsPerTarget(outputs, targets, 3, 1.0, 11);
  CHECK(ids.at(0).size() == 1);
  CHECK(ids.at(1).size() == 1);
  CHECK(*ids.at(0).begin() != *ids.at(1).begin());
}

TEST_CASE("mcmcda follows crossing targets through clutter and missed detections", "[mcmcda]") {
  const std::vector<Target> targets = {{40, 40, 1.0, 0.5}, {40, 50, 1.0, -0.5}};
  const auto outputs = run(mcmcdaScenario(), 30, [&](std::int32_t t) {
    std::vector<Observation> obs;
    for (std::size_t k = 0; k < targets.size(); ++k) {
      // Target 0 is missed every 4th tick, target 1 every 5th (never both at the crossing).
      if ((k == 0 && t % 4 == 0) || (k == 1 && t % 5 == 0)) continue;
      obs.push_back(observation(t, t, targets[k].x(t) + jitter(k, t, 0.1), targets[k].y(t) + jitter(k + 7, t, 0.1),
                                static_cast<int>(k)));
    }
    // Two false alarms a tick, uniform over a 30 x 30 box around the action.
    common::Stream clutter(5, common::Purpose::kSensorNoise, 1000, t);
    for (int c = 0; c < 2; ++c) obs.push_back(observation(t, t, clutter.uniform(30, 60), clutter.uniform(30, 60)));
    return obs;
  });
  std::int32_t right_count = 0;
  for (const auto& out : outputs)
    if (out.tick >= 5 && out.tracks.size() == 2) ++right_count;
  CHECK(right_count >= 24);  // of 26 ticks
  const auto ids = idsPerTarget(outputs, targets, 5, 1.0, 11);
  CHECK(ids.at(0).size() == 1);
  CHECK(ids.at(1).size() == 1);
}

TEST_CASE("mcmcda uses a late observation to fill the gap it belongs to", "[mcmcda]") {
  const Target target{20, 20, 1.0, 1.0};
  // With d-bar = 3, ticks 5 and 7 missed and the report of tick 6 arriving at tick 8 (into its own
  // slot), the track holds only through the late report: without it the gap 4 -> 8 exceeds d-bar.
  const auto deliver = [&](bool with_late) {
    return [&target, with_late](std::int32_t t) {
      std::vector<Observation> obs;
      if (t != 5 && t != 6 && t != 7) obs.push_back(observation(t, t, target.x(t), target.y(t)));
      if (t == 8 && with_late) obs.push_back(observation(6, 8, target.x(6), target.y(6)));
      return obs;
    };
  };
  const auto idsOf = [](const std::vector<SupernodeTracker::TickOutput>& outputs) {
    std::set<common::TrackId> ids;
    for (const auto& out : outputs)
      for (const auto& track : out.tracks) ids.insert(track.track);
    return ids;
  };
  const auto with_late = run(mcmcdaScenario(10, 3), 12, deliver(true));
  CHECK(idsOf(with_late).size() == 1);
  for (const auto& out : with_late)
    if (out.tick >= 8) {
      REQUIRE(out.tracks.size() == 1);
      CHECK(out.tracks[0].x == Approx(target.x(out.tick)).margin(0.3));
    }
  // The control: without the late report the track breaks in two.
  CHECK(idsOf(run(mcmcdaScenario(10, 3), 12, deliver(false))).size() == 2);
}

TEST_CASE("mcmcda keeps a track's id after its first observations leave the window", "[mcmcda]") {
  const Target target{10, 10, 0.8, 0.3};
  const auto outputs = run(mcmcdaScenario(5), 30, [&](std::int32_t t) {
    return std::vector<Observation>{observation(t, t, target.x(t) + jitter(1, t, 0.1), target.y(t) + jitter(2, t, 0.1))};
  });
  std::set<common::TrackId> ids;
  for (const auto& out : outputs)
    for (const auto& track : out.tracks) ids.insert(track.track);
  CHECK(ids.size() == 1);
  CHECK(outputs.back().tracks.size() == 1);
  CHECK(outputs.back().tracks[0].vx == Approx(0.8).margin(0.25));
}

TEST_CASE("mcmcda continues a handed-over track under its id", "[mcmcda]") {
  const auto scenario = mcmcdaScenario();
  auto tracker = test::trackerFor(scenario, 0);
  const Target target{30, 30, 1.0, 0.0};
  common::TrackHandoff handoff;
  handoff.track = (std::uint64_t{3} << 48) | 17;  // minted by supernode 2
  handoff.to_supernode = 0;
  handoff.last_tick = 4;
  handoff.state = {target.x(4), target.y(4), 1.0, 0.0};
  handoff.covariance = {0.04, 0, 0.01, 0, 0, 0.04, 0, 0.01, 0.01, 0, 0.02, 0, 0, 0.01, 0, 0.02};
  handoff.hits = 4;
  handoff.confirmed = true;
  for (std::int32_t t = 1; t <= 4; ++t) tracker.step(t, {}, {});
  const std::vector<common::TrackHandoff> incoming = {handoff};
  std::vector<SupernodeTracker::TickOutput> outputs;
  for (std::int32_t t = 5; t <= 15; ++t) {
    const std::vector<Observation> obs = {observation(t, t, target.x(t), target.y(t))};
    outputs.push_back(tracker.step(t, obs, t == 5 ? std::span(incoming) : std::span<const common::TrackHandoff>()));
  }
  for (const auto& out : outputs) {
    INFO("tick " << out.tick);
    REQUIRE(out.tracks.size() == 1);
    CHECK(out.tracks[0].track == handoff.track);
  }
}

TEST_CASE("mcmcda hands a crossing target to the next supernode, which continues it under its id", "[mcmcda]") {
  auto scenario = mcmcdaScenario();
  scenario.supernodes = {{25.0, 50.0}, {75.0, 50.0}};
  std::array<SupernodeTracker, 2> trackers{test::trackerFor(scenario, 0), test::trackerFor(scenario, 1)};
  std::vector<common::TrackHandoff> in_flight;
  const Target target{40.5, 50.0, 1.0, 0.2};  // crosses x = 50 between ticks 10 and 11
  std::set<common::TrackId> ids;
  for (std::int32_t t = 1; t <= 25; ++t) {
    const auto o = observation(t, t, target.x(t) + jitter(1, t, 0.05), target.y(t) + jitter(2, t, 0.05));
    std::array<std::vector<Observation>, 2> delivered;
    delivered[nearestSupernode(scenario.supernodes, {o.x, o.y})].push_back(o);
    std::array<std::vector<common::TrackHandoff>, 2> incoming;
    for (const auto& h : in_flight) incoming[h.to_supernode].push_back(h);
    in_flight.clear();
    INFO("tick " << t);
    std::size_t reported = 0;
    for (std::uint32_t j = 0; j < 2; ++j) {
      const auto out = trackers[j].step(t, delivered[j], incoming[j]);
      in_flight.insert(in_flight.end(), out.handoffs.begin(), out.handoffs.end());
      for (const auto& track : out.tracks) ids.insert(track.track);
      reported += out.tracks.size();
    }
    if (t >= 3) CHECK(reported == 1);  // one target, one track: never both supernodes at once
  }
  CHECK(ids.size() == 1);
}

TEST_CASE("mcmcda counts a handed-over track's misses from when its target was last seen", "[mcmcda]") {
  // Handed over at tick 4 after 3 ticks unseen and never observed again: the target was last seen
  // at tick 1, so with d-bar = 5 only reports generated up to tick 6 can continue the track. It
  // must not be reported as if it had been seen at tick 4, and it is gone once tick 6 has left
  // the window (ws = 10: from tick 16 on).
  auto tracker = test::trackerFor(mcmcdaScenario(), 0);
  common::TrackHandoff handoff;
  handoff.track = (std::uint64_t{3} << 48) | 5;
  handoff.to_supernode = 0;
  handoff.last_tick = 4;
  handoff.state = {40.0, 40.0, 1.0, 0.0};
  handoff.covariance = {0.3, 0, 0.1, 0, 0, 0.3, 0, 0.1, 0.1, 0, 0.1, 0, 0, 0.1, 0, 0.1};
  handoff.hits = 6;
  handoff.misses = 3;
  handoff.confirmed = true;
  for (std::int32_t t = 1; t <= 4; ++t) tracker.step(t, {}, {});
  const std::vector<common::TrackHandoff> incoming = {handoff};
  const auto& engine = static_cast<const McmcdaEngine&>(tracker.engine());
  for (std::int32_t t = 5; t <= 16; ++t) {
    const auto out = tracker.step(t, {}, t == 5 ? std::span(incoming) : std::span<const common::TrackHandoff>());
    INFO("tick " << out.tick);
    if (out.tick >= 6) CHECK(out.tracks.empty());  // unseen for 5 ticks with pd = 0.7: gone
    if (out.tick == 14) CHECK(engine.predictions().size() == 1);  // a late report of tick 6 could come
  }
  CHECK(engine.predictions().empty());
}

TEST_CASE("mcmcda refuses a non-finite handoff and the release of an unknown track", "[mcmcda]") {
  const auto scenario = mcmcdaScenario();
  McmcdaEngine engine(engineContext(scenario, 0));
  common::TrackHandoff handoff;
  handoff.track = (std::uint64_t{2} << 48) | 1;
  handoff.last_tick = 1;
  handoff.state = {10.0, std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};
  engine.adopt(handoff);
  CHECK(engine.rejectedHandoffs() == 1);
  CHECK(engine.predictions().empty());
  CHECK_THROWS_WITH(engine.release(handoff.track, 1), Catch::Contains("unknown track"));
}

TEST_CASE("mcmcda gives the same outputs on two runs of the same input", "[mcmcda]") {
  const std::vector<Target> targets = {{40, 40, 1.0, 0.5}, {40, 50, 1.0, -0.5}};
  const auto deliver = [&](std::int32_t t) {
    std::vector<Observation> obs;
    for (std::size_t k = 0; k < targets.size(); ++k)
      obs.push_back(observation(t, t, targets[k].x(t) + jitter(k, t, 0.3), targets[k].y(t) + jitter(k + 7, t, 0.3)));
    common::Stream clutter(5, common::Purpose::kSensorNoise, 1000, t);
    for (int c = 0; c < 3; ++c) obs.push_back(observation(t, t, clutter.uniform(30, 60), clutter.uniform(30, 60)));
    return obs;
  };
  CHECK(run(mcmcdaScenario(), 25, deliver) == run(mcmcdaScenario(), 25, deliver));
}

}  // namespace wsn::supernode::mcmcda

namespace wsn::supernode::mcmcda {

TEST_CASE("the settled stream covers a track from the tick it was born and smooths its velocity") {
  // One target from tick 1 at (40, 40) with v = (1, 0.5), observed every tick without noise. The
  // live estimate needs confirm_observations = 3 reports: nothing at ticks 1 and 2. Settled, each
  // tick as it leaves the 10-tick window is re-estimated with all of its track: tick 1 is covered,
  // and its velocity is the line's, where the filter's first state only has its prior (0).
  const Target target{40, 40, 1.0, 0.5};
  const auto scenario = mcmcdaScenario();
  auto tracker = test::trackerFor(scenario, 0);
  std::vector<SupernodeTracker::TickOutput> outputs;
  for (std::int32_t t = 1; t <= 20; ++t)
    outputs.push_back(tracker.step(t, std::vector<Observation>{observation(t, t, target.x(t), target.y(t), 0)}, {}));
  CHECK(outputs[0].tracks.empty());
  CHECK(outputs[1].tracks.empty());
  // Tick t - 9 settles at tick t: the first settled tick is 1, at tick 10.
  for (std::int32_t t = 1; t <= 9; ++t) CHECK(outputs[static_cast<std::size_t>(t - 1)].settled.by_tick.empty());
  const auto& first = outputs[9].settled;
  REQUIRE(first.first == 1);
  REQUIRE(first.by_tick.size() == 1);
  REQUIRE(first.by_tick[0].size() == 1);
  const auto& settled = first.by_tick[0][0];
  CHECK(settled.x == Approx(40.0).margin(0.05));
  CHECK(settled.y == Approx(40.0).margin(0.05));
  CHECK(settled.vx == Approx(1.0).margin(0.05));
  CHECK(settled.vy == Approx(0.5).margin(0.05));
  // The smoothed covariance is smaller than the filtered one at the same tick.
  const auto filtered = dynamic_cast<const McmcdaEngine&>(tracker.engine()).tracksAt(11);
  const auto revised = tracker.engine().revisedTracks(11);
  REQUIRE(filtered.size() == 1);
  REQUIRE(revised.has_value());
  REQUIRE(revised->size() == 1);
  CHECK((*revised)[0].covariance[0] < filtered[0].covariance[0]);
  CHECK((*revised)[0].covariance[10] < filtered[0].covariance[10]);  // vx variance
}

TEST_CASE("a missed report is bridged in the settled stream by smoothing across the gap") {
  // A straight target, reports with noise 0.2 (fixed draws) and none at tick 5. The filtered
  // estimate of tick 5 is tick 4's predicted, with its noisy velocity; the smoothed one also
  // uses the reports after the gap: it is closer to the target and surer (smaller variance).
  const Target target{40, 40, 1.0, 0.5};
  auto tracker = test::trackerFor(mcmcdaScenario(), 0);
  SupernodeTracker::Settled settled;
  for (std::int32_t t = 1; t <= 15; ++t) {
    std::vector<Observation> obs;
    if (t != 5)
      obs.push_back(observation(t, t, target.x(t) + jitter(1, t, 0.2), target.y(t) + jitter(2, t, 0.2), 0));
    auto out = tracker.step(t, obs, {});
    for (auto& tick_tracks : out.settled.by_tick) settled.by_tick.push_back(std::move(tick_tracks));
    if (t == 9) {  // the window still holds tick 5 and four ticks after it
      const auto filtered = dynamic_cast<const McmcdaEngine&>(tracker.engine()).tracksAt(5);
      const auto revised = tracker.engine().revisedTracks(5);
      REQUIRE(filtered.size() == 1);
      REQUIRE(revised.has_value());
      REQUIRE(revised->size() == 1);
      const double filtered_error = std::hypot(filtered[0].x - target.x(5), filtered[0].y - target.y(5));
      const double smoothed_error = std::hypot((*revised)[0].x - target.x(5), (*revised)[0].y - target.y(5));
      CHECK(smoothed_error < filtered_error);
      CHECK((*revised)[0].covariance[0] < 0.5 * filtered[0].covariance[0]);
    }
  }
  REQUIRE(settled.by_tick.size() >= 5);
  REQUIRE(settled.by_tick[4].size() == 1);  // tick 5 is in the settled stream despite the miss
}

}  // namespace wsn::supernode::mcmcda

namespace wsn::supernode::mcmcda {

TEST_CASE("confirmed at one report a lone newest report is a track at once and keeps its id") {
  // One target observed every tick from tick 1, and one stray report at tick 3 that nothing
  // continues. With confirm_observations = 1 the target is reported from tick 1 (at confirmation
  // 3 from tick 3), under one id throughout: its track of omega-hat at tick 2 takes the id of the
  // lone track of tick 1 by their shared report. The stray report is a track of its own from tick 3,
  // reported while its target is more likely there than gone: at pd 0.7 and pz 0.02, unseen for
  // m ticks it is alive with weight 0.98^m 0.3^m against ended sum_i 0.02 (0.98 x 0.3)^i:
  // 0.294 vs 0.020, 0.086 vs 0.026, 0.025 vs 0.028, so it is reported at ticks 3, 4 and 5, not 6.
  const Target target{40, 40, 1.0, 0.5};
  // Confirmation at one report goes with a scenario without clutter (the derivation's reason).
  common::Scenario scenario = mcmcdaScenario();
  scenario.tracker.params["confirm_observations"] = {1, 0};
  scenario.tracker.params["false_alarm_density"] = {1e-9, 0};
  scenario.tracker.params["detection_probability"] = {0.7, 0};
  scenario.tracker.params["termination_probability"] = {0.02, 0};
  resolveEngineParams(scenario, wsn::common::kNoStatistics);
  const auto outputs = run(scenario, 7, [&](std::int32_t t) {
    std::vector<Observation> obs{observation(t, t, target.x(t), target.y(t), 0)};
    if (t == 3) obs.push_back(observation(t, t, 10.0, 10.0, 1));
    return obs;
  });
  REQUIRE(outputs[0].tracks.size() == 1);
  CHECK(outputs[0].tracks[0].x == Approx(40.0));
  CHECK(outputs[0].tracks[0].vx == 0.0);  // one report: no velocity yet, the prior's mean
  const common::TrackId id = outputs[0].tracks[0].track;
  for (std::size_t k : {1u, 5u, 6u}) {
    INFO("tick " << k + 1);
    REQUIRE(outputs[k].tracks.size() == 1);
    CHECK(outputs[k].tracks[0].track == id);
  }
  common::TrackId stray = 0;
  for (std::size_t k : {2u, 3u, 4u}) {
    INFO("tick " << k + 1);
    REQUIRE(outputs[k].tracks.size() == 2);
    for (const auto& track : outputs[k].tracks)
      if (track.track != id) {
        CHECK(track.x == Approx(10.0));
        CHECK((stray == 0 || stray == track.track));
        stray = track.track;
      }
  }
  CHECK(stray != 0);

  const auto waited = run(mcmcdaScenario(), 3, [&](std::int32_t t) {
    return std::vector<Observation>{observation(t, t, target.x(t), target.y(t), 0)};
  });
  CHECK(waited[0].tracks.empty());
  CHECK(waited[1].tracks.empty());
  CHECK(waited[2].tracks.size() == 1);
}

}  // namespace wsn::supernode::mcmcda

namespace wsn::supernode::mcmcda {

TEST_CASE("a newborn track is not handed over until its second report makes it a track") {
  // Confirmation at one report without clutter: after tick 1 the target is a one-report newborn,
  // reported but not offered to a neighbour (predictions() lists what a supernode may hand over);
  // after tick 2 it is a track of omega-hat and is offered.
  common::Scenario scenario = mcmcdaScenario();
  scenario.tracker.params["confirm_observations"] = {1, 0};
  scenario.tracker.params["false_alarm_density"] = {1e-9, 0};
  resolveEngineParams(scenario, wsn::common::kNoStatistics);
  auto tracker = test::trackerFor(scenario, 0);
  const auto first = tracker.step(1, std::vector<Observation>{observation(1, 1, 40.0, 40.0, 0)}, {});
  REQUIRE(first.tracks.size() == 1);
  CHECK(tracker.engine().predictions().empty());
  const auto second = tracker.step(2, std::vector<Observation>{observation(2, 2, 41.0, 40.5, 0)}, {});
  REQUIRE(second.tracks.size() == 1);
  const auto offered = tracker.engine().predictions();
  REQUIRE(offered.size() == 1);
  CHECK(offered[0].track == second.tracks[0].track);
}

}  // namespace wsn::supernode::mcmcda

namespace wsn::supernode::mcmcda {

TEST_CASE("a track of one report outlives the window its report leaves and a later report continues it") {
  // Heavy loss: pd 0.1, confirmation at one report, a window of 4 ticks and max_gap 8. The target is
  // reported once at tick 1 and next at tick 7, six ticks on: its report left the window at tick 5,
  // and the track goes on from it as an anchor, reported all along (alive 0.882^m against ended
  // 0.02 (1 - 0.882^m) / 0.118 while m <= 15), and tick 7's report continues it under its id.
  const Target target{40, 40, 1.0, 0.5};
  const common::Scenario scenario = heavyLossScenario();
  const auto outputs = run(scenario, 8, [&](std::int32_t t) {
    std::vector<Observation> obs;
    if (t == 1 || t == 7) obs.push_back(observation(t, t, target.x(t), target.y(t), 0));
    return obs;
  });
  REQUIRE(outputs[0].tracks.size() == 1);
  const common::TrackId id = outputs[0].tracks[0].track;
  for (std::size_t k = 1; k < outputs.size(); ++k) {
    INFO("tick " << k + 1);
    REQUIRE(outputs[k].tracks.size() == 1);
    CHECK(outputs[k].tracks[0].track == id);
  }
  // Tick 7's report joined the anchored track: its velocity is now learnt from the two reports.
  CHECK(outputs[6].tracks[0].vx == Approx(1.0).margin(0.2));
  CHECK(outputs[6].tracks[0].last_seen_tick == 7);
}

TEST_CASE("an unseen track coasts where no sensor looks and ends where its sensor would have seen it") {
  // Heavy loss on average (pd 0.1, confirmation at one report, window 4, max_gap 8), but the field's
  // sensors are known: one disc of radius 5 at (20, 20) with PD 0.9 covers 0.7 % of the region, so
  // there a target is seen at pd 0.1 x 0.9 / 0.00707 > 1, capped at 1, and nowhere else at all. Two
  // targets at rest, reported at ticks 1 to 3 and then silent: the one in the disc would have been
  // seen at tick 4, so its track ends there; the one outside coasts while a report could still
  // continue it (through tick 13: tick 3 + max_gap 8 leaves the window that tick 14 opens), as both
  // do when the coverage is not known.
  const common::Scenario scenario = heavyLossScenario();
  const auto deliver = [](std::int32_t t) {
    std::vector<Observation> obs;
    if (t <= 3) obs = {observation(t, t, 20.0, 20.0, 0), observation(t, t, 70.0, 70.0, 1)};
    return obs;
  };
  const auto reported = [](const SupernodeTracker::TickOutput& out, double x) {
    return std::ranges::count_if(out.tracks, [&](const common::TrackEstimate& e) { return std::abs(e.x - x) < 1.0; });
  };
  EngineContext context = engineContext(scenario, 0);
  SupernodeTracker without_coverage(SupernodeConfig{context, scenario.supernodes});
  common::SensorCoverage disc{0, {20.0, 20.0}, 0.0, 2 * std::numbers::pi, 5.0, 0.9, common::SightBlockers::none};
  context.coverage = {disc};
  context.coverage_region_mean = common::meanSensedProbability(context.coverage, context.region, nullptr);
  REQUIRE(context.coverage_region_mean == Approx(std::numbers::pi * 25.0 / 1e4 * 0.9).epsilon(0.02));
  SupernodeTracker with_coverage(SupernodeConfig{context, scenario.supernodes});
  for (std::int32_t t = 1; t <= 16; ++t) {
    INFO("tick " << t);
    const auto plain = without_coverage.step(t, deliver(t), {});
    const auto covered = with_coverage.step(t, deliver(t), {});
    const std::int32_t coasting = t <= 13 ? 1 : 0;
    CHECK(reported(plain, 20.0) == coasting);
    CHECK(reported(plain, 70.0) == coasting);
    CHECK(reported(covered, 20.0) == (t <= 3 ? 1 : 0));
    CHECK(reported(covered, 70.0) == coasting);
  }
}

}  // namespace wsn::supernode::mcmcda

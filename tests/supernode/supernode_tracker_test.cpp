#include "supernode/supernode_tracker.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/rng.hpp"
#include "supernode/gnn/gnn_engine.hpp"
#include "tests/supernode/test_support.hpp"

namespace wsn::supernode {
namespace {

using test::observation;
using test::sensorAt;

TEST_CASE("the nearest supernode decides the tracking group, ties going to the lower index", "[tracker]") {
  const std::vector<common::Vec2> supernodes = {{0.0, 0.0}, {10.0, 0.0}};
  CHECK(nearestSupernode(supernodes, {4.9, 3.0}) == 0);
  CHECK(nearestSupernode(supernodes, {5.0, 3.0}) == 0);  // equidistant
  CHECK(nearestSupernode(supernodes, {5.1, -3.0}) == 1);
  CHECK(nearestSupernode({}, {5.1, -3.0}) == 0);
}

TEST_CASE("a supernode index outside the scenario is rejected", "[tracker]") {
  auto s = test::gnnScenario();  // one supernode
  CHECK_THROWS_AS(test::trackerFor(s, 1), std::invalid_argument);
  s.tracker.engine = "nope";
  CHECK_THROWS_AS(test::trackerFor(s, 0), common::ScenarioError);  // resolving names the file
  // A config built without resolving (a bug, not a user error) fails in the tracker itself.
  auto config = supernodeConfig(test::gnnScenario(), 0);
  config.engine.engine = "nope";
  CHECK_THROWS_AS(SupernodeTracker(config), std::invalid_argument);
  config = supernodeConfig(test::gnnScenario(), 0);
  config.engine.params.erase("gate_chi2");
  CHECK_THROWS_AS(SupernodeTracker(config), std::logic_error);  // an unresolved parameter
}

/// Two supernodes with the Voronoi boundary at x = 50.
common::Scenario twoSupernodes() {
  auto s = test::gnnScenario();
  s.supernodes = {{25.0, 50.0}, {75.0, 50.0}};
  return s;
}

/// Runs two trackers that exchange handoffs in memory: observations go to the supernode of their
/// position, a handoff released at tick t is adopted at tick t + 1.
struct Pair {
  explicit Pair(const common::Scenario& s) : scenario(s), trackers{test::trackerFor(s, 0), test::trackerFor(s, 1)} {}
  std::array<SupernodeTracker::TickOutput, 2> step(std::int32_t tick, const std::vector<common::Observation>& all) {
    std::array<std::vector<common::Observation>, 2> delivered;
    for (const auto& o : all) delivered[nearestSupernode(scenario.supernodes, {o.x, o.y})].push_back(o);
    std::array<std::vector<common::TrackHandoff>, 2> incoming;
    for (const auto& h : in_flight) incoming[h.to_supernode].push_back(h);
    std::array<SupernodeTracker::TickOutput, 2> out{trackers[0].step(tick, delivered[0], incoming[0]),
                                                    trackers[1].step(tick, delivered[1], incoming[1])};
    in_flight.clear();
    for (const auto& o : out) in_flight.insert(in_flight.end(), o.handoffs.begin(), o.handoffs.end());
    return out;
  }
  common::Scenario scenario;
  std::array<SupernodeTracker, 2> trackers;
  std::vector<common::TrackHandoff> in_flight;
};

TEST_CASE("a target crossing into the next tracking group continues there under the same id", "[tracker]") {
  Pair pair(twoSupernodes());
  // x = 40.5 + t: the prediction for tick 10 (x = 50.5) is the first beyond the boundary x = 50,
  // so supernode 0 releases the track at tick 9 and supernode 1 adopts it at tick 10.
  auto truth = [](std::int32_t t) { return common::Vec2{40.5 + t, 50.0 + 0.2 * t}; };
  const common::TrackId id = common::track_id::birth(0, 1, sensorAt(truth(1).x, truth(1).y));
  for (std::int32_t t = 1; t <= 25; ++t) {
    const auto p = truth(t);
    const auto out = pair.step(t, {observation(t, t, p.x, p.y)});
    INFO("tick " << t);
    CHECK(out[0].tick == t);
    CHECK(out[1].handoffs.empty());  // never handed back
    if (t < 3) continue;
    if (t <= 9) {
      REQUIRE(out[0].tracks.size() == 1);
      CHECK(out[0].tracks[0].track == id);
      CHECK(out[1].tracks.empty());
    } else {
      CHECK(out[0].tracks.empty());
      REQUIRE(out[1].tracks.size() == 1);
      CHECK(out[1].tracks[0].track == id);
      CHECK(std::hypot(out[1].tracks[0].x - p.x, out[1].tracks[0].y - p.y) < 0.1);
    }
    if (t == 9) {
      REQUIRE(out[0].handoffs.size() == 1);
      const auto& h = out[0].handoffs[0];
      CHECK(h.track == id);
      CHECK(h.to_supernode == 1);
      CHECK(h.last_tick == 9);
      CHECK(h.hits == 9);
      CHECK(h.confirmed);
    } else {
      CHECK(out[0].handoffs.empty());
    }
  }
}

/// Two targets, clutter and delays of 0-2 ticks, all from fixed streams.
std::vector<std::vector<common::Observation>> busyDeliveries(std::int32_t ticks) {
  std::vector<std::vector<common::Observation>> by_delivery(static_cast<std::size_t>(ticks) + 3);
  for (std::int32_t t = 1; t <= ticks; ++t) {
    common::Stream s(5, common::Purpose::kNetworkDelay, 0, t);
    std::vector<common::Observation> generated = {
        observation(t, t, 30.0 + 1.5 * t + 0.3 * s.normal(), 40.0 + 0.4 * t + 0.3 * s.normal(), 0),
        observation(t, t, 70.0 - 1.2 * t + 0.3 * s.normal(), 60.0 - 0.3 * t + 0.3 * s.normal(), 1)};
    for (int k = 0; k < 4; ++k) generated.push_back(observation(t, t, s.uniform(0, 100), s.uniform(0, 100), -1));
    for (auto& o : generated) {
      o.tick_delivered = t + static_cast<std::int32_t>(s.below(3));
      by_delivery[static_cast<std::size_t>(o.tick_delivered)].push_back(o);
    }
  }
  return by_delivery;
}

std::vector<std::array<SupernodeTracker::TickOutput, 2>> runBusy(bool reverse_arrival) {
  Pair pair(twoSupernodes());
  const auto deliveries = busyDeliveries(40);
  std::vector<std::array<SupernodeTracker::TickOutput, 2>> outputs;
  for (std::int32_t t = 1; t <= 40; ++t) {
    auto batch = deliveries[static_cast<std::size_t>(t)];
    if (reverse_arrival) std::reverse(batch.begin(), batch.end());
    outputs.push_back(pair.step(t, batch));
  }
  return outputs;
}

TEST_CASE("two runs on the same inputs are identical, whatever the arrival order", "[tracker]") {
  const auto first = runBusy(false);
  const auto second = runBusy(false);
  const auto reversed = runBusy(true);
  CHECK(first == second);
  CHECK(first == reversed);
  // The run did something: tracks were confirmed and handed over, and the window held data.
  std::size_t confirmed = 0;
  std::size_t handoffs = 0;
  for (const auto& tick : first)
    for (const auto& o : tick) {
      confirmed += o.tracks.size();
      handoffs += o.handoffs.size();
    }
  CHECK(confirmed > 40);
  CHECK(handoffs >= 1);
  CHECK(first.back()[0].observations_in_window + first.back()[1].observations_in_window > 0);
}

TEST_CASE("the tick output reports the window's contents and the stale drops", "[tracker]") {
  auto tracker = test::trackerFor(test::gnnScenario(3), 0);
  tracker.step(1, std::vector{observation(1, 1, 10.0, 10.0)}, {});
  const auto out = tracker.step(5, std::vector{observation(1, 5, 10.0, 10.0), observation(4, 5, 12.0, 10.0),
                                               observation(5, 5, 13.0, 10.0)},
                                {});
  CHECK(out.tick == 5);
  CHECK(out.observations_in_window == 2);      // ticks 3-5 hold the ones of ticks 4 and 5
  CHECK(out.observations_dropped_stale == 1);  // tick 1 left the window
}

TEST_CASE("a handoff addressed to another supernode is ignored and counted", "[tracker]") {
  auto tracker = test::trackerFor(twoSupernodes(), 0);
  common::TrackHandoff h;
  h.track = common::track_id::birth(1, 1, 1);
  h.to_supernode = 1;
  h.last_tick = 1;
  h.confirmed = true;
  for (int i = 0; i < 4; ++i) h.covariance[static_cast<std::size_t>(i * 5)] = 1.0;
  const auto out = tracker.step(2, {}, std::vector{h});
  CHECK(out.tracks.empty());
  CHECK(tracker.misaddressedHandoffs() == 1);
}

TEST_CASE("a track that leaps past the neighbouring groups goes one group nearer per tick", "[tracker]") {
  // Five groups in a row: each borders only the next ones, so supernode 0 can hand to 1 alone.
  auto s = test::gnnScenario();
  s.supernodes = {{10.0, 50.0}, {30.0, 50.0}, {50.0, 50.0}, {70.0, 50.0}, {90.0, 50.0}};
  auto first = test::trackerFor(s, 0);
  CHECK(first.neighbours() == std::vector<std::uint32_t>{1});
  CHECK(test::trackerFor(s, 2).neighbours() == std::vector<std::uint32_t>{1, 3});
  // A confirmed track at x = 15 moving 30 a tick: its next positions lie two and more groups on.
  common::TrackHandoff h;
  h.track = common::track_id::birth(0, 1, 1);
  h.to_supernode = 0;
  h.last_tick = 1;
  h.state = {15.0, 50.0, 30.0, 0.0};
  h.hits = 5;
  h.confirmed = true;
  for (int i = 0; i < 4; ++i) h.covariance[static_cast<std::size_t>(i * 5)] = 0.01;
  std::uint32_t holder = 0;
  auto tracker = std::move(first);
  // Two hops (the coasting track then runs out of misses).
  for (std::int32_t t = 2; t <= 3; ++t) {
    INFO("tick " << t << ", held by supernode " << holder);
    const auto out = tracker.step(t, {}, std::vector{h});
    REQUIRE(out.handoffs.size() == 1);
    const auto& next = out.handoffs[0];
    const common::Vec2 predicted{next.state[0] + next.state[2], next.state[1] + next.state[3]};
    // The nearest supernode of all is further on than a neighbour: the track goes to the neighbour
    // nearest to it, the next group on.
    CHECK(nearestSupernode(s.supernodes, predicted) > holder + 1);
    CHECK(next.to_supernode == holder + 1);
    holder = next.to_supernode;
    h = next;
    tracker = test::trackerFor(s, holder);
  }
}

}  // namespace
}  // namespace wsn::supernode

namespace wsn::supernode {
namespace {

TEST_CASE("every position engine handed a bearing observation fails naming itself and the kind", "[tracker]") {
  common::Measurement measured;
  measured.kind = common::MeasurementKind::bearing;
  measured.values = {0.4};
  measured.sensor = common::SensorPose{20.0, 30.0, 0.0};
  REQUIRE(common::wellFormed(measured));  // well formed, only of the wrong kind
  common::Observation bearing{3, 3, test::sensorAt(20.0, 30.0), 20.0, 30.0, 0, 0, common::MeasurementRef(measured)};

  for (const char* engine : {"gnn", "mcmcda", "rulebased"}) {
    INFO(engine);
    auto s = test::gnnScenario();
    s.tracker.engine = engine;
    s.tracker.params.clear();
    resolveEngineParams(s, wsn::common::kNoStatistics);
    auto tracker = test::trackerFor(s, 0);
    const std::vector<common::Observation> position{test::observation(2, 2, 20.0, 30.0)};
    tracker.step(2, position, {});  // what it declared in `accepts` goes through
    const std::vector<common::Observation> delivered{bearing};
    CHECK_THROWS_AS(tracker.step(3, delivered, {}), std::logic_error);
    CHECK_THROWS_WITH(tracker.step(4, delivered, {}), Catch::Contains("engine '" + std::string(engine) + "'") &&
                                                          Catch::Contains("kind 'bearing'") &&
                                                          Catch::Contains("accepts only: position"));
  }
}

TEST_CASE("sbmht handed a presence observation fails naming itself and the kind", "[tracker]") {
  // sbmht takes positions, bearings, radar plots and camera angles, but a presence has no h(x).
  common::Measurement presence;
  presence.kind = common::MeasurementKind::presence;
  presence.sensor = common::SensorPose{20.0, 30.0, 0.0};
  REQUIRE(common::wellFormed(presence));
  const std::vector<common::Observation> delivered{
      common::Observation{3, 3, test::sensorAt(20.0, 30.0), 20.0, 30.0, 0, 0, common::MeasurementRef(presence)}};
  auto s = test::gnnScenario();
  s.tracker.engine = "sbmht";
  s.tracker.params.clear();
  resolveEngineParams(s, wsn::common::kNoStatistics);
  auto tracker = test::trackerFor(s, 0);
  CHECK_THROWS_WITH(tracker.step(3, delivered, {}),
                    Catch::Contains("engine 'sbmht'") && Catch::Contains("kind 'presence'") &&
                        Catch::Contains("accepts only: position, bearing, range_bearing_rate, azimuth_elevation"));
}

}  // namespace
}  // namespace wsn::supernode

namespace wsn::supernode {

TEST_CASE("every tick of a run is settled once and in order, and GNN's settled tracks are its live ones") {
  // GNN does not revise the past: the settled estimate of a tick is what it reported live then.
  auto tracker = test::trackerFor(test::gnnScenario(4), 0);
  std::vector<std::vector<common::TrackEstimate>> live;
  std::vector<std::vector<common::TrackEstimate>> settled;
  std::int32_t next = 1;
  const auto collect = [&](const SupernodeTracker::Settled& s) {
    if (s.by_tick.empty()) return;
    CHECK(s.first == next);
    for (const auto& tracks : s.by_tick) settled.push_back(tracks);
    next = s.last() + 1;
  };
  for (std::int32_t t = 1; t <= 12; ++t) {
    const double x = 20.0 + t;
    const auto out = tracker.step(t, std::vector<common::Observation>{test::observation(t, t, x, 30.0)}, {});
    // With ws = 4, tick t - 3 leaves the window at t.
    if (t >= 4) {
      CHECK(out.settled.first == t - 3);
      CHECK(out.settled.by_tick.size() == 1);
    } else {
      CHECK(out.settled.by_tick.empty());
    }
    live.push_back(out.tracks);
    collect(out.settled);
  }
  const auto rest = tracker.settleRemaining();
  CHECK(rest.first == 10);
  CHECK(rest.last() == 12);
  collect(rest);
  REQUIRE(settled.size() == 12);
  CHECK(settled == live);
  CHECK(tracker.settleRemaining().by_tick.empty());  // nothing is settled twice
}

}  // namespace wsn::supernode

// The sbmht engine with the sensors' coverage (ONERA eq. 15): one scan per sensor, a miss weighed by
// whether the sensor could have seen the target, masks that make a silent sensor no evidence.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <set>
#include <vector>

#include "common/sensor_coverage.hpp"
#include "common/terrain.hpp"
#include "common/track_id.hpp"
#include "supernode/sbmht/sbmht_engine.hpp"
#include "tests/supernode/sbmht/sbmht_test_support.hpp"

namespace wsn::supernode::sbmht {
namespace {

using namespace support;
using common::SensorCoverage;
using common::SightBlockers;
using common::Vec2;

constexpr double kAllRound = 2.0 * std::numbers::pi;

/// A position report of sensor `sensor` (at `at`) placing the target exactly at p, R = I.
common::Observation fix(std::int32_t t, common::SensorId sensor, Vec2 at, Vec2 p) {
  return sensed(t, sensor, {at.x, at.y, 0.0, 0.0}, common::MeasurementKind::position, p, {0.0, 0.0}, {1.0, 1.0}, 1e-4);
}

TEST_CASE("sbmht fuses two sensors that report one target each tick into one track", "[sbmht]") {
  // Two all-round sensors of PD 0.9 both place the target every tick. Each sensor is a scan, so the
  // tree that took the first sensor's report takes the second's too, and the second sensor's birth
  // loses to it: one track, both reports a tick.
  const Vec2 a{10, 10};
  const Vec2 b{90, 10};
  Harness h(sbmhtScenario(), [&](EngineContext& c) {
    c.coverage = {SensorCoverage{1, a, 0.0, kAllRound, 200.0, 0.9, SightBlockers::none},
                  SensorCoverage{2, b, 0.0, kAllRound, 200.0, 0.9, SightBlockers::none}};
  });
  auto truth = [](std::int32_t t) { return Vec2{20.0 + t, 40.0}; };
  std::set<common::TrackId> ids;
  for (std::int32_t t = 1; t <= 25; ++t) {
    h.step(t, {fix(t, 1, a, truth(t)), fix(t, 2, b, truth(t))});
    for (const auto& track : h.engine.confirmedTracks()) ids.insert(track.track);
  }
  REQUIRE(ids.size() == 1);
  const auto* leaf = bestLeaf(h.engine, *ids.begin());
  REQUIRE(leaf != nullptr);
  for (std::int32_t t = 5; t <= 25; ++t) CHECK(leaf->reportsAt(t).size() == 2);
}

TEST_CASE("sbmht starts a track where two antennas' bearings cross and follows it on bearings alone", "[sbmht]") {
  // Two all-round acoustic antennas (3 deg, 0.01 false bearings a tick) hear one walker; no sensor
  // places it. A bearing alone starts nothing, but two that no track took start a tree at their
  // crossing (ONERA §II-C): one track, under one id, fed both bearings every tick. Without the
  // pair births the field has no track at all.
  const Vec2 a{10, 10};
  const Vec2 b{90, 10};
  const common::SensorPose pose_a{a.x, a.y, 0.0, 0.0};
  const common::SensorPose pose_b{b.x, b.y, 0.0, 0.0};
  const double clutter = 0.01 / (2.0 * std::numbers::pi);
  auto truth = [](std::int32_t t) { return Vec2{20.0 + t, 50.0}; };
  for (const int pair_births : {1, 0}) {
    Harness h(sbmhtScenario({{"bearing_pair_births", pair_births}}), [&](EngineContext& c) {
      c.coverage = {SensorCoverage{1, a, 0.0, kAllRound, 200.0, 0.9, SightBlockers::none},
                    SensorCoverage{2, b, 0.0, kAllRound, 200.0, 0.9, SightBlockers::none}};
    });
    std::set<common::TrackId> ids;
    for (std::int32_t t = 1; t <= 20; ++t) {
      h.step(t, {sensed(t, 1, pose_a, common::MeasurementKind::bearing, truth(t), {1.0, 0.0},
                        {9.0 * kDegree * kDegree}, clutter),
                 sensed(t, 2, pose_b, common::MeasurementKind::bearing, truth(t), {1.0, 0.0},
                        {9.0 * kDegree * kDegree}, clutter)});
      for (const auto& track : h.engine.confirmedTracks()) ids.insert(track.track);
    }
    INFO("bearing_pair_births " << pair_births);
    if (pair_births == 0) {
      CHECK(h.engine.leaves().empty());
      continue;
    }
    REQUIRE(ids.size() == 1);
    // Born at tick 1 after sensor 2's scan, the first pair birth named after it.
    CHECK(*ids.begin() == common::track_id::birth(0, 1, 2, 0));
    const auto tracks = h.engine.confirmedTracks();
    REQUIRE(tracks.size() == 1);
    // Noise-free bearings: the fix is exact and the track follows the walker closely.
    CHECK(distance(tracks[0], truth(20)) < 1.0);
    const auto* leaf = bestLeaf(h.engine, tracks[0].track);
    REQUIRE(leaf != nullptr);
    for (std::int32_t t = 1; t <= 20; ++t) CHECK(leaf->reportsAt(t).size() == 2);
  }
}

TEST_CASE("sbmht starts no pair tree where one antenna cannot see the crossing", "[sbmht]") {
  // The same walker, but antenna 2 reaches only 30 m: its bearing is the walker's false alarm as far
  // as the rays go (they cross about 70 m from it), so the pair starts nothing.
  const Vec2 a{10, 10};
  const Vec2 b{90, 10};
  const double clutter = 0.01 / (2.0 * std::numbers::pi);
  Harness h(sbmhtScenario(), [&](EngineContext& c) {
    c.coverage = {SensorCoverage{1, a, 0.0, kAllRound, 200.0, 0.9, SightBlockers::none},
                  SensorCoverage{2, b, 0.0, kAllRound, 30.0, 0.9, SightBlockers::none}};
  });
  for (std::int32_t t = 1; t <= 5; ++t)
    h.step(t, {sensed(t, 1, {a.x, a.y, 0.0, 0.0}, common::MeasurementKind::bearing, {20.0 + t, 50.0}, {1.0, 0.0},
                      {9.0 * kDegree * kDegree}, clutter),
               sensed(t, 2, {b.x, b.y, 0.0, 0.0}, common::MeasurementKind::bearing, {20.0 + t, 50.0}, {1.0, 0.0},
                      {9.0 * kDegree * kDegree}, clutter)});
  CHECK(h.engine.leaves().empty());
}

/// One camera-like sensor at (50, -50) sees the whole region but for what a building at
/// [40, 60] x [-30, -20] hides: along y = 10 the target is hidden for x in about [26, 74]
/// (the line to it crosses y = -25 within the building when |x - 50| <= 24).
struct HiddenPass {
  static constexpr common::SensorId kSensor = 1;
  static constexpr Vec2 kAt{50.0, -50.0};
  static Vec2 truth(std::int32_t t) { return {2.0 * t, 10.0}; }
  static common::TerrainConfig building() {
    common::TerrainConfig c;
    c.masks.push_back({"house", common::MaskKind::kBuilding, {{40, -30}, {60, -30}, {60, -20}, {40, -20}}});
    return c;
  }
  static bool hidden(std::int32_t t) { return std::abs(truth(t).x - 50.0) <= 24.0; }
};

TEST_CASE("sbmht coasts a masked target at no cost and keeps its id, without stopping it (C2)", "[sbmht]") {
  // 25 ticks behind the building. The estimate lags when it comes out (mixing with the stop model,
  // whose probability drifts towards its stationary share, slows the moving models: 12 m behind
  // at tick 38), but the report is inside the grown gate, and a report proves the target was in
  // sight whatever Pe the lagging prediction has.
  const auto terrain = std::make_shared<const common::Terrain>(HiddenPass::building());
  Harness h(sbmhtScenario(), [&](EngineContext& c) {
    c.coverage = {SensorCoverage{HiddenPass::kSensor, HiddenPass::kAt, 0.0, kAllRound, 500.0, 0.95,
                                 SightBlockers::buildings_and_vegetation}};
    c.terrain = terrain;
  });
  common::TrackId id = 0;
  double score_when_hidden = 0.0;
  for (std::int32_t t = 1; t <= 48; ++t) {
    const Vec2 p = HiddenPass::truth(t);
    if (HiddenPass::hidden(t))
      h.step(t);
    else
      h.step(t, {fix(t, HiddenPass::kSensor, HiddenPass::kAt, p)});
    const auto tracks = h.engine.confirmedTracks();
    INFO("tick " << t);
    if (t == 10) {
      REQUIRE(tracks.size() == 1);
      id = tracks[0].track;
    }
    if (t < 10) continue;
    REQUIRE(tracks.size() == 1);
    CHECK(tracks[0].track == id);
    const auto* leaf = bestLeaf(h.engine, id);
    REQUIRE(leaf != nullptr);
    // Deep behind the building every model's prediction is hidden: Pe = 0, the miss costs nothing
    // (Lambda = 1, eq. 14) and mu only follows Pi, towards its stationary mix, never to the stop model.
    if (HiddenPass::hidden(t) && HiddenPass::hidden(t - 3)) {
      if (score_when_hidden == 0.0) score_when_hidden = leaf->score.score;
      CHECK(leaf->score.score == score_when_hidden);
      CHECK(leaf->imm.probabilities(0) < 0.5);
    }
  }
  CHECK(score_when_hidden != 0.0);
  CHECK(distance(h.engine.confirmedTracks().at(0), HiddenPass::truth(48)) < 1.0);
}

TEST_CASE("sbmht counts the same silence as misses where no mask hides the target", "[sbmht]") {
  // The same reports on open ground: the sensor saw the place and said nothing, 25 ticks running,
  // which no moving target explains. The track is not carried across under its id.
  Harness h(sbmhtScenario(), [&](EngineContext& c) {
    c.coverage = {SensorCoverage{HiddenPass::kSensor, HiddenPass::kAt, 0.0, kAllRound, 500.0, 0.95,
                                 SightBlockers::buildings_and_vegetation}};
  });
  std::set<common::TrackId> ids;
  for (std::int32_t t = 1; t <= 48; ++t) {
    if (HiddenPass::hidden(t))
      h.step(t);
    else
      h.step(t, {fix(t, HiddenPass::kSensor, HiddenPass::kAt, HiddenPass::truth(t))});
    for (const auto& track : h.engine.confirmedTracks()) ids.insert(track.track);
  }
  CHECK(ids.size() == 2);
}

TEST_CASE("sbmht keeps a stopped target's track through a silent minute and moves on with it (S1)", "[sbmht]") {
  // Moves 20 ticks along y = 50, stands at (40, 50) for 60 ticks (the sensor hears nothing of a
  // target below its minimum speed), then moves on. With the derived Pi (tau 20 / 30 / 10 ticks) and
  // PD 0.95, two misses take mu_stop from 0 to about 0.92 (cbar_0 = 0.016 mu_slow + 0.048 mu_fast,
  // then mu_0 = cbar_0 / (cbar_0 + 0.05 (1 - cbar_0))), above 0.9 within the 3 scans S1 allows.
  const Vec2 at{50, 0};
  Harness h(sbmhtScenario(), [&](EngineContext& c) {
    c.coverage = {SensorCoverage{1, at, 0.0, kAllRound, 500.0, 0.95, SightBlockers::none}};
  });
  auto truth = [](std::int32_t t) {
    if (t <= 20) return Vec2{20.0 + t, 50.0};
    if (t <= 80) return Vec2{40.0, 50.0};
    return Vec2{40.0 + (t - 80), 50.0};
  };
  common::TrackId id = 0;
  for (std::int32_t t = 1; t <= 95; ++t) {
    const bool stopped = t > 20 && t <= 80;
    if (stopped)
      h.step(t);
    else
      h.step(t, {fix(t, 1, at, truth(t))});
    const auto tracks = h.engine.confirmedTracks();
    INFO("tick " << t);
    if (t == 15) {
      REQUIRE(tracks.size() == 1);
      id = tracks[0].track;
    }
    if (t < 15) continue;
    REQUIRE(tracks.size() == 1);
    CHECK(tracks[0].track == id);
    const auto* leaf = bestLeaf(h.engine, id);
    REQUIRE(leaf != nullptr);
    if (t >= 23 && stopped) CHECK(leaf->imm.probabilities(0) > 0.9);
    if (t >= 82) CHECK(leaf->imm.probabilities(0) < 0.1);
  }
  CHECK(distance(h.engine.confirmedTracks().at(0), truth(95)) < 1.0);
}

TEST_CASE("sbmht lets a sensor that cannot see the track leave its score alone", "[sbmht]") {
  // Sensor 1 places the target every tick; sensor 2 looks the other way (a 90 deg sector facing -x
  // from (0, 50)) and is silent. Adding sensor 2 to the coverage changes nothing; turning it to
  // face the target makes its silence a miss each tick.
  const Vec2 a{50, 0};
  auto run = [&](double heading) {
    Harness h(sbmhtScenario(), [&](EngineContext& c) {
      c.coverage = {SensorCoverage{1, a, 0.0, kAllRound, 500.0, 0.9, SightBlockers::none},
                    SensorCoverage{2, {0, 50}, heading, std::numbers::pi / 2, 500.0, 0.9, SightBlockers::none}};
    });
    for (std::int32_t t = 1; t <= 12; ++t) h.step(t, {fix(t, 1, a, {30.0 + t, 50.0})});
    const auto tracks = h.engine.confirmedTracks();
    REQUIRE(tracks.size() == 1);
    return bestLeaf(h.engine, tracks[0].track)->score.score;
  };
  Harness alone(sbmhtScenario(), [&](EngineContext& c) {
    c.coverage = {SensorCoverage{1, a, 0.0, kAllRound, 500.0, 0.9, SightBlockers::none}};
  });
  for (std::int32_t t = 1; t <= 12; ++t) alone.step(t, {fix(t, 1, a, {30.0 + t, 50.0})});
  const double single = bestLeaf(alone.engine, alone.engine.confirmedTracks().at(0).track)->score.score;
  CHECK(run(std::numbers::pi) == single);  // facing away
  CHECK(run(0.0) < single - 5.0);          // facing the target: about ln 0.1 a tick
}

TEST_CASE("sbmht starts no tree from a presence sensor but lets it update one", "[sbmht]") {
  // Sensor 1 is a presence sensor (a beacon): its report of the target starts nothing. Sensor 2
  // places the target from tick 6 on and starts its track; from then on the beacon's reports are
  // taken by that track as well (two reports a tick in its best leaf).
  const Vec2 beacon{30, 50};
  const Vec2 other{90, 10};
  Harness h(sbmhtScenario(), [&](EngineContext& c) {
    SensorCoverage presence{1, beacon, 0.0, kAllRound, 60.0, 0.9, SightBlockers::none};
    presence.presence = true;
    c.coverage = {presence, SensorCoverage{2, other, 0.0, kAllRound, 200.0, 0.9, SightBlockers::none}};
  });
  auto truth = [](std::int32_t t) { return Vec2{20.0 + t, 50.0}; };
  for (std::int32_t t = 1; t <= 5; ++t) {
    h.step(t, {fix(t, 1, beacon, truth(t))});
    CHECK(h.engine.leaves().empty());
  }
  for (std::int32_t t = 6; t <= 15; ++t) h.step(t, {fix(t, 1, beacon, truth(t)), fix(t, 2, other, truth(t))});
  const auto tracks = h.engine.confirmedTracks();
  REQUIRE(tracks.size() == 1);
  CHECK(tracks[0].track == common::track_id::birth(0, 6, 2));
  const auto* leaf = bestLeaf(h.engine, tracks[0].track);
  REQUIRE(leaf != nullptr);
  CHECK(leaf->reportsAt(15).size() == 2);
}

TEST_CASE("sbmht ends a track no sensor could see after max_coast_ticks", "[sbmht]") {
  // One sensor covers a disc of radius 45 about (10, 50). The target runs east at 2 a tick from
  // x = 12, 2t from the sensor: reported through tick 22 (44 <= 45), out of range from tick 23.
  // The moving models' predictions follow it out (the stop model's lags, but its silence is no
  // evidence), so ticks 23-32 are 10 unseen ticks: with max_coast_ticks = 10 the track is present
  // through tick 31 and gone from tick 32, though the target is still in the region.
  Harness h(sbmhtScenario({{"max_coast_ticks", 10}}), [&](EngineContext& c) {
    c.coverage = {SensorCoverage{1, {10, 50}, 0.0, kAllRound, 45.0, 0.9, SightBlockers::none}};
  });
  auto truth = [](std::int32_t t) { return Vec2{10.0 + 2.0 * t, 50.0}; };
  for (std::int32_t t = 1; t <= 35; ++t) {
    const Vec2 p = truth(t);
    if (std::hypot(p.x - 10.0, p.y - 50.0) <= 45.0)
      h.step(t, {fix(t, 1, {10, 50}, p)});
    else
      h.step(t);
    INFO("tick " << t);
    if (t >= 5 && t <= 31) CHECK(h.engine.confirmedTracks().size() == 1);
    if (t >= 32) CHECK(h.engine.confirmedTracks().empty());
  }
}

/// A sensor model's settings that list four of the default grid's sensors: ids 0 and 49 (true
/// positions (0.5, 0.5) and (49.5, 0.5)) and 50 and 99 ((50.5, 0.5) and (99.5, 0.5)).
struct FourListedSensors : common::SensorModelSettingsOf<FourListedSensors> {
  std::vector<SensorCoverage> coverage(const common::Scenario&) const override {
    std::vector<SensorCoverage> out;
    for (const common::SensorId id : {0U, 49U, 50U, 99U})
      out.push_back(SensorCoverage{id, {0.5 + id, 0.5}, 0.0, kAllRound, 10.0, 0.9, SightBlockers::none});
    return out;
  }
  friend bool operator==(const FourListedSensors&, const FourListedSensors&) = default;
};

std::vector<common::SensorId> sensorsOf(const EngineContext& context) {
  std::vector<common::SensorId> ids;
  for (const auto& sensor : context.coverage) ids.push_back(sensor.sensor);
  return ids;
}

TEST_CASE("sbmht rejects a sensor listed twice in its coverage", "[sbmht]") {
  const SensorCoverage sensor{3, {50, 50}, 0.0, kAllRound, 100.0, 0.9, SightBlockers::none};
  const common::Scenario s = sbmhtScenario();
  EngineContext context = engineContext(s, 0);
  context.coverage = {sensor, sensor};
  CHECK_THROWS_WITH(SbmhtEngine(context), Catch::Contains("sensor 3 is listed twice"));
}

TEST_CASE("each supernode's sbmht scans only the sensors of its tracking group", "[sbmht]") {
  // Oh §V's g(i): a sensor reports to the supernode nearest its true position, so that supernode
  // alone weighs its detections and misses. With supernodes at x = 25 and 75 the bisector is
  // x = 50: sensors 0 and 49 are the first's, 50 and 99 the second's.
  common::Scenario s = sbmhtScenario();
  s.sensor_model.settings = std::make_shared<const FourListedSensors>();
  CHECK(sensorsOf(engineContext(s, 0)) == std::vector<common::SensorId>{0, 49, 50, 99});
  s.supernodes = {{25.0, 50.0}, {75.0, 50.0}};
  CHECK_NOTHROW(resolveEngineParams(s, common::kNoStatistics));
  CHECK(sensorsOf(engineContext(s, 0)) == std::vector<common::SensorId>{0, 49});
  CHECK(sensorsOf(engineContext(s, 1)) == std::vector<common::SensorId>{50, 99});
  // A tie goes to the lower index, as the network model routes it: the bisector through sensor 50.
  s.supernodes = {{40.5, 50.0}, {60.5, 50.0}};
  CHECK(sensorsOf(engineContext(s, 0)) == std::vector<common::SensorId>{0, 49, 50});
  CHECK(sensorsOf(engineContext(s, 1)) == std::vector<common::SensorId>{99});
}

}  // namespace
}  // namespace wsn::supernode::sbmht

#include "node/acoustic/acoustic_field.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/tiling.hpp"
#include "scenario/loader.hpp"

namespace wsn::node::acoustic {
namespace {

constexpr double kVs = 343.0;

/// An acoustic scenario on the paper's 50 x 50 grid at Ds = 25 m, with `targets` (YAML list items)
/// and `extra` sensor_model lines.
common::Scenario acousticScenario(const std::string& targets, const std::string& extra = "", int ticks = 60) {
  return scenario::parseScenario(
      "region: {x_min: 0, y_min: 0, x_max: 1250, y_max: 1250}\n"
      "sensors: {layout: grid, spacing: 25}\n"
      "sensor_model:\n  kind: acoustic_doppler\n  alpha: 2\n  sensing_range: 40\n" + extra +
          "dynamics: {delta: 1, process_noise_sigma: 0}\n"
          "targets:\n  scripted:\n" + targets +
          "run: {ticks: " + std::to_string(ticks) + ", node_processes: 1}\n",
      "test.yaml");
}

/// A field over the whole grid (one tile) with the objects it refers to.
struct World {
  explicit World(common::Scenario s)
      : scenario(std::move(s)), truth(truthConfig(scenario)), layout(sensorFieldConfig(scenario)), tiles(makeTiles(layout, 1)),
        field(fieldConfigOf(scenario), layout, tiles.front(), truth) {}
  common::Scenario scenario;
  common::Truth truth;
  common::SensorLayout layout;
  std::vector<Tile> tiles;
  AcousticField field;
};

TEST_CASE("the retarded time of a stationary target is the time minus the travel time", "[acoustic]") {
  // Positions at ticks 1..5 of 0.1 s, all at the origin: tau* = t - d / Vs, here 0.45 - 34.3 / 343 = 0.35 s.
  const Trajectory path(1, 0.1, std::vector<common::Vec2>(5, {0.0, 0.0}));
  const auto tau = path.retardedTime({34.3, 0.0}, 0.45, kVs);
  REQUIRE(tau.has_value());
  CHECK(*tau == Approx(0.35).margin(1e-12));
  // At 0.15 s the first emission (0.1 s) has travelled 17.15 m < 34.3 m: nothing heard yet.
  CHECK_FALSE(path.retardedTime({34.3, 0.0}, 0.15, kVs).has_value());
  // Long after the last emission (0.5 s) its sound has passed: tau* is clamped to the end.
  CHECK(*path.retardedTime({34.3, 0.0}, 5.0, kVs) == Approx(0.5));
}

TEST_CASE("the retarded time of a target driving straight at or away from the listener has a closed form",
          "[acoustic]") {
  // p(tau) = (v tau, 0) with v = 20 m/s, positions at ticks 0..10 of 0.1 s (t in [0, 1] s).
  constexpr double v = 20.0;
  std::vector<common::Vec2> positions;
  for (int i = 0; i <= 10; ++i) positions.push_back({v * 0.1 * i, 0.0});
  const Trajectory path(0, 0.1, positions);
  // Approaching a listener at L = 100 m: Vs (t - tau) = L - v tau, tau = (Vs t - L) / (Vs - v).
  const double t = 0.9;
  CHECK(*path.retardedTime({100.0, 0.0}, t, kVs) == Approx((kVs * t - 100.0) / (kVs - v)).margin(1e-12));
  // Receding from a listener at -100 m: Vs (t - tau) = 100 + v tau, tau = (Vs t - 100) / (Vs + v).
  CHECK(*path.retardedTime({-100.0, 0.0}, t, kVs) == Approx((kVs * t - 100.0) / (kVs + v)).margin(1e-12));
  // The Doppler effect: over 0.2 s of listening the approaching target's emissions of
  // 0.2 Vs / (Vs - v) s arrive (more than one per step), the receding one's of 0.2 Vs / (Vs + v) s.
  const double approach = *path.retardedTime({100.0, 0.0}, 0.8, kVs) - *path.retardedTime({100.0, 0.0}, 0.6, kVs);
  const double recede = *path.retardedTime({-100.0, 0.0}, 0.8, kVs) - *path.retardedTime({-100.0, 0.0}, 0.6, kVs);
  CHECK(approach == Approx(0.2 * kVs / (kVs - v)));
  CHECK(recede == Approx(0.2 * kVs / (kVs + v)));
}

TEST_CASE("a stationary target is heard once per step at Pt / d^alpha, so exactly within its sensing range",
          "[acoustic]") {
  // Target at (612.5, 600): the sensor at (612.5, 637.5) is 37.5 m away, inside SR = 40 m; the one at
  // (637.5, 637.5) is sqrt(25^2 + 37.5^2) = 45.07 m away, outside.
  World w(acousticScenario("    - {x: 612.5, y: 600, vx: 0, vy: 0}\n"));
  // Pt = cs SR^2 = 1600; at 37.5 m one emission per step gives 1600 / 1406.25 = 1.1378.
  const auto [power, target] = w.field.targetPower({612.5, 637.5}, 20);
  CHECK(power == Approx(1600.0 / (37.5 * 37.5)).epsilon(1e-12));
  CHECK(target == 0);
  std::set<common::SensorId> expected;
  for (common::SensorId id = 0; id < w.layout.size(); ++id)
    if (common::distance(w.layout.truePosition(id), {612.5, 600.0}) <= 40.0) expected.insert(id);
  std::set<common::SensorId> detected;
  for (const auto& r : w.field.detect(20)) {
    detected.insert(r.sensor);
    // ws = floor(Ps / cs) (eq. 4)
    const double d = common::distance(w.layout.truePosition(r.sensor), {612.5, 600.0});
    CHECK(r.power_level == static_cast<int>(std::floor(1600.0 / (d * d))));
    CHECK(r.target == 0);
    // A detection measures a position, the sensor's, with the engine's own noise model.
    CHECK(r.measurement.get() == nullptr);  // a plain position
  }
  CHECK(detected == expected);
  // Rows y = 587.5 and 612.5 at x = 587.5, 612.5, 637.5 (12.5 or 27.95 m) and (612.5, 562.5),
  // (612.5, 637.5) at 37.5 m.
  CHECK(expected.size() == 8);
}

TEST_CASE("no sound is heard before it can have travelled, and it fades after the target is gone",
          "[acoustic]") {
  // The target appears at tick 5 (0.5 s) and is gone from tick 8: its sound reaches 200 m away
  // only 0.58 s later, in tick 11.
  World w(acousticScenario("    - {appear_tick: 5, disappear_tick: 8, x: 600, y: 600, vx: 0, vy: 0}\n"));
  CHECK(w.field.targetPower({800.0, 600.0}, 10).first == 0.0);
  CHECK(w.field.targetPower({800.0, 600.0}, 11).first > 0.0);
  CHECK(w.field.targetPower({800.0, 600.0}, 20).first == 0.0);
  CHECK(w.field.detect(4).empty());
}

TEST_CASE("a moving target is louder ahead than behind at the same distance (Doppler)", "[acoustic]") {
  // 25 m/s east. Ahead, the emissions of (Vs / (Vs - v)) dt arrive per step, behind those of
  // (Vs / (Vs + v)) dt; at equal distance from where the sound left the target, the mean powers
  // differ by (Vs + v) / (Vs - v) = 368 / 318 = 1.157.
  World w(acousticScenario("    - {x: 300, y: 612.5, vx: 2.5, vy: 0}\n"));
  std::vector<common::Vec2> positions;
  for (int t = 1; t <= 60; ++t) positions.push_back({300.0 + 2.5 * (t - 1), 612.5});
  const Trajectory path(1, 0.1, positions);
  // One tick holds a whole number of emissions (18 or 19 behind, 21 or 22 ahead), so the ratio is
  // averaged over ticks 21..40 at listeners fixed 200 m ahead of and behind the tick-30 position,
  // where the count's phase drifts from tick to tick.
  const auto relative = [&](double offset) {
    const common::Vec2 listener{300.0 + 2.5 * 29.0 + offset, 612.5};
    double sum = 0.0;
    for (int t = 21; t <= 40; ++t) {
      const double tau = *path.retardedTime(listener, 0.1 * t - 0.05, kVs);  // the middle of tick t
      const double d = common::distance(listener, path.at(tau));
      sum += w.field.targetPower(listener, t).first * d * d / 1600.0;  // Pt = 40^2
    }
    return sum / 20.0;
  };
  const double ahead = relative(200.0);
  const double behind = relative(-200.0);
  CHECK(ahead == Approx(kVs / (kVs - 25.0)).epsilon(0.03));
  CHECK(behind == Approx(kVs / (kVs + 25.0)).epsilon(0.03));
  CHECK(ahead / behind == Approx(368.0 / 318.0).epsilon(0.03));
}

TEST_CASE("sound power fluctuates within the given percentage", "[acoustic]") {
  World steady(acousticScenario("    - {x: 612.5, y: 600, vx: 0, vy: 0}\n"));
  World noisy(acousticScenario("    - {x: 612.5, y: 600, vx: 0, vy: 0}\n", "  acoustic: {power_fluctuation: 0.4}\n"));
  const double base = steady.field.targetPower({612.5, 637.5}, 20).first;
  bool differs = false;
  for (int t = 10; t < 40; ++t) {
    const double p = noisy.field.targetPower({612.5, 637.5}, t).first;
    CHECK(p >= 0.6 * base);
    CHECK(p <= 1.4 * base);
    differs = differs || p != base;
  }
  CHECK(differs);
}

TEST_CASE("environmental noise hits the given fraction of sensors for the given duration", "[acoustic]") {
  // Noise 3: 0.1 s (1 tick) on 5 % plus 1 s (10 ticks) on 1 %, power cs (1 + U(0, 1)).
  World w(acousticScenario("    - {x: 10, y: 10, vx: 0, vy: 0}\n", "  environmental_noise: {preset: noise3}\n", 200));
  std::size_t noisy = 0;
  std::size_t samples = 0;
  for (common::SensorId id = 0; id < w.layout.size(); id += 7)
    for (int t = 1; t <= 200; ++t) {
      const double p = w.field.noisePower(id, t);
      ++samples;
      if (p > 0.0) ++noisy;
      CHECK((p == 0.0 || (p >= 1.0 && p < 4.0)));  // one or two components, each in [1, 2)
    }
  // 1 - (1 - 0.05)(1 - 0.01) = 5.95 % of sensor-ticks, over 358 x 200 samples (sd 0.09 %).
  CHECK(static_cast<double>(noisy) / static_cast<double>(samples) == Approx(0.0595).margin(0.005));

  // The 1 s component alone: runs of noisy ticks are whole episodes of 10 ticks.
  World long_noise(acousticScenario("    - {x: 10, y: 10, vx: 0, vy: 0}\n",
                                    "  environmental_noise:\n    components: [{fraction: 0.2, duration_s: 1}]\n", 200));
  std::size_t runs = 0;
  for (common::SensorId id = 0; id < 200; ++id) {
    int run = 0;
    for (int t = 1; t <= 200; ++t) {
      if (long_noise.field.noisePower(id, t) > 0.0) {
        ++run;
        continue;
      }
      // A run cut by the start of the run (tick 1) can be shorter; every other run is whole episodes.
      if (run > 0 && t - run > 1) CHECK(run % 10 == 0);
      if (run > 0) ++runs;
      run = 0;
    }
  }
  CHECK(runs > 100);
}

TEST_CASE("detect() reports exactly what a brute-force pass over every sensor finds", "[acoustic]") {
  // Two crossing targets, power fluctuation and Noise 2: every sensor evaluated with the full model.
  World w(acousticScenario("    - {x: 300, y: 300, vx: 2, vy: 0.5, sensing_range: 30}\n"
                           "    - {x: 330, y: 380, vx: 1.5, vy: -1.5, sensing_range: 40}\n",
                           "  acoustic: {power_fluctuation: 0.2}\n  environmental_noise: {preset: noise2}\n"));
  for (const int tick : {3, 25, 40, 60}) {
    INFO("tick " << tick);
    std::vector<common::Report> brute;
    for (common::SensorId id = 0; id < w.layout.size(); ++id) {
      const auto [power, target] = w.field.targetPower(w.layout.truePosition(id), tick);
      const double total = power + w.field.noisePower(id, tick);
      if (total >= 1.0)
        brute.push_back({tick, id, w.layout.believedPosition(id).x, w.layout.believedPosition(id).y, target,
                         static_cast<std::int32_t>(std::floor(total))});
    }
    const auto fast = w.field.detect(tick);
    CHECK(fast == brute);
    CHECK(!fast.empty());
  }
}

TEST_CASE("the detections do not depend on the tiling and are deterministic", "[acoustic]") {
  const auto scenario = acousticScenario("    - {x: 300, y: 300, vx: 2, vy: 0.5}\n    - {x: 900, y: 900, vx: -2, vy: 0}\n",
                                         "  environmental_noise: {preset: noise1}\n");
  const common::Truth truth(truthConfig(scenario));
  const common::SensorLayout layout(sensorFieldConfig(scenario));
  const auto one = makeTiles(layout, 1);
  const AcousticField whole(fieldConfigOf(scenario), layout, one.front(), truth);
  for (const int count : {2, 4}) {
    const auto tiles = makeTiles(layout, count);
    std::vector<AcousticField> fields;
    for (const auto& tile : tiles) fields.emplace_back(fieldConfigOf(scenario), layout, tile, truth);
    for (const int tick : {5, 30}) {
      std::vector<common::Report> joined;
      for (const auto& f : fields) {
        const auto part = f.detect(tick);
        joined.insert(joined.end(), part.begin(), part.end());
      }
      std::sort(joined.begin(), joined.end(), [](const auto& a, const auto& b) { return a.sensor < b.sensor; });
      CHECK(joined == whole.detect(tick));
    }
  }
  const AcousticField again(fieldConfigOf(scenario), layout, one.front(), truth);
  CHECK(again.detect(30) == whole.detect(30));
}

TEST_CASE("the acoustic field refuses a non-acoustic scenario and more than 8 noise components", "[acoustic]") {
  const auto scenario = scenario::parseScenario("run: {ticks: 5}\n", "plain.yaml");
  const common::Truth truth(truthConfig(scenario));
  const common::SensorLayout layout(sensorFieldConfig(scenario));
  CHECK_THROWS_AS(fieldConfigOf(scenario), std::invalid_argument);

  // Noise streams are keyed by sensor * 8 + component: a ninth component would share them.
  auto crowded = acousticScenario("    - {x: 10, y: 10, vx: 0, vy: 0}\n");
  auto crowded_config = fieldConfigOf(crowded);
  crowded_config.settings.environmental_noise.components.assign(9, {0.01, 0.1});
  const common::Truth crowded_truth(truthConfig(crowded));
  const common::SensorLayout crowded_layout(sensorFieldConfig(crowded));
  CHECK_THROWS_WITH(AcousticField(crowded_config, crowded_layout, makeTiles(crowded_layout, 1).front(), crowded_truth),
                    Catch::Contains("9 environmental noise components; at most 8"));
}

}  // namespace
}  // namespace wsn::node::acoustic

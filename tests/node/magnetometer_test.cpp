#include "node/magnetometer/magnetometer_field.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/rng.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/tiling.hpp"
#include "scenario/loader.hpp"

namespace wsn::node::magnetometer {
namespace {

using common::Vec2;

constexpr double kEta = 80.0;  // eta of eq. (11), the default threshold
constexpr int kW = 5;          // W of eq. (11)

/// Oh's testbed: a 9 x 5 grid of pitch 1 over [-0.5, 8.5] x [-0.5, 4.5] (sensors at integer
/// points), default magnetometer settings, one target along y = 2 at 0.5 pitch per tick from
/// x = -0.5, no process noise. `extra` adds sensor_model lines.
common::Scenario testbed(const std::string& extra = "") {
  return scenario::parseScenario(
      "region: {x_min: -0.5, y_min: -0.5, x_max: 8.5, y_max: 4.5}\n"
      "sensors: {layout: grid, spacing: 1}\n"
      "sensor_model:\n  kind: magnetometer\n  sensing_range: 0.6\n" + extra +
          "localisation: {sigma: 0}\n"
          "dynamics: {delta: 1, process_noise_sigma: 0}\n"
          "targets:\n  scripted:\n    - {appear_tick: 1, x: -0.5, y: 2, vx: 0.5, vy: 0}\n"
          "run: {ticks: 24, node_processes: 1}\n",
      "magnetometer_test.yaml");
}

/// The peak over a long straight pass of eq. (11)'s D at a sensor at lateral offset d from the
/// path: the magnet moves along y = 0 from x = -5 + phase to x = 5 at 1 pitch/s, sampled at 10 Hz
/// (0.1 pitch between samples), the sensor at (0, d). With `clip` a reading is
/// clip(512 + field, 0, 1023) per axis.
double passPeak(double d, double phase, bool clip = false) {
  constexpr double kHeight = 0.2;
  constexpr double kStrength = 125.0;
  ChangeDetector detector(kW);
  double peak = 0.0;
  for (int i = 0; i <= 100; ++i) {
    const Vec2 field = horizontalField({-5.0 + phase + 0.1 * i, 0.0}, {0.0, d}, kHeight, kStrength);
    const Vec2 reading = clip ? Vec2{std::clamp(512.0 + field.x, 0.0, 1023.0), std::clamp(512.0 + field.y, 0.0, 1023.0)}
                              : field;
    peak = std::max(peak, detector.push(reading));
  }
  return peak;
}

/// The worst sampling phase: the minimum over phases in [0, 0.1) pitch (one sample period) of the
/// pass's peak D.
double worstPhasePeak(double d, bool clip = false) {
  double worst = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 200; ++k) worst = std::min(worst, passPeak(d, 0.1 * k / 200.0, clip));
  return worst;
}
double bestPhasePeak(double d) {
  double best = 0.0;
  for (int k = 0; k < 200; ++k) best = std::max(best, passPeak(d, 0.1 * k / 200.0));
  return best;
}

TEST_CASE("the horizontal field of a vertical dipole is 3 K h rho over r to the fifth, away from the magnet",
          "[magnetometer]") {
  // rho = 0.5 along x, h = 0.2, K = 125: 3 * 125 * 0.2 * 0.5 / (0.25 + 0.04)^2.5 = 37.5 / 0.29^2.5.
  const Vec2 b = horizontalField({1.0, 2.0}, {1.5, 2.0}, 0.2, 125.0);
  CHECK(b.x == Approx(37.5 / std::pow(0.29, 2.5)));
  CHECK(b.y == Approx(0.0).margin(1e-12));
  // Along the magnet-to-sensor direction (3, 4) / 5 at rho = 0.5.
  const Vec2 c = horizontalField({0.0, 0.0}, {0.3, 0.4}, 0.2, 125.0);
  CHECK(c.x == Approx(0.6 * 37.5 / std::pow(0.29, 2.5)));
  CHECK(c.y == Approx(0.8 * 37.5 / std::pow(0.29, 2.5)));
  // Zero right under the magnet.
  const Vec2 under = horizontalField({3.0, 3.0}, {3.0, 3.0}, 0.2, 125.0);
  CHECK(under.x == 0.0);
  CHECK(under.y == 0.0);
}

TEST_CASE("B4.1 a slow steady drift of 3 counts per sample gives D = 3 and no detection", "[magnetometer]") {
  // x_i = 100 + 3 i, y_i = 50: every change is |(3, 0)| = 3, so D = (1/5) * 5 * 3 = 3 <= 80.
  std::vector<Vec2> samples;
  for (int i = 0; i <= kW; ++i) samples.push_back({100.0 + 3.0 * i, 50.0});
  CHECK(changeStatistic(samples) == Approx(3.0).margin(1e-12));
  ChangeDetector detector(kW);
  for (int i = 0; i < 100; ++i) {
    const double d = detector.push({100.0 + 3.0 * i, 50.0});
    CHECK_FALSE(d > kEta);
    if (i >= kW) CHECK(d == Approx(3.0).margin(1e-9));
  }
  CHECK_THROWS_AS(changeStatistic(std::span<const Vec2>(samples.data(), 1)), std::invalid_argument);
}

TEST_CASE("B4.2 a step of J counts gives D = J over W for exactly W samples, detected only above eta",
          "[magnetometer]") {
  // Constant readings, then a step J on x: the one change of size J sits in the window of the step
  // sample and the W - 1 = 4 after it, so D = J / 5 for exactly 5 samples, then 0 again.
  // J = 500: D = 100 > 80 (detected); J = 400: D = 80, not detected (eq. 11 is strict).
  for (const double jump : {500.0, 400.0}) {
    INFO("J = " << jump);
    ChangeDetector detector(kW);
    for (int i = 0; i < 10; ++i) CHECK(detector.push({512.0, 600.0}) == 0.0);
    int above = 0;
    int at_step = 0;
    for (int i = 0; i < 20; ++i) {
      const double d = detector.push({512.0 + jump, 600.0});
      CHECK(detector.value() == d);
      if (i < kW) {
        CHECK(d == Approx(jump / kW).margin(1e-12));
        ++at_step;
      } else {
        CHECK(d == 0.0);
      }
      if (d > kEta) ++above;
    }
    CHECK(at_step == 5);
    CHECK(above == (jump == 500.0 ? 5 : 0));
  }
}

TEST_CASE("B4.3 rotating the sensor axes or adding constant offsets leaves D unchanged", "[magnetometer]") {
  // D sums Euclidean lengths of differences: a rotation keeps lengths, an offset cancels in b_i - b_(i-1).
  std::vector<Vec2> samples;
  for (int i = 0; i <= kW; ++i)
    samples.push_back(horizontalField({-0.3 + 0.1 * i, 0.0}, {0.0, 0.45}, 0.2, 125.0) + Vec2{3.0 * i, -7.0 * i * i});
  const double base = changeStatistic(samples);
  REQUIRE(base > 0.0);
  for (const double angle : {0.3, 1.0, std::numbers::pi / 2.0, 2.5, -0.7}) {
    for (const Vec2 offset : {Vec2{0.0, 0.0}, Vec2{512.0, 512.0}, Vec2{-200.0, 733.0}}) {
      INFO("angle " << angle << ", offset (" << offset.x << ", " << offset.y << ")");
      std::vector<Vec2> moved;
      for (const Vec2 b : samples)
        moved.push_back(Vec2{std::cos(angle) * b.x - std::sin(angle) * b.y, std::sin(angle) * b.x + std::cos(angle) * b.y} +
                        offset);
      CHECK(changeStatistic(moved) == Approx(base).epsilon(1e-12));
    }
  }
}

TEST_CASE("B4.4 pure read noise of sigma 5 gives mean D = sqrt(pi) 5 and never reaches eta", "[magnetometer]") {
  // b_i ~ N(0, 25 I): b_i - b_(i-1) ~ N(0, 50 I), its length Rayleigh with scale 5 sqrt(2), mean
  // 5 sqrt(2) sqrt(pi / 2) = 5 sqrt(pi) = 8.862. D averages W such lengths, so its mean is the same.
  // Its standard error over 1e5 samples is ~0.02 (sd of a length 4.6, neighbours correlated).
  common::Stream draw(1, common::Purpose::kMagnetometerSample, 0, 0);
  ChangeDetector detector(kW);
  double sum = 0.0;
  double largest = 0.0;
  constexpr int kSamples = 100000;
  int counted = 0;
  for (int i = 0; i < kSamples; ++i) {
    const Vec2 b{5.0 * draw.normal(), 5.0 * draw.normal()};
    const double d = detector.push(b);
    if (i < kW) continue;  // the first W values hold fewer than W changes
    sum += d;
    ++counted;
    largest = std::max(largest, d);
  }
  const double mean = sum / counted;
  CHECK(std::sqrt(std::numbers::pi) * 5.0 == Approx(8.862).margin(5e-4));
  CHECK(mean == Approx(std::sqrt(std::numbers::pi) * 5.0).margin(0.1));
  CHECK(largest < kEta);
}

TEST_CASE("B4.5 the peak D of a straight pass at the worst sampling phase matches the spec table",
          "[magnetometer]") {
  // Computed here, h = 0.2, K = 125, 1 pitch/s at 10 Hz, W = 5, no noise. Worst phase (min over the
  // phase of the max over time), best phase for comparison:
  //   d     spec   worst    best
  //   0.3   1152   1147.8   1165.6
  //   0.4    430    428.0    432.5
  //   0.5    176    175.7    176.7   (clipped to [0, 1023] around 512: worst 126.2)
  //   0.6   80.0    79.70    79.87
  //   0.65  55.8    55.55    55.59
  //   0.7   39.7    39.53    39.55
  //   0.8   21.6    21.52    21.59
  //   1.0    7.7     7.67     7.70
  // Every spec number is within 0.5 % of the worst-phase peak (within the 2 % asked), but most are
  // slightly above it, between the worst and the best phase (1152 is neither; rounding of another
  // computation). Note d = 0.6: the exact peak is 79.70 (79.87 even at the best phase), below
  // eta = 80 -- strictly a car at 0.6 pitch is not detected without noise; the spec's "80.0" is
  // rounded up. The detection range is just under 0.6 pitch.
  struct Row {
    double d;
    double spec;
  };
  for (const Row row : {Row{0.3, 1152.0}, Row{0.4, 430.0}, Row{0.5, 176.0}, Row{0.6, 80.0}, Row{0.65, 55.8},
                        Row{0.7, 39.7}, Row{0.8, 21.6}, Row{1.0, 7.7}}) {
    INFO("d = " << row.d);
    const double worst = worstPhasePeak(row.d);
    CHECK(worst == Approx(row.spec).epsilon(0.02));
    CHECK(worst <= bestPhasePeak(row.d));
  }
  CHECK(worstPhasePeak(0.5, true) == Approx(126.0).epsilon(0.02));
  // Tighter, against the values computed above (to 0.1 %).
  CHECK(worstPhasePeak(0.3) == Approx(1147.8).epsilon(1e-3));
  CHECK(worstPhasePeak(0.6) == Approx(79.70).epsilon(1e-3));
  CHECK(worstPhasePeak(0.65) == Approx(55.55).epsilon(1e-3));
  // Detection (D > 80) at the worst phase out to 0.5 pitch, none from 0.6 on.
  CHECK(worstPhasePeak(0.5) > kEta);
  CHECK(worstPhasePeak(0.5, true) > kEta);
  CHECK_FALSE(worstPhasePeak(0.6) > kEta);
  CHECK_FALSE(bestPhasePeak(0.6) > kEta);
  CHECK_FALSE(worstPhasePeak(0.65) > kEta);
}

/// The fields of `config` over `layout` tiled into `count` tiles; detect(tick) joins their reports.
struct Tiled {
  Tiled(const MagnetometerFieldConfig& config, const common::SensorLayout& layout, const common::Truth& truth, int count) {
    for (const auto& tile : makeTiles(layout, count)) fields.emplace_back(config, layout, tile, truth);
  }
  std::vector<common::Report> detect(std::int32_t tick) {
    std::vector<common::Report> joined;
    for (auto& field : fields) {
      const auto part = field.detect(tick);
      joined.insert(joined.end(), part.begin(), part.end());
    }
    std::sort(joined.begin(), joined.end(), [](const auto& a, const auto& b) { return a.sensor < b.sensor; });
    return joined;
  }
  std::vector<MagnetometerField> fields;
};

TEST_CASE("B4.6 a target crossing the testbed along a sensor row is reported every tick near where it is",
          "[magnetometer]") {
  const auto scenario = testbed();
  const common::Truth truth(truthConfig(scenario));
  const common::SensorLayout layout(sensorFieldConfig(scenario));
  REQUIRE(layout.size() == 45);
  REQUIRE(layout.truePosition(0).x == Approx(0.0).margin(1e-12));
  REQUIRE(truth.targetCount() == 1);
  const auto tiles = makeTiles(layout, 1);
  const auto defaults = fieldConfigOf(scenario.sensor_model, 1).settings;
  CHECK(defaults == MagnetometerSettings{});
  // The target is at x = -0.5 + 0.5 (t - 1) at tick t: inside x in [0, 8] at ticks 2..18; it leaves
  // the region (x = 9 > 8.5) at tick 20.
  REQUIRE(truth.at(19).size() == 1);
  REQUIRE(truth.at(20).empty());

  std::int64_t true_reports = 0;
  std::int64_t target_ticks = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    INFO("seed " << seed);
    MagnetometerField field(fieldConfigOf(scenario.sensor_model, seed), layout, tiles.front(), truth);
    for (std::int32_t tick = 1; tick <= 24; ++tick) {
      const auto reports = field.detect(tick);
      for (const auto& r : reports) CHECK(r.power_level > static_cast<int>(kEta) - 1);
      if (truth.at(tick).empty()) continue;
      const auto& target = truth.at(tick).front();
      ++target_ticks;
      for (const auto& r : reports)
        if (r.target == target.id) ++true_reports;
      if (target.x >= 0.0 && target.x <= 8.0) {
        INFO("tick " << tick << ", target at x = " << target.x);
        const bool near = std::any_of(reports.begin(), reports.end(), [&](const common::Report& r) {
          return common::distance({r.x, r.y}, {target.x, target.y}) <= 1.2;
        });
        CHECK(near);
      }
    }
  }
  // Per target-tick (the 19 ticks 1..19 it is alive, over 20 seeds): 1.84 measured. Roughly: each
  // sensor of row y = 2 fires while the target is from ~0.5 before to ~1.05 past it (above), ~1.5
  // pitch of path, i.e. over ~3.5 ticks of 0.5 pitch, one sensor per 2 ticks: ~1.8 per tick.
  const double per_target_tick = static_cast<double>(true_reports) / static_cast<double>(target_ticks);
  CHECK(per_target_tick >= 1.5);
  CHECK(per_target_tick <= 2.5);
}

TEST_CASE("B4.6 without bias jumps every report is of the target and near its path in the tick",
          "[magnetometer]") {
  // The spec: "with jump_rate_hz = 0 no report lies farther than 1.2 pitch from the target". Against
  // the target's position at the END of the tick this does not hold, and cannot: eq. (11) at a
  // sample looks back W = 5 samples (0.5 pitch here), so D stays above eta until the target is
  // about 1.05 pitch past a sensor it drove over, e.g. sensor (2, 2), target from x = 2.55 to 3.05
  // over the window: on-axis field 3 K h rho / (rho^2 + h^2)^2.5 = 601 -> 56 counts, D = (601 - 56)
  // / 5 = 109 unclipped (clipped at 0 from an offset of 412..612: (offset - 56) / 5, 71..111). That
  // sample can be the first of a tick whose end finds the target another 0.45 pitch on, so a
  // report can lie ~1.5 pitch from the tick-end position (seed 1: sensor (2, 2) at tick 9, target
  // at (3.5, 2), 1.5 away; and sensor (8, 2) reports at tick 20, when the target, at x = 8.5 at
  // tick 19, has left the region and its field vanishes in one step). What holds is the labelling rule's 1.2 = 2 sensing ranges:
  // every report is the target's (not a false alarm), and lies within 1.2 pitch of the target's
  // path in the tick (from its position at tick - 1 to that at tick).
  const auto scenario = testbed("  jump_rate_hz: 0\n");
  const common::Truth truth(truthConfig(scenario));
  const common::SensorLayout layout(sensorFieldConfig(scenario));
  const auto tiles = makeTiles(layout, 1);
  std::size_t reports_seen = 0;
  double farthest_from_end = 0.0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    MagnetometerField field(fieldConfigOf(scenario.sensor_model, seed), layout, tiles.front(), truth);
    for (std::int32_t tick = 1; tick <= 24; ++tick) {
      for (const auto& r : field.detect(tick)) {
        INFO("seed " << seed << ", tick " << tick << ", sensor at (" << r.x << ", " << r.y << ")");
        ++reports_seen;
        // The target's path in the tick: x = -0.5 + 0.5 (t - 1) at tick t (from x - 0.5 before tick 1).
        const double x_end = -0.5 + 0.5 * (tick - 1);
        const double x_start = x_end - 0.5;
        REQUIRE(x_start <= 8.5);  // it was still there at the tick's start
        const double x_near = std::clamp(r.x, x_start, std::min(x_end, 8.5));
        CHECK(common::distance({r.x, r.y}, {x_near, 2.0}) <= 1.2);
        CHECK(r.target == 0);
        CHECK(r.y == 2.0);  // lateral offset 1 peaks at D = 7.7: only the row the target drives over
        if (!truth.at(tick).empty()) {
          const auto& target = truth.at(tick).front();
          CHECK(target.x == Approx(x_end).margin(1e-9));
          farthest_from_end = std::max(farthest_from_end, common::distance({r.x, r.y}, {target.x, target.y}));
        }
      }
    }
  }
  CHECK(reports_seen > 0);
  // 1.5 measured (seeds 1-20).
  CHECK(farthest_from_end > 1.2);  // the spec's bound against the tick-end position is exceeded
  CHECK(farthest_from_end <= 1.55);
}

TEST_CASE("the magnetometer field refuses a tick earlier than one already reported", "[magnetometer]") {
  const auto scenario = testbed();
  const common::Truth truth(truthConfig(scenario));
  const common::SensorLayout layout(sensorFieldConfig(scenario));
  MagnetometerField field(fieldConfigOf(scenario.sensor_model, 1), layout, makeTiles(layout, 1).front(), truth);
  CHECK_NOTHROW(field.detect(5));
  CHECK_THROWS_AS(field.detect(3), std::logic_error);
  CHECK_NOTHROW(field.detect(6));
  CHECK_THROWS_AS(field.detect(1), std::logic_error);
}

TEST_CASE("the magnetometer reports do not depend on the tiling", "[magnetometer]") {
  // Default settings, and frequent bias jumps so that false alarms are compared too.
  for (const char* extra : {"", "  jump_rate_hz: 0.5\n"}) {
    const auto scenario = testbed(extra);
    const common::Truth truth(truthConfig(scenario));
    const common::SensorLayout layout(sensorFieldConfig(scenario));
    for (const std::uint64_t seed : {1, 7}) {
      INFO("extra '" << extra << "', seed " << seed);
      const auto config = fieldConfigOf(scenario.sensor_model, seed);
      Tiled one(config, layout, truth, 1);
      Tiled two(config, layout, truth, 2);
      REQUIRE(one.fields.size() == 1);
      REQUIRE(two.fields.size() == 2);
      std::size_t total = 0;
      std::size_t false_alarms = 0;
      for (std::int32_t tick = 1; tick <= 24; ++tick) {
        const auto whole = one.detect(tick);
        CHECK(two.detect(tick) == whole);
        total += whole.size();
        for (const auto& r : whole) false_alarms += r.target == common::kFalseAlarm ? 1 : 0;
      }
      CHECK(total > 0);
      if (*extra != 0) CHECK(false_alarms > 0);
    }
  }
}

TEST_CASE("the magnetometer field config refuses other sensor models", "[magnetometer]") {
  const auto scenario = scenario::parseScenario("run: {ticks: 5}\n", "plain.yaml");
  CHECK_THROWS_AS(fieldConfigOf(scenario.sensor_model, 1), std::invalid_argument);
}

}  // namespace
}  // namespace wsn::node::magnetometer

#include "node/signal_strength/sensor_field.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/scenario_config.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/tiling.hpp"

namespace {

using wsn::common::Report;
using wsn::common::Scenario;
using wsn::common::SensorId;
using wsn::common::SensorLayout;
using wsn::common::SensorReading;
using wsn::common::TargetState;
using wsn::node::DetectStats;
using wsn::node::makeTiles;
using wsn::node::SensorField;
using wsn::node::Tile;

/// Default field (Oh §VII): 100 x 100 grid, spacing 1, sensor (col, row) at (col + .5, row + .5)
/// with id row * 100 + col; Rs = 1.5, alpha = 2, beta = 9.75, gamma = 1, eta = 2.
Scenario defaultScenario(double noise_sigma, std::uint64_t seed = 5) {
  Scenario s;
  s.run.seed = seed;
  auto model = std::make_shared<wsn::node::signal_strength::SignalStrengthSettings>();
  model->noise_sigma = noise_sigma;
  s.sensor_model.settings = model;
  return s;
}

/// The signal-strength field of scenario `s` over `tile`.
SensorField fieldOf(const Scenario& s, const SensorLayout& layout, const Tile& tile) {
  return SensorField(wsn::common::settingsOf<wsn::node::signal_strength::SignalStrengthSettings>(s.sensor_model),
                     s.sensor_model.sensing_range, s.run.seed, layout, tile);
}

SensorId gridId(int column, int row) { return static_cast<SensorId>(row * 100 + column); }

TargetState target(int id, double x, double y) { return TargetState{id, x, y, 0.0, 0.0}; }

const SensorReading* findReading(const std::vector<SensorReading>& readings, SensorId id) {
  const auto it = std::find_if(readings.begin(), readings.end(), [&](const auto& r) { return r.sensor == id; });
  return it == readings.end() ? nullptr : &*it;
}

/// The field as a single tile.
struct WholeField {
  explicit WholeField(const Scenario& s) : layout(sensorFieldConfig(s)), tiles(makeTiles(layout, 1)), field(fieldOf(s, layout, tiles[0])) {}
  SensorLayout layout;
  std::vector<Tile> tiles;
  SensorField field;
};

bool sortedById(const std::vector<SensorReading>& readings) {
  return std::is_sorted(readings.begin(), readings.end(), [](const auto& a, const auto& b) { return a.sensor < b.sensor; });
}

}  // namespace

TEST_CASE("detect gives the eq. 5 signal at a known distance when noise is off", "[node][sensor_field]") {
  const WholeField w(defaultScenario(0.0));
  const std::vector<TargetState> targets{target(3, 51.7, 50.5)};
  const auto readings = w.field.detect(1, targets);
  REQUIRE(sortedById(readings));

  // Sensor (50, 50) sits at (50.5, 50.5), 1.2 from the target: 9.75 / (1 + 1.2^2) = 3.99590164.
  const auto* at_1_2 = findReading(readings, gridId(50, 50));
  REQUIRE(at_1_2 != nullptr);
  CHECK(at_1_2->z == Approx(3.9959016393).margin(1e-9));
  // Sensor (51, 50) at distance 0.2: 9.75 / 1.04 = 9.375.
  const auto* at_0_2 = findReading(readings, gridId(51, 50));
  REQUIRE(at_0_2 != nullptr);
  CHECK(at_0_2->z == Approx(9.375).margin(1e-9));
  // Sensor (49, 50) at distance 2.2 > Rs: z = 0 < eta.
  CHECK(findReading(readings, gridId(49, 50)) == nullptr);
  // Within Rs (d^2 <= 2.25): dx in {-1.2, -0.2, 0.8} on the target's row, dx in {-0.2, 0.8}
  // one row up or down (dx^2 + 1 <= 2.25) -> 3 + 2 + 2 = 7 sensors, each with z >= 3 >= eta.
  CHECK(readings.size() == 7);
}

TEST_CASE("detect adds the signals of several targets within Rs", "[node][sensor_field]") {
  const WholeField w(defaultScenario(0.0));
  // Sensor (50, 50) at (50.5, 50.5) has two targets at distance 1 (4.875 each) and one at
  // distance 2 > Rs that must not count: z = 9.75.
  const std::vector<TargetState> targets{target(1, 49.5, 50.5), target(2, 51.5, 50.5), target(7, 50.5, 52.5)};
  const auto readings = w.field.detect(4, targets);
  const auto* both = findReading(readings, gridId(50, 50));
  REQUIRE(both != nullptr);
  CHECK(both->z == Approx(9.75).margin(1e-9));
  // Sensor (49, 50) is on target 1 (9.75) and 2 from target 2 (out of range): 9.75 alone.
  const auto* one = findReading(readings, gridId(49, 50));
  REQUIRE(one != nullptr);
  CHECK(one->z == Approx(9.75).margin(1e-9));
}

TEST_CASE("a single target on a sensor with noise off gives one report at that sensor", "[node][sensor_field]") {
  const WholeField w(defaultScenario(0.0));
  const std::vector<TargetState> targets{target(9, 50.5, 50.5)};
  const auto own = w.field.detect(2, targets);
  // The 3 x 3 block around sensor (50, 50) is within Rs: z = 9.75 at d = 0, 4.875 at the four
  // d = 1 sensors, 9.75 / 3 = 3.25 at the four d = sqrt 2 corners; d = 2 is out of range.
  REQUIRE(own.size() == 9);
  const auto reports = w.field.fuse(2, own, {}, targets);
  // Only the centre beats everything within 2 Rs = 3. Its centre of mass
  // (9.75 s0 + 4.875 sum(edges) + 3.25 sum(corners)) / 42.25 is symmetric about (50.5, 50.5),
  // so it is exactly that point.
  REQUIRE(reports.size() == 1);
  CHECK(reports[0].sensor == gridId(50, 50));
  CHECK(reports[0].tick == 2);
  CHECK(reports[0].target == 9);
  CHECK(reports[0].x == Approx(50.5).margin(1e-12));
  CHECK(reports[0].y == Approx(50.5).margin(1e-12));
  // Eq. 6 measures a position: kind position, dimension 2, values (x, y), no noise of its own.
  CHECK(reports[0].measurement.get() == nullptr);  // a plain position
}

TEST_CASE("equal readings within 2 Rs elect the smaller sensor id", "[node][sensor_field]") {
  const WholeField w(defaultScenario(0.0));
  SECTION("a target midway between two sensors") {
    // Target at (51.0, 50.5): sensors (50,50) and (51,50) both at d = 0.5 -> 7.8 each (exact
    // same double, the distances are equal). (50,50) wins the tie. Sensors within Rs: those two,
    // (49,50) and (52,50) at d = 1.5 -> 3.0, and (50..51, 49) and (50..51, 51) at d^2 = 1.25
    // -> 4.3333. The set is symmetric about x = 51.0 and y = 50.5, so the centre of mass is
    // (51.0, 50.5); all of them are within 2 Rs of (50.5, 50.5) (farthest: (52.5, 50.5) at 2).
    const std::vector<TargetState> targets{target(4, 51.0, 50.5)};
    const auto own = w.field.detect(1, targets);
    REQUIRE(own.size() == 8);
    REQUIRE(findReading(own, gridId(50, 50))->z == findReading(own, gridId(51, 50))->z);
    const auto reports = w.field.fuse(1, own, {}, targets);
    REQUIRE(reports.size() == 1);
    CHECK(reports[0].sensor == gridId(50, 50));
    CHECK(reports[0].x == Approx(51.0).margin(1e-12));
    CHECK(reports[0].y == Approx(50.5).margin(1e-12));
  }
  SECTION("hand-made readings, in either input order") {
    // (10,10) and (12,10) are 2 <= 2 Rs apart with equal z: only 1010 reports. (20,10) and
    // (24,10) are 4 > 2 Rs apart: both report.
    std::vector<SensorReading> own{{gridId(12, 10), 5.0}, {gridId(10, 10), 5.0}, {gridId(24, 10), 4.0},
                                   {gridId(20, 10), 4.0}};
    for (int order = 0; order < 2; ++order) {
      const auto reports = w.field.fuse(3, own, {}, {});
      REQUIRE(reports.size() == 3);
      CHECK(reports[0].sensor == gridId(10, 10));
      CHECK(reports[1].sensor == gridId(20, 10));
      CHECK(reports[2].sensor == gridId(24, 10));
      CHECK(reports[0].target == wsn::common::kFalseAlarm);
      // 1010's centre of mass: (5 * 10.5 + 5 * 12.5) / 10 = 11.5.
      CHECK(reports[0].x == Approx(11.5).margin(1e-12));
      std::reverse(own.begin(), own.end());
    }
  }
}

TEST_CASE("localisation error shifts the report but not the election", "[node][sensor_field]") {
  Scenario exact = defaultScenario(0.0);
  Scenario shifted = defaultScenario(0.0);
  shifted.localisation.sigma = 0.8;
  const WholeField a(exact);
  const WholeField b(shifted);

  SECTION("same target, same readings, report at the believed centre of mass") {
    const std::vector<TargetState> targets{target(1, 50.5, 50.5)};
    const auto own_a = a.field.detect(1, targets);
    const auto own_b = b.field.detect(1, targets);
    REQUIRE(own_a == own_b);  // detection uses true positions only
    const auto reports = b.field.fuse(1, own_b, {}, targets);
    REQUIRE(reports.size() == 1);
    CHECK(reports[0].sensor == gridId(50, 50));
    // Eq. 6 in believed positions, weights 9.75 (centre), 4.875 (edges), 3.25 (corners), sum 42.25.
    double x = 0.0;
    double y = 0.0;
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) {
        const double weight = (dr == 0 && dc == 0) ? 9.75 : (dr == 0 || dc == 0) ? 4.875 : 3.25;
        const auto believed = b.layout.believedPosition(gridId(50 + dc, 50 + dr));
        x += weight * believed.x / 42.25;
        y += weight * believed.y / 42.25;
      }
    CHECK(reports[0].x == Approx(x).margin(1e-9));
    CHECK(reports[0].y == Approx(y).margin(1e-9));
    CHECK(std::hypot(reports[0].x - 50.5, reports[0].y - 50.5) > 1e-3);
  }

  SECTION("who hears whom is decided by true positions") {
    // Find a pair 4 apart (out of 2 Rs = 3) that believes itself within 3, and a pair 3 apart
    // (in range) that believes itself farther than 3. With sigma = 0.8 the believed distance
    // spreads by ~1.1, so such pairs exist along row 20.
    SensorId far_i = 0, far_j = 0, near_i = 0, near_j = 0;
    bool far_found = false, near_found = false;
    for (int c = 0; c + 4 < 100 && !(far_found && near_found); ++c) {
      const SensorId i = gridId(c, 20);
      const auto bi = b.layout.believedPosition(i);
      if (!far_found && wsn::common::distance(bi, b.layout.believedPosition(gridId(c + 4, 20))) < 3.0) {
        far_found = true;
        far_i = i;
        far_j = gridId(c + 4, 20);
      }
      if (!near_found && wsn::common::distance(bi, b.layout.believedPosition(gridId(c + 3, 20))) > 3.0) {
        near_found = true;
        near_i = i;
        near_j = gridId(c + 3, 20);
      }
    }
    REQUIRE(far_found);
    REQUIRE(near_found);
    const std::vector<SensorReading> far{{far_i, 6.0}, {far_j, 5.0}};
    CHECK(b.field.fuse(1, far, {}, {}).size() == 2);  // they cannot hear each other
    const std::vector<SensorReading> near{{near_i, 6.0}, {near_j, 5.0}};
    const auto reports = b.field.fuse(1, near, {}, {});
    REQUIRE(reports.size() == 1);  // the weaker one heard the stronger
    CHECK(reports[0].sensor == near_i);
  }
}

TEST_CASE("a report names the target with the largest signal term, or none", "[node][sensor_field]") {
  const WholeField w(defaultScenario(0.0));
  // Sensor (50,50): target 8 at distance 1.0 (4.875), target 2 at distance 1.4 (9.75/2.96 =
  // 3.29) -> target 8; sensor (20,20) has no target within Rs -> false alarm.
  const std::vector<TargetState> targets{target(2, 50.5, 51.9), target(8, 51.5, 50.5)};
  const std::vector<SensorReading> own{{gridId(50, 50), 7.0}, {gridId(20, 20), 3.0}};
  const auto reports = w.field.fuse(5, own, {}, targets);
  REQUIRE(reports.size() == 2);
  CHECK(reports[0].sensor == gridId(20, 20));
  CHECK(reports[0].target == wsn::common::kFalseAlarm);
  CHECK(reports[1].sensor == gridId(50, 50));
  CHECK(reports[1].target == 8);
}

TEST_CASE("fuse lets foreign readings within 2 Rs win and ignores the rest", "[node][sensor_field]") {
  const Scenario s = defaultScenario(1.0);
  const SensorLayout layout(sensorFieldConfig(s));
  const auto tiles = makeTiles(layout, 2);  // boundary at x = 51
  const SensorField left = fieldOf(s, layout, tiles[0]);
  // Own sensor (50,20) at x = 50.5; foreign (51,20) at x = 51.5 is 1 away and stronger: it wins.
  const std::vector<SensorReading> own{{gridId(50, 20), 4.0}};
  CHECK(left.fuse(1, own, std::vector<SensorReading>{{gridId(51, 20), 4.5}}, {}).empty());
  // A stronger foreign reading 4 away, one far away, one below eta, one with an unknown id: all
  // ignored, and the report's centre of mass is the own sensor alone.
  const std::vector<SensorReading> noise{
      {gridId(54, 20), 9.0}, {gridId(90, 90), 9.0}, {gridId(51, 21), 1.0}, {SensorId{1'000'000}, 9.0}};
  const auto reports = left.fuse(1, own, noise, {});
  REQUIRE(reports.size() == 1);
  CHECK(reports[0].x == Approx(50.5).margin(1e-12));
  CHECK(reports[0].y == Approx(20.5).margin(1e-12));
  // An own reading of a sensor of another tile is heard but never reported by this tile.
  CHECK(left.fuse(1, std::vector<SensorReading>{{gridId(70, 70), 5.0}}, {}, {}).empty());
}

TEST_CASE("boundaryReadings keeps exactly the readings within 2 Rs of another tile", "[node][sensor_field]") {
  const Scenario s = defaultScenario(1.0);
  const SensorLayout layout(sensorFieldConfig(s));
  const auto tiles = makeTiles(layout, 4);  // 2 x 2, split at x = 51 and y = 51
  const SensorField lower_left = fieldOf(s, layout, tiles[0]);
  // Columns 48..50 have x = 48.5..50.5, within 3 of x = 51; column 47 (x = 47.5) is 3.5 away.
  // Likewise for rows against y = 51. Region edges (x = 0, y = 0) border no tile.
  const std::vector<SensorReading> own{{gridId(0, 0), 3.0},   {gridId(10, 10), 3.0}, {gridId(47, 10), 3.0},
                                       {gridId(48, 10), 3.0}, {gridId(10, 48), 3.0}, {gridId(47, 47), 3.0},
                                       {gridId(50, 50), 3.0}};
  const auto boundary = lower_left.boundaryReadings(own);
  std::vector<SensorId> ids;
  for (const auto& r : boundary) ids.push_back(r.sensor);
  CHECK(ids == std::vector<SensorId>{gridId(48, 10), gridId(10, 48), gridId(50, 50)});

  // A single tile has no neighbours and sends nothing.
  const auto whole = makeTiles(layout, 1);
  CHECK(fieldOf(s, layout, whole[0]).boundaryReadings(own).empty());
}

TEST_CASE("reports are the same for 1, 2, 3, 4, 6 and 8 tiles with targets on the tile boundaries",
          "[node][sensor_field][acceptance]") {
  // Noise on, localisation error on, targets straddling the cuts at x = 33, 51, 66 (2, 3, 4
  // tiles: 34 cells of side 3 split at columns 11, 17, 22) and y = 51. Each tile fuses its own
  // readings with the others' boundary readings, exchanged in memory.
  Scenario s = defaultScenario(1.0, 2024);
  s.localisation.sigma = 0.2;
  const SensorLayout layout(sensorFieldConfig(s));

  auto targetsAt = [](std::int32_t tick) {
    const double t = tick;
    return std::vector<TargetState>{
        target(0, 51.0, 20.0 + 0.3 * t),        target(1, 51.0, 51.0),
        target(2, 30.0 + 0.4 * t, 51.0),        target(3, 50.8 + 0.05 * t, 75.3),
        target(4, 51.4, 50.6 - 0.1 * t),        target(5, 33.0, 80.0 - 0.2 * t),
        target(6, 66.0 - 0.02 * t, 10.0),       target(7, 66.2, 51.0 + 0.01 * t),
        target(8, 50.2, 40.0),                  target(9, 51.9, 40.3 + 0.02 * t),
        target(10, 65.9, 50.9),                 target(11, 51.0 + 0.5 * std::sin(t), 51.0 - 0.5 * std::cos(t))};
  };

  struct Outcome {
    std::vector<SensorReading> readings;
    std::vector<Report> reports;
    std::vector<Report> reports_without_exchange;
  };
  auto run = [&](int count, std::int32_t tick) {
    const auto tiles = makeTiles(layout, count);
    std::vector<SensorField> fields;
    for (const Tile& tile : tiles) fields.push_back(fieldOf(s, layout, tile));
    const auto targets = targetsAt(tick);
    std::vector<std::vector<SensorReading>> own(tiles.size());
    std::vector<std::vector<SensorReading>> boundary(tiles.size());
    for (std::size_t k = 0; k < tiles.size(); ++k) {
      own[k] = fields[k].detect(tick, targets);
      boundary[k] = fields[k].boundaryReadings(own[k]);
    }
    Outcome outcome;
    for (std::size_t k = 0; k < tiles.size(); ++k) {
      std::vector<SensorReading> foreign;
      for (std::size_t m = 0; m < tiles.size(); ++m)
        if (m != k) foreign.insert(foreign.end(), boundary[m].begin(), boundary[m].end());
      const auto reports = fields[k].fuse(tick, own[k], foreign, targets);
      const auto alone = fields[k].fuse(tick, own[k], {}, targets);
      outcome.reports.insert(outcome.reports.end(), reports.begin(), reports.end());
      outcome.reports_without_exchange.insert(outcome.reports_without_exchange.end(), alone.begin(), alone.end());
      outcome.readings.insert(outcome.readings.end(), own[k].begin(), own[k].end());
    }
    auto by_sensor = [](const auto& a, const auto& b) { return a.sensor < b.sensor; };
    std::sort(outcome.readings.begin(), outcome.readings.end(), by_sensor);
    std::sort(outcome.reports.begin(), outcome.reports.end(), by_sensor);
    std::sort(outcome.reports_without_exchange.begin(), outcome.reports_without_exchange.end(), by_sensor);
    return outcome;
  };

  int ticks_where_exchange_matters = 0;
  int target_reports = 0;
  for (std::int32_t tick = 1; tick <= 8; ++tick) {
    const Outcome single = run(1, tick);
    // Sanity: the scene has false alarms (q * 10^4 ~ 227) and detections of the 12 targets.
    REQUIRE(single.readings.size() > 150);
    for (const auto& r : single.reports) target_reports += r.target != wsn::common::kFalseAlarm ? 1 : 0;
    for (int count : {2, 3, 4, 6, 8}) {
      INFO("tick " << tick << ", " << count << " tiles");
      const Outcome split = run(count, tick);
      CHECK(split.readings == single.readings);
      CHECK(split.reports == single.reports);  // bit-identical, including the centres of mass
      if (count == 4 && split.reports_without_exchange != single.reports) ++ticks_where_exchange_matters;
    }
  }
  // The test can fail: without the boundary exchange the split result does differ.
  CHECK(ticks_where_exchange_matters > 0);
  CHECK(target_reports >= 8 * 6);
}

TEST_CASE("noise-only exceedances over the 100 x 100 field average 10^4 q per tick", "[node][sensor_field]") {
  // With no target every sensor exceeds eta = 2 independently with q = Q(2) = 0.02275013, so
  // the count per tick is Binomial(10^4, q): mean 227.50, variance 10^4 q (1 - q) = 222.33
  // (sd 14.91). Over 400 ticks the mean has standard error 0.75 (margin 3 ~ 4 se) and the
  // sample variance about 222 sqrt(2 / 399) = 15.7 (margin 63 ~ 4 se).
  // Values follow w | w >= 2: mean phi(2) / Q(2) = 2.37322, sd 0.338; ~91000 draws give a
  // standard error of 0.0011 (margin 0.005).
  // Cells: 34 x 34 = 1156, each of whose first sensor is hit with probability q: expected
  // 1156 * 400 * q = 10519.6, sd 101 (margin 420) -- a skip walk that started one late or
  // never looked at position 0 would miss this.
  const WholeField w(defaultScenario(1.0, 77));
  const int ticks = 400;
  double sum = 0.0;
  double sum_squares = 0.0;
  double sum_z = 0.0;
  double lowest = INFINITY;
  std::int64_t total = 0;
  std::int64_t first_in_cell = 0;
  for (std::int32_t tick = 1; tick <= ticks; ++tick) {
    const auto readings = w.field.detect(tick, {});
    const auto n = static_cast<double>(readings.size());
    sum += n;
    sum_squares += n * n;
    total += static_cast<std::int64_t>(readings.size());
    for (const auto& r : readings) {
      sum_z += r.z;
      lowest = std::min(lowest, r.z);
      const auto& cell = w.layout.sensorsInCell(w.layout.cellOf(w.layout.truePosition(r.sensor)));
      first_in_cell += cell.front() == r.sensor ? 1 : 0;
    }
  }
  const double mean = sum / ticks;
  const double variance = (sum_squares - ticks * mean * mean) / (ticks - 1);
  CHECK(mean == Approx(227.5013).margin(3.0));
  CHECK(variance == Approx(222.33).margin(63.0));
  CHECK(lowest >= 2.0);
  CHECK(sum_z / static_cast<double>(total) == Approx(2.37322).margin(0.005));
  CHECK(static_cast<double>(first_in_cell) == Approx(10519.6).margin(420.0));
}

TEST_CASE("sensors far from every target get no per-sensor draw", "[node][sensor_field]") {
  const WholeField w(defaultScenario(1.0, 3));
  DetectStats stats;
  SECTION("no target: work is one walk per cell plus the exceedances") {
    const auto readings = w.field.detect(17, {}, stats);
    CHECK(stats.exact_draws == 0);
    CHECK(stats.cells_visited == 34 * 34);
    CHECK(stats.skipped_hits == 0);
    CHECK(stats.exceedances == static_cast<std::int64_t>(readings.size()));
  }
  SECTION("one target: exact draws only for the 9 sensors within Rs") {
    // (50.5, 50.5) has its 3 x 3 block within Rs = 1.5 (corners at sqrt 2), nothing else.
    const std::vector<TargetState> targets{target(0, 50.5, 50.5)};
    const auto readings = w.field.detect(17, targets, stats);
    CHECK(stats.exact_draws == 9);
    CHECK(stats.cells_visited == 34 * 34);
    // Every reading is either one of the block's exact values or a far sensor's exceedance.
    const auto in_block = std::count_if(readings.begin(), readings.end(), [](const SensorReading& r) {
      return std::abs(static_cast<int>(r.sensor % 100) - 50) <= 1 && std::abs(static_cast<int>(r.sensor / 100) - 50) <= 1;
    });
    CHECK(static_cast<std::int64_t>(readings.size()) == stats.exceedances + in_block);
  }
}

TEST_CASE("detect is deterministic and ignores the order of the targets", "[node][sensor_field]") {
  const WholeField w(defaultScenario(1.0, 9));
  std::vector<TargetState> targets{target(1, 20.2, 30.3), target(5, 20.9, 31.0), target(3, 70.0, 70.0)};
  const auto first = w.field.detect(6, targets);
  std::reverse(targets.begin(), targets.end());
  const auto second = w.field.detect(6, targets);
  CHECK(first == second);
  CHECK(w.field.fuse(6, first, {}, targets) == w.field.fuse(6, second, {}, std::vector<TargetState>(targets.rbegin(), targets.rend())));
  // A different tick draws different noise.
  CHECK(w.field.detect(7, targets) != first);
}

#include "node/field_sensors/field_sensors.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "common/kalman.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/tiling.hpp"
#include "scenario/loader.hpp"
#include "supernode/sbmht/measurement_models.hpp"

namespace wsn::node::field_sensors {
namespace {

using common::TargetState;
using common::Vec2;
using std::numbers::pi;

/// Every type with its defaults, as a scenario without sensor_model keys has them.
const FieldSensorsSettings& defaults() {
  static const FieldSensorsSettings settings;
  return settings;
}

/// One listed sensor of type `type` at `at`, heading `heading_deg`; zero fov, range and height
/// take the type's defaults. No localisation error, so the believed position is `at`.
FieldSensor placed(const std::string& type, Vec2 at, double heading_deg, double fov_deg = 0.0, double range = 0.0,
                   double height = 0.0) {
  common::SensorFieldConfig field;
  field.region = {-2000.0, -2000.0, 2000.0, 2000.0};
  field.sensors.kind = common::SensorLayoutConfig::Kind::kList;
  common::PlacedSensorConfig sensor;
  sensor.name = "s";
  sensor.type = type;
  sensor.position = at;
  sensor.heading_deg = heading_deg;
  sensor.fov_deg = fov_deg;
  sensor.range = range;
  sensor.height = height;
  field.sensors.list = {sensor};
  field.sensing_range = 100.0;
  return fieldSensorOf(common::SensorLayout(field), 0, defaults());
}

/// A target at distance rho and bearing theta (radians, field frame) from `from`, moving at
/// `speed` per tick along +y.
TargetState at(Vec2 from, double rho, double theta, double speed = 1.0) {
  return {7, from.x + rho * std::cos(theta), from.y + rho * std::sin(theta), 0.0, speed};
}

bool sees(const FieldSensor& sensor, const TargetState& target, double min_speed = 0.5) {
  return covers(sensor, target, min_speed);
}

TEST_CASE("every type covers a target within its range and misses one beyond it", "[field_sensors]") {
  // Ranges are the types' defaults (spec §1 PROP, Table I): 200, 200, 2, 200, 1000, 200. Along the
  // heading a target is inside every field of view; range is inclusive.
  const Vec2 o{10.0, -20.0};
  for (const auto& type : sensorTypes()) {
    const std::string name(type->name());
    INFO(name);
    const FieldSensor s = placed(name, o, 30.0);
    const double r = type->defaults().range;
    const double heading = pi / 6.0;
    CHECK(sees(s, at(o, 0.5 * r, heading)));
    CHECK(sees(s, at(o, r * (1.0 - 1e-12), heading)));
    CHECK_FALSE(sees(s, at(o, r * 1.001, heading)));
  }
}

TEST_CASE("a sector sensor covers its field of view up to the edges and nothing behind it", "[field_sensors]") {
  // Radar: 90° sector centred on a heading of 120°, so bearings 75° to 165° are inside.
  const Vec2 o{0.0, 0.0};
  const FieldSensor radar = placed("radar", o, 120.0);
  CHECK(radar.fov == Approx(pi / 2.0).margin(1e-15));
  CHECK(sees(radar, at(o, 500.0, (120.0 - 44.999) * pi / 180.0)));
  CHECK(sees(radar, at(o, 500.0, (120.0 + 44.999) * pi / 180.0)));
  CHECK_FALSE(sees(radar, at(o, 500.0, (120.0 - 45.01) * pi / 180.0)));
  CHECK_FALSE(sees(radar, at(o, 500.0, (120.0 + 45.01) * pi / 180.0)));
  CHECK_FALSE(sees(radar, at(o, 500.0, (120.0 + 180.0) * pi / 180.0)));  // behind
  // A PIR's 10° beam heading 180°: its edges straddle the ±π wrap, at 175° and -175°.
  const FieldSensor pir = placed("pir", o, 180.0);
  CHECK(sees(pir, at(o, 100.0, 176.0 * pi / 180.0)));
  CHECK(sees(pir, at(o, 100.0, -176.0 * pi / 180.0)));
  CHECK_FALSE(sees(pir, at(o, 100.0, -174.0 * pi / 180.0)));
  CHECK_FALSE(sees(pir, at(o, 100.0, 0.0)));  // behind
  // A camera given its own 40° field of view and 150 m range: ±20° about a heading of -90°.
  const FieldSensor camera = placed("camera", o, -90.0, 40.0, 150.0);
  CHECK(sees(camera, at(o, 149.0, -71.0 * pi / 180.0)));
  CHECK_FALSE(sees(camera, at(o, 149.0, -69.0 * pi / 180.0)));
  CHECK_FALSE(sees(camera, at(o, 151.0, -90.0 * pi / 180.0)));
  // All-round types see behind them.
  for (const char* type : {"acoustic_antenna", "acoustic_beacon", "magnetic"}) {
    INFO(type);
    const FieldSensor s = placed(type, o, 0.0);
    CHECK(sees(s, at(o, 1.0, pi)));
    CHECK(sees(s, at(o, 1.0, -pi / 2.0)));
  }
}

TEST_CASE("no type detects a target slower than min_speed, presence types included", "[field_sensors]") {
  // Spec eq. 9's assumption, v_min = 0.5 per tick: 0.5 is detectable, 0.49 is not.
  const Vec2 o{0.0, 0.0};
  for (const auto& type : sensorTypes()) {
    const std::string name(type->name());
    INFO(name);
    const FieldSensor s = placed(name, o, 0.0);
    CHECK(sees(s, at(o, 1.0, 0.0, 0.5)));
    CHECK_FALSE(sees(s, at(o, 1.0, 0.0, 0.49)));
    CHECK(sees(s, at(o, 1.0, 0.0, 0.49), 0.4));  // min_speed overridden
  }
}

/// The sbmht engine's h(x) for the measurement a sensor's report would carry.
supernode::sbmht::MeasurementVector engineSees(const FieldSensor& s, const TargetState& t) {
  const common::Measurement m{s.type->kind(), s.type->measure(s, viewOf(s, t)), s.type->noise(s), s.pose, {}};
  const auto model = supernode::sbmht::modelOf(m);  // the mast height comes with the pose
  REQUIRE(model.has_value());
  common::StateVector x;
  x << t.x, t.y, t.vx, t.vy;
  return model->predict(x);
}

TEST_CASE("noise-free measurements equal the sbmht engine's h(x)", "[field_sensors]") {
  // Targets chosen so that bearings fall on both sides of the heading and across ±π.
  const Vec2 o{100.0, 50.0};
  struct Case {
    const char* type;
    double heading_deg;
    TargetState target;
  };
  const std::vector<Case> cases = {
      {"acoustic_antenna", 0.0, {1, 60.0, 51.0, 0.7, -0.4}},    // bearing just below +π
      {"acoustic_antenna", 170.0, {1, 60.0, 49.0, 0.7, -0.4}},  // just above -π in the field frame
      {"pir", -30.0, {2, 180.0, 0.0, 1.0, 1.0}},
      {"radar", 45.0, {3, 400.0, 300.0, -3.0, 2.5}},
      {"camera", 90.0, {4, 110.0, 180.0, 1.5, 0.2}},
  };
  for (const auto& c : cases) {
    INFO(c.type << " heading " << c.heading_deg);
    const FieldSensor s = placed(c.type, o, c.heading_deg);
    const std::vector<double> h = s.type->measure(s, viewOf(s, c.target));
    const auto engine = engineSees(s, c.target);
    REQUIRE(static_cast<std::size_t>(engine.size()) == h.size());
    for (std::size_t i = 0; i < h.size(); ++i) CHECK(h[i] == engine(static_cast<Eigen::Index>(i)));
    for (const double v : h) CHECK(std::isfinite(v));
  }
  // Camera on a 3 m mast (its default), target 100 m away: phi = atan2(-3, 100) = -0.029991 rad.
  const FieldSensor camera = placed("camera", {0.0, 0.0}, 0.0);
  CHECK(camera.type->measure(camera, viewOf(camera, {1, 100.0, 0.0, 1.0, 0.0}))[1] ==
        Approx(-0.0299910048).margin(1e-9));
  // Presence types measure their own (believed) position, ONERA's h_mag, whatever the target.
  for (const char* type : {"magnetic", "acoustic_beacon"}) {
    const FieldSensor s = placed(type, o, 0.0);
    CHECK(s.type->measure(s, viewOf(s, {1, 101.0, 50.5, 1.0, 0.0})) == std::vector<double>{100.0, 50.0});
  }
}

TEST_CASE("each type's R is the spec's proposed noise", "[field_sensors]") {
  const auto deg = [](double d) { return d * pi / 180.0; };
  const FieldSensor antenna = placed("acoustic_antenna", {0, 0}, 0.0);
  CHECK(antenna.type->noise(antenna)[0] == Approx(deg(3.0) * deg(3.0)));  // σθ 3°
  // PIR: σθ = fov / √12, so R = fov² / 12; for its default 10° beam σθ = 2.887°.
  const FieldSensor pir = placed("pir", {0, 0}, 0.0);
  CHECK(std::sqrt(pir.type->noise(pir)[0]) * 180.0 / pi == Approx(2.88675).margin(1e-5));
  // Radar: diag(5², (1°)², 0.3²).
  const FieldSensor radar = placed("radar", {0, 0}, 0.0);
  const auto r = radar.type->noise(radar);
  REQUIRE(r.size() == 9);
  CHECK(r[0] == Approx(25.0));
  CHECK(r[4] == Approx(deg(1.0) * deg(1.0)));
  CHECK(r[8] == Approx(0.09));
  CHECK(r[1] == 0.0);
  // Beacon: R = (range/2)² I, 100² for the default 200 m; magnetic: 1 m² I.
  const FieldSensor beacon = placed("acoustic_beacon", {0, 0}, 0.0);
  CHECK(beacon.type->noise(beacon) == std::vector<double>{1e4, 0.0, 0.0, 1e4});
  const FieldSensor magnetic = placed("magnetic", {0, 0}, 0.0);
  CHECK(magnetic.type->noise(magnetic) == std::vector<double>{1.0, 0.0, 0.0, 1.0});
  // Camera: diag((0.1°)², (0.1°)²).
  const FieldSensor camera = placed("camera", {0, 0}, 0.0);
  CHECK(camera.type->noise(camera)[0] == Approx(deg(0.1) * deg(0.1)));
  CHECK(camera.type->noise(camera)[3] == Approx(deg(0.1) * deg(0.1)));
}

/// A 2000 x 2000 m field with the given sensors lines and targets lines (YAML list items).
common::Scenario field(const std::string& sensors, const std::string& targets, const std::string& model = "",
                       int node_processes = 1, const std::string& terrain = "") {
  return scenario::parseScenario(
      "region: {x_min: -1000, y_min: -1000, x_max: 1000, y_max: 1000}\n" + terrain +
          "sensors:\n  layout: list\n  list:\n" + sensors +
          "sensor_model:\n  kind: field_sensors\n  sensing_range: 100\n" + model +
          "dynamics: {delta: 1, process_noise_sigma: 0}\n"
          "targets:\n  scripted:\n" + targets +
          "run: {ticks: 300, node_processes: " + std::to_string(node_processes) + "}\n",
      "field_sensors_test.yaml");
}

/// The reports of every tile of an n-tile split at `tick`, in sensor order.
std::vector<common::Report> reportsAt(const common::Scenario& s, int tiles, std::int32_t tick) {
  const common::SensorLayout layout(common::sensorFieldConfig(s));
  const common::Truth truth(common::truthConfig(s));
  const auto& settings = common::settingsOf<FieldSensorsSettings>(s.sensor_model);
  std::vector<common::Report> all;
  for (const auto& tile : makeTiles(layout, tiles)) {
    const FieldSensors sensors(settings, s.run.seed, layout, tile, truth, s.terrain);
    const auto reports = sensors.detect(tick);
    all.insert(all.end(), reports.begin(), reports.end());
  }
  std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.sensor < b.sensor; });
  return all;
}

TEST_CASE("a report carries its measurement, R and pose, at the sensor's believed position", "[field_sensors]") {
  // PD 1 and no false alarms: a target 300 m east of the radar, inside its 90° sector heading 0.
  const auto s = field("    - {name: r, type: radar, x: 0, y: 0, heading: 0}\n",
                       "    - {appear_tick: 1, x: 300, y: 0, vx: -2, vy: 0}\n",
                       "  radar: {detection_probability: 1, false_alarms_per_tick: 0}\n");
  const auto reports = reportsAt(s, 1, 1);
  REQUIRE(reports.size() == 1);
  const common::Report& r = reports.front();
  CHECK(r.target == 0);
  CHECK(r.x == 0.0);
  CHECK(r.y == 0.0);
  CHECK(common::wellFormed(r));
  REQUIRE(r.measurement);
  CHECK(r.measurement->kind == common::MeasurementKind::range_bearing_rate);
  CHECK(r.measurement->sensor == common::SensorPose{0.0, 0.0, 0.0});
  CHECK(r.measurement->noise.size() == 9);
  CHECK(r.measurement->class_likelihoods.empty());
  // rho = 300 ± a few σρ = 5; theta ≈ 0 within a few degrees; rho_dot = -2 ± a few 0.3.
  CHECK(r.measurement->values[0] == Approx(300.0).margin(25.0));
  CHECK(r.measurement->values[1] == Approx(0.0).margin(5.0 * pi / 180.0));
  CHECK(r.measurement->values[2] == Approx(-2.0).margin(1.5));
  // No false alarms configured: the floor of one per 100 ticks over the radar's space, range 1000 x
  // sector pi/2 x range rates 2 x 20: 0.01 / 62831.85 = 1.5915e-7.
  CHECK(r.measurement->clutter_density == Approx(0.01 / (1000.0 * (pi / 2.0) * 40.0)));
}

TEST_CASE("a camera's report carries its mast height and its clutter density per steradian of view",
          "[field_sensors]") {
  // Camera 4 m up, heading 0, fov 40 deg, range 250, PD 1, 0.01 false alarms a tick (the default):
  // its false alarms fall uniformly over theta in +-20 deg and phi in [-90 deg, atan2(-4, 250)], so
  // the density is 0.01 / (0.69813 x (1.57080 - 0.01600)) = 0.01 / 1.08547 = 9.2126e-3.
  const auto s = field("    - {name: c, type: camera, x: 0, y: 0, heading: 0, fov: 40, range: 250, height: 4}\n",
                       "    - {appear_tick: 1, x: 100, y: 0, vx: 2, vy: 0}\n",
                       "  camera: {detection_probability: 1}\n");
  for (const auto& r : reportsAt(s, 1, 1)) {
    if (r.target != 0) continue;
    REQUIRE(r.measurement);
    CHECK(r.measurement->sensor == common::SensorPose{0.0, 0.0, 0.0, 4.0});
    CHECK(r.measurement->clutter_density == Approx(9.2126e-3).epsilon(1e-4));
    return;
  }
  FAIL("the camera did not report the target");
}

TEST_CASE("a radar whose false alarms have no range rates is refused at load", "[field_sensors]") {
  // max_range_rate 0 would give its false alarms no volume, so an infinite clutter density that
  // the wire refuses mid-run: the loader names the key and the line instead.
  CHECK_THROWS_WITH(field("    - {name: r, type: radar, x: 0, y: 0}\n", "    []\n", "  radar: {max_range_rate: 0}\n"),
                    Catch::Contains("field_sensors_test.yaml:") && Catch::Contains("max_range_rate"));
}

TEST_CASE("detections follow PD over many ticks", "[field_sensors]") {
  // An antenna at the origin (range 200, all round) and a target along y = 10 from x = -149 at
  // 1 per tick: |x| < 151 over ticks 1..300, always covered. Expected 0.8 x 300 = 240 reports, σ =
  // sqrt(300 x 0.8 x 0.2) = 6.9; accept ±25 (3.6 σ). No false alarms, to count detections only.
  const auto s = field("    - {name: a, type: acoustic_antenna, x: 0, y: 0}\n",
                       "    - {appear_tick: 1, x: -149, y: 10, vx: 1, vy: 0}\n",
                       "  acoustic_antenna: {false_alarms_per_tick: 0}\n");
  int detections = 0;
  for (std::int32_t t = 1; t <= 300; ++t) detections += static_cast<int>(reportsAt(s, 1, t).size());
  CHECK(std::abs(detections - 240) <= 25);
}

TEST_CASE("false alarms come at the proposed rate and within the coverage", "[field_sensors]") {
  // No targets. Poisson false alarms per sensor and tick: radar 0.2, antenna, camera and beacon
  // 0.01, PIR and magnetic none. Over N = 20000 ticks the expected counts are 4000 (σ = 63) and
  // 200 (σ = 14): accept 4000 ± 250 and 200 ± 50, about 4 σ.
  const auto s = field(
      "    - {name: r, type: radar, x: 0, y: 0, heading: 90}\n"
      "    - {name: a, type: acoustic_antenna, x: 500, y: 0}\n"
      "    - {name: c, type: camera, x: -500, y: 0, heading: 0}\n"
      "    - {name: p, type: pir, x: 0, y: 500}\n"
      "    - {name: m, type: magnetic, x: 0, y: -500}\n"
      "    - {name: b, type: acoustic_beacon, x: 300, y: -300}\n",
      "    []\n");
  const common::SensorLayout layout(common::sensorFieldConfig(s));
  const common::Truth truth(common::truthConfig(s));
  const FieldSensors sensors(common::settingsOf<FieldSensorsSettings>(s.sensor_model), 1, layout,
                             makeTiles(layout, 1).front(), truth);
  constexpr int kTicks = 20000;
  std::vector<int> count(6, 0);
  for (std::int32_t t = 1; t <= kTicks; ++t)
    for (const auto& r : sensors.detect(t)) {
      ++count[r.sensor];
      CHECK(r.target == common::kFalseAlarm);
      const auto& z = r.measurement->values;
      if (r.sensor == 0) {  // radar: rho in [0, 1000), theta within ±45°, rho_dot within ±20
        CHECK((z[0] >= 0.0 && z[0] < 1000.0));
        CHECK(std::abs(z[1]) <= pi / 4.0);
        CHECK(std::abs(z[2]) <= 20.0);
      }
      if (r.sensor == 5) {  // beacon: a presence at the sensor itself
        CHECK(z == std::vector<double>{300.0, -300.0});
        CHECK((r.x == 300.0 && r.y == -300.0));
      }
      if (r.sensor == 2) {  // camera: theta within ±15°, phi between -90° and atan2(-3, 200)
        CHECK(std::abs(z[0]) <= 15.0 * pi / 180.0);
        CHECK((z[1] >= -pi / 2.0 && z[1] <= std::atan2(-3.0, 200.0)));
      }
    }
  CHECK(std::abs(count[0] - 4000) <= 250);
  CHECK(std::abs(count[1] - 200) <= 50);
  CHECK(std::abs(count[2] - 200) <= 50);
  CHECK(count[3] == 0);
  CHECK(count[4] == 0);
  CHECK(std::abs(count[5] - 200) <= 50);
}

TEST_CASE("the field sensors' reports do not depend on the tiling", "[field_sensors]") {
  // Cells of 2 Rs = 200 m over 2000 m: 10 x 10 cells, split into 1 and 4 tiles.
  const auto s = field(
      "    - {name: r, type: radar, x: -600, y: -600, heading: 45}\n"
      "    - {name: a1, type: acoustic_antenna, x: 300, y: 300}\n"
      "    - {name: a2, type: acoustic_antenna, x: -300, y: 300}\n"
      "    - {name: b, type: acoustic_beacon, x: 0, y: 0}\n"
      "    - {name: c, type: camera, x: 600, y: -600, heading: 135, fov: 50, range: 400, height: 5}\n"
      "    - {name: p, type: pir, x: -100, y: -100, heading: 45, fov: 20}\n"
      "    - {name: m, type: magnetic, x: 1, y: 1}\n",
      "    - {appear_tick: 1, x: -400, y: -400, vx: 3, vy: 3}\n"
      "    - {appear_tick: 5, x: 400, y: -300, vx: -2, vy: 1}\n",
      "", 4);
  std::size_t total = 0;
  for (std::int32_t t = 1; t <= 200; ++t) {
    const auto one = reportsAt(s, 1, t);
    INFO("tick " << t);
    CHECK(one == reportsAt(s, 4, t));
    total += one.size();
  }
  CHECK(total > 200);  // the comparison is not vacuous
}

TEST_CASE("masks hide targets from the sensors whose sight they block, as the coverage says", "[field_sensors]") {
  // Four sensors at the origin seeing all round to 1000 m, PD 1, no false alarms. A house hides the
  // target east of them, a wood the one north, the one west is in the open. A camera or PIR sees
  // only the open target, the radar sees through the wood, the acoustic antenna hears all three.
  const std::string all_round = "heading: 0, fov: 360, range: 1000";
  const auto s = field("    - {name: cam, type: camera, x: 0, y: 0, " + all_round + ", height: 5}\n"
                       "    - {name: pir, type: pir, x: 0, y: 0, " + all_round + "}\n"
                       "    - {name: radar, type: radar, x: 0, y: 0, " + all_round + "}\n"
                       "    - {name: ant, type: acoustic_antenna, x: 0, y: 0, " + all_round + "}\n",
                       "    - {appear_tick: 1, x: 300, y: 0, vx: 0, vy: 2}\n"
                       "    - {appear_tick: 1, x: 0, y: 300, vx: 2, vy: 0}\n"
                       "    - {appear_tick: 1, x: -300, y: 0, vx: 0, vy: 2}\n",
                       "  camera: {detection_probability: 1, false_alarms_per_tick: 0}\n"
                       "  pir: {detection_probability: 1, false_alarms_per_tick: 0}\n"
                       "  radar: {detection_probability: 1, false_alarms_per_tick: 0}\n"
                       "  acoustic_antenna: {detection_probability: 1, false_alarms_per_tick: 0}\n",
                       1,
                       "terrain:\n  masks:\n"
                       "    - {name: house, kind: building, polygon: [[100, -20], [150, -20], [150, 20], [100, 20]]}\n"
                       "    - {name: wood, kind: vegetation, polygon: [[-20, 100], [20, 100], [20, 150], [-20, 150]]}\n");
  const auto reports = reportsAt(s, 1, 1);
  std::vector<std::vector<common::TargetId>> seen(4);
  for (const auto& r : reports) seen[r.sensor].push_back(r.target);
  CHECK(seen[0] == std::vector<common::TargetId>{2});
  CHECK(seen[1] == std::vector<common::TargetId>{2});
  CHECK(seen[2] == std::vector<common::TargetId>{1, 2});
  CHECK(seen[3] == std::vector<common::TargetId>{0, 1, 2});

  // The coverage the trackers get agrees with what the sensors did, target by target.
  const auto coverage = common::settingsOf<FieldSensorsSettings>(s.sensor_model).coverage(s);
  REQUIRE(coverage.size() == 4);
  const common::Terrain terrain(s.terrain);
  const common::Truth truth(common::truthConfig(s));
  for (const auto& sensor : coverage) {
    CHECK(sensor.detection_probability == 1.0);
    for (const auto& target : truth.at(1)) {
      const bool reported = std::count(seen[sensor.sensor].begin(), seen[sensor.sensor].end(), target.id) == 1;
      INFO("sensor " << sensor.sensor << " target " << target.id);
      CHECK((common::detectionProbabilityAt(sensor, {target.x, target.y}, &terrain) > 0.0) == reported);
    }
  }
}

}  // namespace
}  // namespace wsn::node::field_sensors

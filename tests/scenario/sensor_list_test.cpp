// The `list` sensor layout of the scenario loader: individually placed, typed sensors (ONERA
// Table I), their rules and their round trip through the resolved scenario.yaml.
#include <catch2/catch.hpp>

#include <numbers>
#include <string>

#include "common/sensor_layout.hpp"
#include "scenario/writer.hpp"
#include "tests/scenario/test_support.hpp"

namespace wsn::scenario {
namespace {

using namespace common;

/// A valid list scenario; line numbers below count from 1 in this text.
const std::string kSensorLines[] = {
    "    - {name: a1, type: acoustic_antenna, x: 100, y: 100}\n",                                   // line 5
    "    - {name: r1, type: radar, x: 500, y: 500, heading: 90, fov: 90, range: 800}\n",            // line 6
    "    - {name: c1, type: camera, x: 200, y: 800, heading: -45, fov: 30, range: 150, height: 4}\n",  // line 7
};

/// The scenario with sensor line 5 + i replaced by `replacement` (none when i < 0).
std::string listScenario(int i = -1, const std::string& replacement = "", const std::string& model = "field_sensors") {
  std::string sensors;
  for (int k = 0; k < 3; ++k) sensors += k == i ? replacement : kSensorLines[k];
  return "region: {x_min: 0, y_min: 0, x_max: 1000, y_max: 1000}\n"  // 1
         "sensors:\n"                                                   // 2
         "  layout: list\n"                                             // 3
         "  list:\n" +                                                  // 4
         sensors +                                                      // 5-7
         "sensor_model: {kind: " + model + ", sensing_range: 100}\n"    // 8
         "run: {ticks: 10, node_processes: 1}\n"                        // 9
         "supernodes: [{x: 500, y: 500}]\n";  // given, so that the resolved file derives nothing
}

using test_support::errorOf;

TEST_CASE("a list layout places each sensor with its type, pose and coverage", "[scenario][sensor_list]") {
  const Scenario s = parseScenario(listScenario(), "s.yaml");
  REQUIRE(s.sensors.kind == SensorLayoutConfig::Kind::kList);
  REQUIRE(s.sensors.list.size() == 3);
  CHECK(s.sensors.count == 3);  // a list's count is its length
  const PlacedSensorConfig& radar = s.sensors.list[1];
  CHECK(radar.name == "r1");
  CHECK(radar.type == "radar");
  CHECK(radar.position == Vec2{500.0, 500.0});
  CHECK(radar.heading_deg == 90.0);  // degrees as in the file
  CHECK(s.sensors.list[0].fov_deg == 0.0);  // left out: the type's default

  // The layout holds radians: heading 90° = π/2, fov 30° = π/6.
  const SensorLayout layout(sensorFieldConfig(s));
  REQUIRE(layout.hasPlacedSensors());
  REQUIRE(layout.size() == 3);
  CHECK(layout.truePosition(2) == Vec2{200.0, 800.0});
  CHECK(layout.placedSensor(1).heading == Approx(std::numbers::pi / 2.0));
  CHECK(layout.placedSensor(2).fov == Approx(std::numbers::pi / 6.0));
  CHECK(layout.placedSensor(2).heading == Approx(-std::numbers::pi / 4.0));
  CHECK(layout.placedSensor(2).height == 4.0);
  CHECK(layout.placedSensor(2).type == "camera");
}

TEST_CASE("a list scenario written out reads back equal", "[scenario][sensor_list]") {
  const Scenario s = parseScenario(listScenario(), "s.yaml");
  const std::string yaml = resolvedScenarioYaml(s);
  CHECK(yaml.find("  list:\n    - {name: \"a1\", type: \"acoustic_antenna\", x: 100, y: 100, heading: 0}\n") !=
        std::string::npos);
  const Scenario back = parseScenario(yaml, "resolved.yaml");
  CHECK(back == s);
  CHECK(resolvedScenarioYaml(back) == yaml);
}

TEST_CASE("grid and random layouts neither hold nor write a list", "[scenario][sensor_list]") {
  for (const char* layout : {"grid", "random"}) {
    INFO(layout);
    const Scenario s = parseScenario(std::string("sensors: {layout: ") + layout + "}\n", "s.yaml");
    CHECK(s.sensors.list.empty());
    CHECK(resolvedScenarioYaml(s).find("list") == std::string::npos);
    CHECK_FALSE(SensorLayout(sensorFieldConfig(s)).hasPlacedSensors());
  }
}

TEST_CASE("a listed sensor of a type the model lacks is rejected at its type", "[scenario][sensor_list]") {
  CHECK(errorOf(listScenario(1, "    - {name: r1, type: sonar, x: 500, y: 500}\n")) ==
        "s.yaml:6: 'sensors.list[1].type' must be one of: acoustic_antenna, acoustic_beacon, magnetic, pir, radar, "
        "camera; got 'sonar'");
}

TEST_CASE("a listed sensor's field of view must be above 0 and at most 360 degrees", "[scenario][sensor_list]") {
  CHECK(errorOf(listScenario(1, "    - {name: r1, type: radar, x: 500, y: 500, fov: 0}\n")) ==
        "s.yaml:6: 'sensors.list[1].fov' must be in (0, 360], got 0");
  CHECK(errorOf(listScenario(2, "    - {name: c1, type: camera, x: 200, y: 800, fov: 361}\n")) ==
        "s.yaml:7: 'sensors.list[2].fov' must be in (0, 360], got 361");
  CHECK(errorOf(listScenario(2, "    - {name: c1, type: camera, x: 200, y: 800, fov: 360}\n")).empty());
}

TEST_CASE("a listed sensor's range must not be negative", "[scenario][sensor_list]") {
  CHECK(errorOf(listScenario(0, "    - {name: a1, type: acoustic_antenna, x: 100, y: 100, range: -1}\n")) ==
        "s.yaml:5: 'sensors.list[0].range' must be in [0, 1e6], got -1");
}

TEST_CASE("a listed sensor outside the region is rejected at its item", "[scenario][sensor_list]") {
  CHECK(errorOf(listScenario(2, "    - {name: c1, type: camera, x: 200, y: 1000.5}\n")) ==
        "s.yaml:7: 'sensors.list[2]' at (200, 1000.5) is outside the region [0, 1000] x [0, 1000]");
}

TEST_CASE("two listed sensors of one name are rejected at the second", "[scenario][sensor_list]") {
  CHECK(errorOf(listScenario(2, "    - {name: a1, type: camera, x: 200, y: 800}\n")) ==
        "s.yaml:7: 'sensors.list[2].name' 'a1' is already the name of the sensor on line 5; expected names that "
        "differ");
}

TEST_CASE("a listed sensor needs a name, a type and a position", "[scenario][sensor_list]") {
  CHECK(errorOf(listScenario(0, "    - {name: a1, x: 100, y: 100}\n")) ==
        "s.yaml:5: 'sensors.list[0]' needs 'type' (every listed sensor has a name, a type and a position)");
}

TEST_CASE("a list layout and the sensor model must both have sensor types", "[scenario][sensor_list]") {
  // A model without types (signal strength) takes no list; one with types needs one.
  CHECK(errorOf(listScenario(-1, "", "signal_strength")) ==
        "s.yaml:3: 'sensors.layout: list' places typed sensors, but 'sensor_model.kind: signal_strength' has no "
        "sensor types; expected a grid or random layout, or a model with types");
  CHECK(errorOf("sensors: {layout: grid, spacing: 100}\n"
                "sensor_model:\n  kind: field_sensors\n  sensing_range: 100\n") ==
        "s.yaml:3: 'sensor_model.kind: field_sensors' places sensors of types acoustic_antenna, acoustic_beacon, "
        "magnetic, pir, radar, camera one by one; expected 'sensors.layout: list'");
  CHECK(errorOf("sensors:\n  layout: grid\n  list: []\n") ==
        "s.yaml:3: 'sensors.list' applies only with 'sensors.layout: list'");
  CHECK(errorOf("sensors:\n  layout: list\n") ==
        "s.yaml:2: 'sensors.layout: list' needs 'sensors.list', a non-empty list of {name, type, x, y, heading, fov, "
        "range, height}");
}

}  // namespace
}  // namespace wsn::scenario

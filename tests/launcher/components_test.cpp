#include "launcher/components.hpp"

#include <catch2/catch.hpp>

#include "aggregator/association.hpp"
#include "aggregator/metric/metric.hpp"
#include "common/measurement.hpp"
#include "common/scenario.hpp"
#include "common/scenario_schema.hpp"
#include "node/sensor_model_registry.hpp"
#include "supernode/engine.hpp"

namespace wsn::launcher {
namespace {

TEST_CASE("wsntrack components lists every registered component of every kind", "[launcher][components]") {
  const std::string text = componentsText();
  std::size_t listed = 0;
  const auto require_listed = [&](const std::string& name) {
    INFO(name);
    CHECK(text.find("\n" + name + ": ") != std::string::npos);
    ++listed;
  };
  for (const auto& m : node::sensorModelRegistry()) require_listed(m.name);
  for (const auto& e : supernode::engineRegistry()) {
    require_listed(e.name);
    for (const auto& p : e.params) CHECK(text.find("  " + p.name) != std::string::npos);
  }
  for (const auto& a : aggregator::associationRegistry()) require_listed(a.name);
  for (const auto& m : aggregator::metricRegistry()) require_listed(m.name);
  CHECK(listed >= 2 + 3 + 2 + 5);  // today's: 2 sensor models, 3 engines, 2 associations, 5 metrics
}

TEST_CASE("components --names lists each registry's names in order, one per line", "[launcher][components]") {
  const auto names_of = [](const auto& registry) {
    std::string out;
    for (const auto& entry : registry) out += entry.name + "\n";
    return out;
  };
  CHECK(componentNames("engines") == names_of(supernode::engineRegistry()));
  CHECK(componentNames("associations") == names_of(aggregator::associationRegistry()));
  CHECK(componentNames("sensor-models") == names_of(node::sensorModelRegistry()));
  CHECK(componentNames("metrics") == names_of(aggregator::metricRegistry()));
  // The golden outputs take their engine list from here: sbmht must be on it.
  CHECK(componentNames("engines").find("sbmht\n") != std::string::npos);
  CHECK(componentKinds().size() == 4);
  CHECK_THROWS_WITH(componentNames("engine"),
                    Catch::Contains("sensor-models, engines, associations, metrics") && Catch::Contains("'engine'"));
}

TEST_CASE("every key a sensor model or metric reads is listed with its unit, default and range",
          "[launcher][components]") {
  const std::string text = componentsText();
  for (const auto& m : node::sensorModelRegistry())
    for (const auto& table : m.settings.key_tables())
      for (const auto& f : table.fields) {
        const std::string line = "  " + table.section + "." + f.key + (f.unit.empty() ? "" : " [" + f.unit + "]") +
                                 " (default " + f.default_text + ", range " + f.range_text + "): " + f.doc + "\n";
        INFO(m.name << ": " << line);
        CHECK(text.find(line) != std::string::npos);
      }
  // Two rows by hand: the signal-strength model's alpha (no unit) and a metric's setting.
  CHECK(text.find("  sensor_model.alpha (default 2, range (0, 100]): ") != std::string::npos);
  CHECK(text.find("  metrics.ospa_c [separations] (default 5, range (0, 1e6]): OSPA cut-off c") != std::string::npos);
  CHECK(text.find("  targets.scripted[].sensing_range [separations] (default `sensor_model.sensing_range`") !=
        std::string::npos);
}

TEST_CASE("the markdown tables cover every scenario section and every component's parameters",
          "[launcher][components]") {
  const std::string markdown = componentsMarkdown();
  for (const auto& [name, table] : common::schema::markdownTables()) {
    INFO(name);
    CHECK(markdown.find("<!-- table: " + name + " -->\n" + table + "<!-- end table -->") != std::string::npos);
  }
  for (const auto& e : supernode::engineRegistry())
    CHECK(markdown.find("<!-- table: tracker.params " + e.name + " -->") != std::string::npos);
  for (const auto& a : aggregator::associationRegistry())
    CHECK(markdown.find("<!-- table: aggregator.params " + a.name + " -->") != std::string::npos);
  for (const auto& m : node::sensorModelRegistry())
    for (const auto& table : m.settings.key_tables()) {
      INFO(table.marker);
      CHECK(markdown.find("<!-- table: " + table.marker + " -->\n" + common::config::markdownTable(table.fields) +
                          "<!-- end table -->") != std::string::npos);
    }
}

TEST_CASE("every measurement kind a sensor model reports is a known kind", "[launcher][components]") {
  // The fit check compares names, so a misspelt kind would pass validate and fail at run time.
  for (const auto& model : node::sensorModelRegistry()) {
    INFO(model.name);
    CHECK_FALSE(model.measurement_kinds.empty());
    for (const auto& kind : model.measurement_kinds) CHECK(common::measurementKindNamed(kind).has_value());
  }
}

TEST_CASE("a sensor model and an engine fit when the engine accepts every kind the model reports",
          "[launcher][components]") {
  common::Scenario s;
  for (const auto& e : supernode::engineRegistry()) {
    s.tracker.engine = e.name;
    INFO(e.name);
    CHECK_NOTHROW(checkComponentsFit(s));  // every engine today takes positions, every model reports them
  }
  s.tracker.engine = "kalman";
  s.source_path = "s.yaml";
  s.tracker.engine_line = 4;
  CHECK_THROWS_WITH(checkComponentsFit(s), Catch::Contains("s.yaml:4: unknown tracker engine 'kalman'"));
}

TEST_CASE("a model whose sensors differ by type fits an engine by the kinds its placed sensors report",
          "[launcher][components]") {
  // field_sensors reports positions from beacons and magnetic detectors, bearings from antennas:
  // gnn takes positions only, so the first scenario fits it and the second does not; sbmht takes both.
  const auto scenario = [](const std::string& second_type, const std::string& engine) {
    return common::parseScenario(
        "region: {x_min: 0, y_min: 0, x_max: 1000, y_max: 1000}\n"
        "sensors:\n  layout: list\n  list:\n"
        "    - {name: b, type: acoustic_beacon, x: 100, y: 100}\n"
        "    - {name: s, type: " + second_type + ", x: 200, y: 100}\n"
        "sensor_model: {kind: field_sensors, sensing_range: 100}\n"
        "tracker: {engine: " + engine + "}\n",
        "s.yaml");
  };
  CHECK_NOTHROW(checkComponentsFit(scenario("magnetic", "gnn")));
  CHECK_THROWS_WITH(checkComponentsFit(scenario("acoustic_antenna", "gnn")),
                    "s.yaml:8: engine 'gnn' takes position measurements, but sensor model 'field_sensors' reports "
                    "bearing");
  CHECK_NOTHROW(checkComponentsFit(scenario("acoustic_antenna", "sbmht")));
  CHECK_NOTHROW(checkComponentsFit(scenario("radar", "sbmht")));
}

TEST_CASE("an engine that lacks a kind the sensor model reports does not fit", "[launcher][components]") {
  CHECK(unacceptedKind({"position"}, {"position"}) == std::nullopt);
  CHECK(unacceptedKind({"position", "bearing"}, {"position"}) == "bearing");
  CHECK(unacceptedKind({"bearing"}, {"position", "bearing"}) == std::nullopt);
  CHECK(unacceptedKind({}, {"position"}) == std::nullopt);
}

}  // namespace
}  // namespace wsn::launcher

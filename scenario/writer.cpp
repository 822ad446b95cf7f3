// The resolved scenario.yaml: every section written from its field table (common/config/
// yaml_writer.hpp), the sensor model's own keys by its registry entry, and the lists whose items
// hold lists of points (waypoints, roads, masks) as one flow mapping per item.
#include "scenario/writer.hpp"

#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "common/config/yaml_writer.hpp"
#include "common/scenario_schema.hpp"
#include "common/sensor_layout.hpp"
#include "node/sensor_model_registry.hpp"
#include "scenario/faults_section.hpp"

namespace wsn::scenario {
namespace {

namespace config = common::config;
namespace schema = common::schema;
using common::EngineParam;
using common::Scenario;
using common::SensorLayoutConfig;
using common::TargetSpec;
using common::TerrainConfig;
using common::Vec2;
using config::FieldKind;
using config::FieldTable;
using config::keyText;
using config::writeFields;
using config::writeList;
using config::writeSection;
using config::yamlNumber;

/// tracker.params, aggregator.params: every parameter resolved, a derived one with how.
void writeParams(std::ostringstream& out, const std::string& section, const std::map<std::string, EngineParam>& params,
                 const std::map<std::string, std::string>& derived) {
  if (params.empty()) {
    out << "  params: {}\n";
    return;
  }
  out << "  params:\n";
  for (const auto& [name, param] : params) {
    out << "    " << keyText(name) << ": " << yamlNumber(param.value);
    if (const auto it = derived.find(section + "." + name); it != derived.end()) out << "  # derived: " << it->second;
    out << "\n";
  }
}

/// "[[x, y], ...]": a list of points as one flow sequence.
std::string pointsText(const std::vector<Vec2>& points) {
  std::string text;
  for (const Vec2 p : points) text += (text.empty() ? "[[" : ", [") + yamlNumber(p.x) + ", " + yamlNumber(p.y) + "]";
  return text + "]";
}

/// "{key: value, ...}" of a list item whose table has lists of points: `points_of` gives the
/// points of a nested key (null when it writes nothing), other nested keys are left to `extra`.
template <typename C, typename Points, typename Extra>
std::string itemText(const FieldTable<C>& table, const C& item, Points points_of, Extra extra) {
  std::string text;
  for (const auto& field : table.fields) {
    std::string value;
    if (field.kind == FieldKind::kNested) {
      if (const std::vector<Vec2>* points = points_of(field.key))
        value = pointsText(*points);
      else
        value = extra(field.key);
    } else if (!field.leftOutOfItem(item)) {
      value = field.yamlValue(item);
    }
    if (!value.empty()) text += (text.empty() ? "{" : ", ") + field.key + ": " + value;
  }
  return text + "}";
}

/// targets.scripted: as writeList writes it, but a waypoint target with its route in place of the
/// start and velocity it is derived into.
void writeScriptedTargets(std::ostringstream& out, const std::vector<TargetSpec>& targets) {
  if (targets.empty()) {
    out << "  scripted: []\n";
    return;
  }
  out << "  scripted:\n";
  for (const auto& target : targets) {
    if (target.waypoints.empty()) {
      out << "    - " << config::flowMapping(schema::scriptedTarget(), target) << "\n";
      continue;
    }
    const auto route_points = [&](const std::string& key) -> const std::vector<Vec2>* {
      return key == "waypoints" ? &target.waypoints : nullptr;
    };
    const auto other_lists = [&](const std::string& key) -> std::string {
      if (key == "speeds" && !target.speeds.empty()) {
        std::string text;
        for (const double v : target.speeds) text += (text.empty() ? "[" : ", ") + yamlNumber(v);
        return text + "]";
      }
      if (key != "stops" || target.stops.empty()) return "";
      std::string text;
      for (const auto& stop : target.stops)
        text += (text.empty() ? "[" : ", ") + config::flowMapping(schema::waypointStop(), stop);
      return text + "]";
    };
    FieldTable<TargetSpec> without_start = schema::scriptedTarget();
    std::erase_if(without_start.fields, [](const auto& field) {
      return field.key == "x" || field.key == "y" || field.key == "vx" || field.key == "vy";
    });
    out << "    - " << itemText(without_start, target, route_points, other_lists) << "\n";
  }
}

/// terrain: written only when the scenario has one, so that a scenario without it reads as before.
void writeTerrain(std::ostringstream& out, const TerrainConfig& terrain) {
  if (terrain.empty()) return;
  const auto nothing_else = [](const std::string&) { return std::string(); };
  out << "terrain:\n";
  out << "  roads:" << (terrain.roads.empty() ? " []" : "") << "\n";
  for (const auto& road : terrain.roads)
    out << "    - "
        << itemText(schema::road(), road, [&](const std::string&) { return &road.points; }, nothing_else) << "\n";
  out << "  masks:" << (terrain.masks.empty() ? " []" : "") << "\n";
  for (const auto& mask : terrain.masks)
    out << "    - "
        << itemText(schema::mask(), mask, [&](const std::string&) { return &mask.polygon; }, nothing_else) << "\n";
}

}  // namespace

std::string resolvedScenarioYaml(const Scenario& s) {
  std::ostringstream out;
  out << "# wsntrack resolved scenario: every parameter written out with defaults filled in.\n"
      << "# Loading this file gives the same scenario. '# derived:' marks a value the file left out\n"
      << "# and the loader computed from others.\n";
  writeFields(out, "", schema::topLevel(), s);
  writeSection(out, "region", schema::region(), s.region);
  if (s.sensors.kind == SensorLayoutConfig::Kind::kGrid) {
    // count is a random or list layout's key: a grid's size follows from the region and spacing,
    // and its default (10^4) written out would misstate it. The true size goes in a comment.
    writeSection(out, "sensors", schema::sensors(), s.sensors, {}, {"count"});
    const auto grid = common::gridShape(s.region, s.sensors.spacing);
    out << "  # grid of " << grid.columns << " x " << grid.rows << " = " << grid.sensors() << " sensors\n";
  } else {
    writeSection(out, "sensors", schema::sensors(), s.sensors);
  }
  if (s.sensors.kind == SensorLayoutConfig::Kind::kList)
    writeList(out, "  ", "list", schema::placedSensor(), s.sensors.list);
  writeSection(out, "sensor_model", schema::sensorModel(), s.sensor_model, s.derived);
  node::sensorModelRegistry().at(s.sensor_model.kind).settings.write(out, s);
  writeSection(out, "localisation", schema::localisation(), s.localisation);
  writeSection(out, "targets", schema::targets(), s.targets);
  writeScriptedTargets(out, s.targets.scripted);
  writeSection(out, "dynamics", schema::dynamics(), s.dynamics);
  const auto supernodes_derived = s.derived.find("supernodes");
  writeList(out, "", "supernodes", schema::supernode(), s.supernodes,
            supernodes_derived == s.derived.end() ? "" : supernodes_derived->second);
  writeTerrain(out, s.terrain);
  writeSection(out, "network", schema::network(), s.network);
  writeSection(out, "tracker", schema::tracker(), s.tracker);
  writeParams(out, "tracker.params", s.tracker.params, s.derived);
  writeSection(out, "aggregator", schema::aggregator(), s.aggregator);
  writeParams(out, "aggregator.params", s.aggregator.params, s.derived);
  writeSection(out, "metrics", schema::metrics(), s.metrics);
  writeSection(out, "run", schema::run(), s.run);
  out << faultsYaml(s.faults);
  return out.str();
}

}  // namespace wsn::scenario

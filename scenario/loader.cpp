// The strict YAML scenario loader (DESIGN principle 6): every key is known, every value has the
// expected type and lies in its range, and every problem is reported as "file:line: message"
// naming the dotted key and what was expected. The sections are read here, one reader each;
// the rules between keys of different sections are in rules.cpp.
#include "scenario/loader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/config/yaml_documents.hpp"
#include "common/config/yaml_reader.hpp"
#include "common/scenario_schema.hpp"
#include "common/terrain.hpp"
#include "node/sensor_model_registry.hpp"
#include "scenario/document.hpp"
#include "scenario/faults_section.hpp"
#include "scenario/rules.hpp"

namespace wsn::scenario {
namespace {

namespace config = common::config;
namespace schema = common::schema;
using common::EngineParam;
using common::Mask;
using common::PlacedSensorConfig;
using common::RoadLine;
using common::Scenario;
using common::ScenarioError;
using common::SensorLayoutConfig;
using common::TargetSpec;
using common::Vec2;
using common::WaypointStop;
using config::compactNumber;
using config::describe;
using config::Entry;
using config::forEachItem;
using config::lineOr;
using config::Range;
using config::Reader;
using config::Section;
using schema::kMaxCoordinate;
using schema::kMaxNameLength;
using schema::kMaxSensors;
using schema::kMaxSupernodes;

/// sensors.list: the items of a list layout (and none otherwise), each inside the region and
/// named apart from every other; `count` is the list's length.
void readSensorList(const Reader& r, const Section& sec, Scenario& s) {
  const Entry* list = sec.find("list");
  const bool given = list != nullptr && !list->value.IsNull();
  if (s.sensors.kind != SensorLayoutConfig::Kind::kList) {
    if (given) r.fail(Reader::lineOf(*list), "'sensors.list' applies only with 'sensors.layout: list'");
    return;
  }
  const std::string shape = "{name, type, x, y, heading, fov, range, height}";
  if (!given || !list->value.IsSequence() || list->value.size() == 0)
    r.fail(given ? Reader::lineOf(*list) : sec.line,
           "'sensors.layout: list' needs 'sensors.list', a non-empty list of " + shape +
               (given ? ", got " + describe(list->value) : std::string()));
  if (static_cast<double>(list->value.size()) > kMaxSensors)
    r.fail(Reader::lineOf(*list), "'sensors.list' holds " + std::to_string(list->value.size()) +
                                      " sensors; expected at most " + compactNumber(kMaxSensors));
  forEachItem(r, *list, "sensors.list", shape, [&](const YAML::Node& item, int line, auto& path) {
    const Section t = r.item(item, line, path, schema::placedSensor());
    r.require(t, {"name", "type", "x", "y"}, "every listed sensor has a name, a type and a position");
    PlacedSensorConfig sensor;
    r.fields(t, schema::placedSensor(), sensor);
    sensor.line = t.line;
    sensor.type_line = Reader::lineOf(*t.find("type"));
    const int name_line = Reader::lineOf(*t.find("name"));
    if (sensor.name.empty()) r.fail(name_line, "'" + path + ".name' must not be empty");
    for (const auto& earlier : s.sensors.list)
      if (earlier.name == sensor.name)
        r.fail(name_line, "'" + path + ".name' '" + sensor.name + "' is already the name of the sensor on line " +
                              std::to_string(earlier.line) + "; expected names that differ");
    if (!s.region.contains(sensor.position))
      r.fail(t.line, "'" + path + "' at " + pointText(sensor.position) + " is outside the region " +
                         regionText(s.region));
    s.sensors.list.push_back(sensor);
  });
  const auto length = static_cast<std::uint32_t>(s.sensors.list.size());
  if (const Entry* count = sec.find("count"); count != nullptr && s.sensors.count != length)
    r.fail(Reader::lineOf(*count), "'sensors.count' " + std::to_string(s.sensors.count) + " differs from the " +
                                       std::to_string(length) + " sensors of 'sensors.list'; leave count out");
  s.sensors.count = length;
}

/// The line of sensor_model.kind, else of the section, else `fallback`.
int sensorModelKindLine(const Section& top, int fallback) {
  const Entry* e = top.find("sensor_model");
  if (e == nullptr) return fallback;
  if (e->value.IsMap())
    for (const auto& pair : e->value)
      if (pair.first.IsScalar() && pair.first.Scalar() == "kind") return Reader::lineOf(pair.first);
  return Reader::lineOf(*e);
}

/// A list of points [[x, y], ...] with at least `fewest` items, each inside the region: a road's
/// centre line, a mask's outline, a target's waypoints. `what` names the list in messages.
std::vector<Vec2> readPoints(const Reader& r, const Scenario& s, const Entry& list, const std::string& path,
                             std::size_t fewest, const std::string& what) {
  const int list_line = Reader::lineOf(list);
  if (!list.value.IsSequence())
    r.fail(list_line, "'" + path + "' must be a list of [x, y] points, got " + describe(list.value));
  if (list.value.size() < fewest)
    r.fail(list_line, "'" + path + "' has " + std::to_string(list.value.size()) +
                          (list.value.size() == 1 ? " point; " : " points; ") + what + " needs at least " +
                          std::to_string(fewest));
  std::vector<Vec2> points;
  std::size_t i = 0;
  for (const auto& item : list.value) {
    const std::string item_path = path + "[" + std::to_string(i++) + "]";
    const int line = Reader::lineOf(item) > 0 ? Reader::lineOf(item) : list_line;
    if (!item.IsSequence() || item.size() != 2)
      r.fail(line, "'" + item_path + "' must be a point [x, y], got " + describe(item));
    const Entry x{item, item[0]};
    const Entry y{item, item[1]};
    constexpr Range kCoordinate = config::closed(-kMaxCoordinate, kMaxCoordinate);
    const Vec2 p{r.numberValue(x, item_path + "[0]", kCoordinate), r.numberValue(y, item_path + "[1]", kCoordinate)};
    if (!s.region.contains(p))
      r.fail(line, "'" + item_path + "' " + pointText(p) + " is outside the region " + regionText(s.region));
    points.push_back(p);
  }
  return points;
}

/// A params mapping (tracker.params, aggregator.params): any names, numbers only; the owning
/// component's table checks names and ranges (common/param_spec.hpp).
std::map<std::string, EngineParam> readParams(const Reader& r, const Entry& entry, const std::string& path) {
  std::map<std::string, EngineParam> params;
  const Section p = r.section(entry, path, {});
  for (const auto& [name, value] : p.entries) {
    // `auto` asks for the component's default, derived from the scenario where it has a physical
    // meaning: the same as leaving the key out, and a way for --set to undo a value the file sets.
    if (value.value.IsScalar() && value.value.Scalar() == "auto") {
      params[name] = EngineParam{0.0, Reader::lineOf(value.key), true};
      continue;
    }
    params[name] = EngineParam{r.anyNumber(value, p.pathOf(name)), Reader::lineOf(value.key)};
  }
  return params;
}

// ---------------------------------------------------------------------------------------------
// The scenario, section by section. Sections are read in a fixed order (region first) so that
// checks against the region do not depend on the order of keys in the file.

/// sensor_model: kind and sensing_range here, every other key by the chosen model's own spec
/// (node/<model>/config.hpp). A key of another model is named as such. Returns the model, and
/// through `sensing_range_line` the line to blame for Rs (kept when the file does not give it).
const node::SensorModelSpec& readSensorModel(const Reader& r, const Section& top, Scenario& s,
                                             int& sensing_range_line) {
  const auto& models = node::sensorModelRegistry();
  const Entry* e = top.find("sensor_model");
  if (e == nullptr) {
    const auto& model = models.at(s.sensor_model.kind);
    s.sensor_model.settings = model.settings.read(r, nullptr, s);
    return model;
  }
  const Section sec = r.section(*e, "sensor_model", {});  // keys checked below, once the kind is known
  r.fields(sec, schema::sensorModel(), s.sensor_model);
  sensing_range_line = lineOr(sec, "sensing_range", sensing_range_line);
  const node::SensorModelSpec* model = models.find(s.sensor_model.kind);
  if (model == nullptr)
    r.fail(lineOr(sec, "kind", sec.line),
           "'sensor_model.kind' must be one of: " + models.names() + "; got '" + s.sensor_model.kind + "'");
  std::vector<std::string> keys = schema::sensorModel().sortedKeys();
  keys.insert(keys.end(), model->settings.keys.begin(), model->settings.keys.end());
  std::sort(keys.begin(), keys.end());
  for (const auto& [key, entry] : sec.entries) {
    if (contains(keys, key)) continue;
    const std::vector<std::string> readers = modelsReading(key, &node::SensorModelSettingsSpec::keys);
    if (!readers.empty())
      r.fail(Reader::lineOf(entry.key), "'sensor_model." + key + "' applies only with " + kindsText(readers));
    r.fail(Reader::lineOf(entry.key), "unknown key '" + key + "' in 'sensor_model' of kind " + model->name +
                                          "; expected one of: " + config::join(keys));
  }
  s.sensor_model.settings = model->settings.read(r, &sec, s);
  return *model;
}

/// A waypoint target's route: its waypoints and stops, and from them where it starts and how it
/// first moves.
void readRoute(const Reader& r, const Scenario& s, const Section& t, const Entry& waypoints, TargetSpec& spec) {
  const std::string path = t.pathOf("waypoints");
  spec.waypoints = readPoints(r, s, waypoints, path, 2, "a route");
  noRepeatedPoint(r, spec.waypoints, waypoints, path);
  if (const Entry* stops = t.find("stops"); stops != nullptr && !stops->value.IsNull()) {
    const std::string stops_path = t.pathOf("stops");
    if (!stops->value.IsSequence())
      r.fail(Reader::lineOf(*stops), "'" + stops_path + "' must be a list of {at, ticks}, got " + describe(stops->value));
    forEachItem(r, *stops, stops_path, "{at, ticks}", [&](const YAML::Node& item, int line, auto& stop_path) {
      const Section stop_section = r.item(item, line, stop_path, schema::waypointStop());
      r.require(stop_section, {"at", "ticks"}, "the waypoint's number and how many ticks the target rests there");
      WaypointStop stop;
      r.fields(stop_section, schema::waypointStop(), stop);
      const int at_line = lineOr(stop_section, "at", line);
      if (static_cast<std::size_t>(stop.at) >= spec.waypoints.size())
        r.fail(at_line, "'" + stop_section.pathOf("at") + "' " + std::to_string(stop.at) + " is not a waypoint; expected 0 to " +
                            std::to_string(spec.waypoints.size() - 1));
      if (!spec.stops.empty() && stop.at <= spec.stops.back().at)
        r.fail(at_line, "'" + stop_section.pathOf("at") + "' " + std::to_string(stop.at) +
                            " must come after the previous stop's waypoint " + std::to_string(spec.stops.back().at) +
                            "; expected stops in route order, one per waypoint");
      spec.stops.push_back(stop);
    });
  }
  if (const Entry* speeds = t.find("speeds"); speeds != nullptr) {
    const std::string speeds_path = t.pathOf("speeds");
    const int line = Reader::lineOf(*speeds);
    if (!speeds->value.IsSequence())
      r.fail(line, "'" + speeds_path + "' must be a list of speeds, one per waypoint, got " + describe(speeds->value));
    if (speeds->value.size() != spec.waypoints.size())
      r.fail(line, "'" + speeds_path + "' has " + std::to_string(speeds->value.size()) + " speeds for " +
                       std::to_string(spec.waypoints.size()) + " waypoints; expected one per waypoint");
    for (std::size_t i = 0; i < speeds->value.size(); ++i) {
      const YAML::Node item = speeds->value[i];
      spec.speeds.push_back(r.numberValue(Entry{item, item}, speeds_path + "[" + std::to_string(i) + "]", config::kPositive));
    }
  }
  spec.position = spec.waypoints.front();
  const Vec2 leg = spec.waypoints[1] - spec.waypoints[0];
  const double first_speed = spec.speeds.empty() ? spec.speed : spec.speeds.front();
  spec.velocity = (first_speed / std::hypot(leg.x, leg.y)) * leg;
}

/// targets: the random births and the scripted list.
void readTargets(const Reader& r, const Section& top, const node::SensorModelSpec& model, Scenario& s) {
  if (const Entry* e = top.find("targets")) {
    const Section sec = r.section(*e, schema::targets());
    r.fields(sec, schema::targets(), s.targets);
    if (sec.find("birth_rate") != nullptr) birthsPerTickBounded(r, s, Reader::lineOf(*sec.find("birth_rate")));
    if (s.targets.lifetime_max < s.targets.lifetime_min) {
      const Entry* at = sec.find("lifetime_max") != nullptr ? sec.find("lifetime_max") : sec.find("lifetime_min");
      r.fail(Reader::lineOf(*at), "'targets.lifetime_max' " + std::to_string(s.targets.lifetime_max) +
                                      " is below 'targets.lifetime_min' " + std::to_string(s.targets.lifetime_min) +
                                      "; expected lifetime_min <= lifetime_max");
    }
    if (const Entry* scripted = sec.find("scripted"); scripted != nullptr && !scripted->value.IsNull()) {
      const std::string shape = "{appear_tick, disappear_tick, x, y, vx, vy}";
      if (!scripted->value.IsSequence())
        r.fail(Reader::lineOf(*scripted),
               "'targets.scripted' must be a list of " + shape + ", got " + describe(scripted->value));
      forEachItem(r, *scripted, "targets.scripted", shape, [&](const YAML::Node& item, int line, auto& path) {
        const Section t = r.item(item, line, path, schema::scriptedTarget());
        const Entry* waypoints = t.find("waypoints");
        if (waypoints == nullptr) {
          r.require(t, {"x", "y"}, "initial position, sensor separations");
          r.require(t, {"vx", "vy"}, "velocity, sensor separations per tick");
          for (const char* key : {"speed", "speeds", "stops"})
            if (const Entry* given = t.find(key))
              r.fail(Reader::lineOf(given->key), "'" + t.pathOf(key) + "' applies only with 'waypoints'");
        } else {
          for (const char* key : {"x", "y", "vx", "vy"})
            if (const Entry* given = t.find(key))
              r.fail(Reader::lineOf(given->key), "'" + t.pathOf(key) + "' does not apply with 'waypoints': the target " +
                                                 "starts at the first waypoint and moves at 'speed'");
          const Entry* speed = t.find("speed");
          const Entry* speeds = t.find("speeds");
          if (speed != nullptr && speeds != nullptr)
            r.fail(Reader::lineOf(speeds->key), "'" + t.pathOf("speeds") + "' and 'speed' both given; expected " +
                                                    "one speed for the route or one per waypoint, not both");
          if (speeds == nullptr) r.require(t, {"speed"}, "distance per tick along the waypoints (or 'speeds')");
        }
        TargetSpec spec;
        r.fields(t, schema::scriptedTarget(), spec);
        if (waypoints != nullptr) readRoute(r, s, t, *waypoints, spec);
        scriptedTargetIsValid(r, s, model, spec, t);
        s.targets.scripted.push_back(spec);
      });
    }
  }
  if (const Entry* e = top.find("targets"); e != nullptr && model.settings.check_targets)
    model.settings.check_targets(r, s, Reader::lineOf(*e));
}

/// supernodes: the listed ones, or one at the centre of the region.
void readSupernodes(const Reader& r, const Section& top, Scenario& s) {
  if (const Entry* e = top.find("supernodes"); e != nullptr && !e->value.IsNull()) {
    const int list_line = Reader::lineOf(*e);
    if (!e->value.IsSequence()) r.fail(list_line, "'supernodes' must be a list of {x, y}, got " + describe(e->value));
    if (e->value.size() == 0) r.fail(list_line, "'supernodes' must list at least one supernode");
    if (e->value.size() > kMaxSupernodes)
      r.fail(list_line, "'supernodes' lists " + std::to_string(e->value.size()) + " supernodes; expected at most " +
                            std::to_string(kMaxSupernodes));
    forEachItem(r, *e, "supernodes", "{x, y}", [&](const YAML::Node& item, int line, auto& path) {
      const Section sec = r.item(item, line, path, schema::supernode());
      r.require(sec, {"x", "y"}, "position, sensor separations");
      Vec2 p;
      r.fields(sec, schema::supernode(), p);
      supernodeIsPlaced(r, s, p, sec);
      s.supernodes.push_back(p);
    });
  } else {
    s.supernodes = {{0.5 * (s.region.x_min + s.region.x_max), 0.5 * (s.region.y_min + s.region.y_max)}};
    s.derived["supernodes"] = "one supernode at the centre of the region";
  }
}

/// terrain: the roads and the masks, each named, every point inside the region.
void readTerrain(const Reader& r, const Section& top, Scenario& s) {
  const Entry* e = top.find("terrain");
  if (e == nullptr) return;
  const Section sec = r.section(*e, schema::terrain());
  const auto list = [&](const char* key, const std::string& shape) -> const Entry* {
    const Entry* items = sec.find(key);
    if (items == nullptr || items->value.IsNull()) return nullptr;
    if (!items->value.IsSequence())
      r.fail(Reader::lineOf(*items), "'" + sec.pathOf(key) + "' must be a list of " + shape + ", got " + describe(items->value));
    return items;
  };
  if (const Entry* roads = list("roads", "{name, points}")) {
    forEachItem(r, *roads, "terrain.roads", "{name, points}", [&](const YAML::Node& item, int line, auto& path) {
      const Section t = r.item(item, line, path, schema::road());
      r.require(t, {"name", "points"}, "the road's name and centre line");
      RoadLine road;
      r.fields(t, schema::road(), road);
      nameIsNew(r, s.terrain.roads, road, t, "terrain.roads");
      road.points = readPoints(r, s, *t.find("points"), t.pathOf("points"), 2, "a road");
      noRepeatedPoint(r, road.points, *t.find("points"), t.pathOf("points"));
      s.terrain.roads.push_back(std::move(road));
    });
  }
  if (const Entry* masks = list("masks", "{name, kind, polygon}")) {
    forEachItem(r, *masks, "terrain.masks", "{name, kind, polygon}", [&](const YAML::Node& item, int line, auto& path) {
      const Section t = r.item(item, line, path, schema::mask());
      r.require(t, {"name", "kind", "polygon"}, "the mask's name, what it is made of and its outline");
      Mask mask;
      r.fields(t, schema::mask(), mask);
      nameIsNew(r, s.terrain.masks, mask, t, "terrain.masks");
      const Entry& polygon = *t.find("polygon");
      mask.polygon = readPoints(r, s, polygon, t.pathOf("polygon"), 3, "a polygon");
      if (!common::isSimplePolygon(mask.polygon))
        r.fail(Reader::lineOf(polygon), "'" + t.pathOf("polygon") +
                                            "' is not a simple polygon: its edges cross or fold back, or it has no "
                                            "area; expected an outline that goes round once");
      s.terrain.masks.push_back(std::move(mask));
    });
  }
}

/// tracker and aggregator: which components, and their parameters as written (the engine and
/// association registries check them against the chosen component's table).
void readComponentChoices(const Reader& r, const Section& top, Scenario& s) {
  if (const Entry* e = top.find("tracker")) {
    const Section sec = r.section(*e, schema::tracker());
    r.fields(sec, schema::tracker(), s.tracker);
    if (const Entry* engine = sec.find("engine")) {
      s.tracker.engine_line = Reader::lineOf(*engine);
      if (s.tracker.engine.empty()) r.fail(s.tracker.engine_line, "'tracker.engine' must name an engine, got ''");
    }
    if (const Entry* params = sec.find("params")) s.tracker.params = readParams(r, *params, "tracker.params");
  }
  if (const Entry* e = top.find("aggregator")) {
    const Section sec = r.section(*e, schema::aggregator());
    r.fields(sec, schema::aggregator(), s.aggregator);
    if (const Entry* association = sec.find("association")) {
      s.aggregator.association_line = Reader::lineOf(*association);
      if (s.aggregator.association.empty())
        r.fail(s.aggregator.association_line, "'aggregator.association' must name a method, got ''");
    }
    if (const Entry* params = sec.find("params")) s.aggregator.params = readParams(r, *params, "aggregator.params");
  }
}

Scenario readScenario(const YAML::Node& root, const std::string& file) {
  const Reader r(file);
  Scenario s;
  s.source_path = file;
  const Section top = r.section(root, 1, "", schema::sectionNames());

  if (const Entry* e = top.find("name")) {
    r.fields(top, schema::topLevel(), s);
    if (!validName(s.name))
      r.fail(Reader::lineOf(*e), "'name' must be 1 to " + std::to_string(kMaxNameLength) +
                                     " characters from A-Z a-z 0-9 _ - . (it names the run directory), got '" + s.name +
                                     "'");
  }

  int region_line = 1;
  if (const Entry* e = top.find("region")) {
    const Section sec = r.section(*e, schema::region());
    region_line = sec.line;
    r.fields(sec, schema::region(), s.region);
    regionIsOrdered(r, s.region, sec.line);
  }

  int layout_line = region_line;  // where a layout that does not fit the region is reported
  int list_line = region_line;    // where a list layout the sensor model cannot take is reported
  if (const Entry* e = top.find("sensors")) {
    const Section sec = r.section(*e, schema::sensors());
    r.fields(sec, schema::sensors(), s.sensors);
    layout_line = lineOr(sec, "spacing", layout_line);
    readSensorList(r, sec, s);
    list_line = lineOr(sec, "layout", sec.line);
  }
  gridFitsRegion(r, s, layout_line);

  int sensing_range_line = region_line;
  const node::SensorModelSpec& model = readSensorModel(r, top, s, sensing_range_line);
  sensorTypesFitModel(r, s, model, list_line, sensorModelKindLine(top, region_line));

  if (const Entry* e = top.find("localisation"))
    r.fields(r.section(*e, schema::localisation()), schema::localisation(), s.localisation);

  readTargets(r, top, model, s);
  if (const Entry* e = top.find("dynamics"))
    r.fields(r.section(*e, schema::dynamics()), schema::dynamics(), s.dynamics);

  readSupernodes(r, top, s);
  readTerrain(r, top, s);

  if (const Entry* e = top.find("network")) r.fields(r.section(*e, schema::network()), schema::network(), s.network);

  readComponentChoices(r, top, s);

  if (const Entry* e = top.find("metrics")) r.fields(r.section(*e, schema::metrics()), schema::metrics(), s.metrics);

  int node_processes_line = sensing_range_line;
  if (const Entry* e = top.find("run")) {
    const Section sec = r.section(*e, schema::run());
    r.fields(sec, schema::run(), s.run);
    node_processes_line = lineOr(sec, "node_processes", node_processes_line);
  }
  nodeProcessesFitCells(r, s, node_processes_line);
  readFaults(r, top, s);
  return s;
}

}  // namespace

YAML::Node parseScenarioDocument(const std::string& yaml_text, const std::string& name_for_errors) {
  common::config::YamlDocuments documents;
  try {
    documents = common::config::readYamlDocuments(yaml_text);
  } catch (const YAML::ParserException& error) {
    const int line = error.mark.is_null() ? 1 : error.mark.line + 1;
    throw ScenarioError(name_for_errors + ":" + std::to_string(line) + ": invalid YAML: " + error.msg);
  } catch (const YAML::Exception& error) {
    throw ScenarioError(name_for_errors + ":1: invalid YAML: " + error.msg);
  }
  if (documents.later_content_line > 0)
    throw ScenarioError(name_for_errors + ":" + std::to_string(documents.later_content_line) +
                        ": a scenario file holds one YAML document; found a second one here");
  return documents.first;
}

Scenario scenarioFromDocument(const YAML::Node& root, const std::string& name_for_errors) {
  try {
    return readScenario(root, name_for_errors);
  } catch (const YAML::Exception& error) {  // not expected: every access above is checked
    const int line = error.mark.is_null() ? 1 : error.mark.line + 1;
    throw ScenarioError(name_for_errors + ":" + std::to_string(line) + ": " + error.msg);
  }
}

std::string readScenarioFile(const std::string& path) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw ScenarioError(path + ": cannot open scenario file (" + std::strerror(errno) + ")");
  std::string text;
  char buffer[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, n);
  if (std::ferror(file.get())) throw ScenarioError(path + ": cannot read scenario file (" + std::strerror(errno) + ")");
  return text;
}

Scenario parseScenario(const std::string& yaml_text, const std::string& name_for_errors) {
  return scenarioFromDocument(parseScenarioDocument(yaml_text, name_for_errors), name_for_errors);
}

Scenario loadScenario(const std::string& path) { return parseScenario(readScenarioFile(path), path); }

}  // namespace wsn::scenario

// The strict YAML scenario loader (DESIGN principle 6): every key is known, every value has the
// expected type and lies in its range, and every problem is reported as "file:line: message"
// naming the dotted key and what was expected. Also applies command-line overrides (--set) to a
// file's YAML before validating it, and writes a scenario back fully resolved.
#include "common/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>

#include "common/config/yaml_reader.hpp"
#include "common/config/yaml_writer.hpp"
#include "common/scenario_schema.hpp"
#include "node/sensor_model_registry.hpp"

namespace wsn::common {
namespace {

using config::compactNumber;
using config::deriveLeftOut;
using config::describe;
using config::Entry;
using config::FieldKind;
using config::FieldTable;
using config::forEachItem;
using config::keyText;
using config::lineOr;
using config::Range;
using config::Reader;
using config::Section;
using config::writeFields;
using config::writeList;
using config::writeSection;
using config::yamlNumber;
using schema::kMaxBirthsPerTick;
using schema::kMaxCoordinate;
using schema::kMaxNameLength;
using schema::kMaxSensors;
using schema::kMaxSupernodes;

std::string regionText(const Rect& r) {
  return "[" + compactNumber(r.x_min) + ", " + compactNumber(r.x_max) + "] x [" + compactNumber(r.y_min) + ", " +
         compactNumber(r.y_max) + "]";
}

std::string pointText(Vec2 p) { return "(" + compactNumber(p.x) + ", " + compactNumber(p.y) + ")"; }

/// Number of sensors a grid layout puts in the region, as common/sensor_layout.cpp computes it.
double gridSensorCount(const Rect& region, double spacing) {
  return std::floor(region.width() / spacing + 1e-9) * std::floor(region.height() / spacing + 1e-9);
}

/// Number of cells of side 2 Rs over the region, as common/sensor_layout.cpp computes it: node
/// tiles are unions of these cells, so there can be no more node processes than cells.
double layoutCellCount(const Rect& region, double sensing_range) {
  const double cell = std::max(2.0 * sensing_range, 1e-6);
  const double columns = std::max(1.0, std::ceil(region.width() / cell - 1e-9));
  const double rows = std::max(1.0, std::ceil(region.height() / cell - 1e-9));
  return columns * rows;
}

bool validName(const std::string& name) {
  if (name.empty() || name.size() > kMaxNameLength) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
           c == '.';
  });
}

// ---------------------------------------------------------------------------------------------
// Cross-field rules: each says what must hold between values of different keys, and the line to
// blame when it does not. They run after the keys they involve are read.

/// region: x_min < x_max and y_min < y_max.
void regionIsOrdered(const Reader& r, const Rect& region, int line) {
  if (!(region.x_min < region.x_max))
    r.fail(line, "'region' must have x_min < x_max, got x_min = " + compactNumber(region.x_min) +
                     ", x_max = " + compactNumber(region.x_max));
  if (!(region.y_min < region.y_max))
    r.fail(line, "'region' must have y_min < y_max, got y_min = " + compactNumber(region.y_min) +
                     ", y_max = " + compactNumber(region.y_max));
}

/// sensors: a grid holds 1 to kMaxSensors sensors.
void gridFitsRegion(const Reader& r, const Scenario& s, int line) {
  if (s.sensors.kind != SensorLayoutConfig::Kind::kGrid) return;
  const double n = gridSensorCount(s.region, s.sensors.spacing);
  if (n < 1.0 || n > kMaxSensors)
    r.fail(line, "'sensors.spacing' " + compactNumber(s.sensors.spacing) + " puts " + compactNumber(n) +
                     " sensors on the grid over the region " + regionText(s.region) + "; expected 1 to " +
                     compactNumber(kMaxSensors));
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

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

/// sensors and sensor_model: a model with sensor types places them by a list, each item of one of
/// its types; a model without types places none.
void sensorTypesFitModel(const Reader& r, const Scenario& s, const node::SensorModelSpec& model, int layout_line,
                         int kind_line) {
  const auto& types = model.settings.sensor_types;
  const bool listed = s.sensors.kind == SensorLayoutConfig::Kind::kList;
  if (!types.empty() && !listed)
    r.fail(kind_line, "'sensor_model.kind: " + model.name + "' places sensors of types " + config::join(types) +
                          " one by one; expected 'sensors.layout: list'");
  if (types.empty() && listed)
    r.fail(layout_line, "'sensors.layout: list' places typed sensors, but 'sensor_model.kind: " + model.name +
                            "' has no sensor types; expected a grid or random layout, or a model with types");
  for (std::size_t i = 0; i < s.sensors.list.size(); ++i) {
    const PlacedSensorConfig& sensor = s.sensors.list[i];
    if (!contains(types, sensor.type))
      r.fail(sensor.type_line, "'sensors.list[" + std::to_string(i) + "].type' must be one of: " +
                                   config::join(types) + "; got '" + sensor.type + "'");
  }
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

/// targets.birth_rate: at most kMaxBirthsPerTick expected births per tick over the region.
void birthsPerTickBounded(const Reader& r, const Scenario& s, int line) {
  const double births = s.targets.birth_rate * s.region.area();
  if (births > kMaxBirthsPerTick)
    r.fail(line, "'targets.birth_rate' " + compactNumber(s.targets.birth_rate) + " gives " + compactNumber(births) +
                     " expected births per tick over the region (area " + compactNumber(s.region.area()) +
                     "); expected at most " + compactNumber(kMaxBirthsPerTick));
}

/// The sensor models whose keys (`which`: of sensor_model or of a scripted target) include `key`.
std::vector<std::string> modelsReading(const std::string& key,
                                       std::vector<std::string> node::SensorModelSettingsSpec::*which) {
  std::vector<std::string> names;
  for (const auto& model : node::sensorModelRegistry())
    if (contains(model.settings.*which, key)) names.push_back(model.name);
  return names;
}

/// "'sensor_model.kind: a'" or "'sensor_model.kind: a' or 'sensor_model.kind: b'".
std::string kindsText(const std::vector<std::string>& kinds) {
  std::string text;
  for (const auto& kind : kinds)
    text += (text.empty() ? "'" : " or '") + std::string("sensor_model.kind: ") + kind + "'";
  return text;
}

/// A scripted target: disappearing after it appears, starting inside the region, and what its
/// sensor model asks of it.
void scriptedTargetIsValid(const Reader& r, const Scenario& s, const node::SensorModelSpec& model,
                           const TargetSpec& spec, const Section& t) {
  const std::string& path = t.path;
  for (const auto& [key, entry] : t.entries) {
    const std::vector<std::string> readers = modelsReading(key, &node::SensorModelSettingsSpec::target_keys);
    if (!readers.empty() && !contains(model.settings.target_keys, key))
      r.fail(Reader::lineOf(entry.key), "'" + path + "." + key + "' applies only with " + kindsText(readers));
  }
  if (model.settings.check_target) model.settings.check_target(r, s, spec, t);
  if (spec.disappear_tick != 0 && spec.disappear_tick <= spec.appear_tick)
    r.fail(Reader::lineOf(*t.find("disappear_tick")),
           "'" + path + ".disappear_tick' must be 0 (never) or greater than appear_tick " +
               std::to_string(spec.appear_tick) + ", got " + std::to_string(spec.disappear_tick));
  if (!s.region.contains(spec.position))
    r.fail(t.line,
           "'" + path + "' starts at " + pointText(spec.position) + ", outside the region " + regionText(s.region));
}

/// A supernode inside the region and apart from every earlier one.
void supernodeIsPlaced(const Reader& r, const Scenario& s, Vec2 p, const Section& sec) {
  if (!s.region.contains(p))
    r.fail(sec.line, "'" + sec.path + "' at " + pointText(p) + " is outside the region " + regionText(s.region));
  for (std::size_t j = 0; j < s.supernodes.size(); ++j)
    if (s.supernodes[j] == p)
      r.fail(sec.line, "'" + sec.path + "' at " + pointText(p) + " is at the same place as 'supernodes[" +
                           std::to_string(j) + "]'");
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

/// A polyline's points: no two in a row equal, since a leg of length 0 has no direction.
void noRepeatedPoint(const Reader& r, const std::vector<Vec2>& points, const Entry& list, const std::string& path) {
  for (std::size_t i = 1; i < points.size(); ++i)
    if (points[i] == points[i - 1]) {
      const int line = Reader::lineOf(list.value[i]) > 0 ? Reader::lineOf(list.value[i]) : Reader::lineOf(list);
      r.fail(line, "'" + path + "[" + std::to_string(i) + "]' " + pointText(points[i]) + " repeats the point before it; " +
                       "expected a leg of nonzero length");
    }
}

/// A feature's name: valid, and not one an earlier feature of the same list has.
template <typename Feature>
void nameIsNew(const Reader& r, const std::vector<Feature>& earlier, const Feature& feature, const Section& t,
               const std::string& list_path) {
  const int line = lineOr(t, "name", t.line);
  if (!validName(feature.name))
    r.fail(line, "'" + t.pathOf("name") + "' must be 1 to " + std::to_string(kMaxNameLength) +
                     " characters from A-Z a-z 0-9 _ - ., got '" + feature.name + "'");
  for (std::size_t j = 0; j < earlier.size(); ++j)
    if (earlier[j].name == feature.name)
      r.fail(line, "'" + t.pathOf("name") + "' '" + feature.name + "' is already the name of '" + list_path + "[" +
                       std::to_string(j) + "]'; expected unique names");
}

/// run.node_processes: at most one tile per cell of side 2 Rs.
void nodeProcessesFitCells(const Reader& r, const Scenario& s, int line) {
  const double cells = layoutCellCount(s.region, s.sensor_model.sensing_range);
  if (static_cast<double>(s.run.node_processes) > cells)
    r.fail(line, "'run.node_processes' " + std::to_string(s.run.node_processes) + " exceeds the " +
                     compactNumber(cells) +
                     " cells of side 2 Rs = " + compactNumber(2.0 * s.sensor_model.sensing_range) +
                     " that node tiles are made of; expected at most " + compactNumber(cells));
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
      if (!isSimplePolygon(mask.polygon))
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
  return s;
}

// ---------------------------------------------------------------------------------------------
// Writing.

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

// ---------------------------------------------------------------------------------------------
// Reading a document.

/// The one YAML document of a scenario text (null when empty); syntax errors as "name:line: ...".
YAML::Node parseDocument(const std::string& yaml_text, const std::string& name_for_errors) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(yaml_text);
  } catch (const YAML::ParserException& error) {
    const int line = error.mark.is_null() ? 1 : error.mark.line + 1;
    throw ScenarioError(name_for_errors + ":" + std::to_string(line) + ": invalid YAML: " + error.msg);
  } catch (const YAML::Exception& error) {
    throw ScenarioError(name_for_errors + ":1: invalid YAML: " + error.msg);
  }
  for (std::size_t i = 1; i < documents.size(); ++i)
    if (!documents[i].IsNull())
      throw ScenarioError(name_for_errors + ":" + std::to_string(std::max(Reader::lineOf(documents[i]), 1)) +
                          ": a scenario file holds one YAML document; found a second one here");
  return documents.empty() ? YAML::Node() : documents.front();
}

Scenario validateTree(const YAML::Node& root, const std::string& name_for_errors) {
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

// ---------------------------------------------------------------------------------------------
// Overrides. They are set in the YAML tree of the file as written, not in the resolved
// scenario, so that what the loader derives from other values (beta from Rs, the default
// supernode from the region, engine defaults from the engine) follows them as after an edit.

/// One step of a key's path: a mapping key, or an item of a list.
struct PathStep {
  std::string key;  ///< empty for a list item
  std::size_t index = 0;
};

/// "supernodes[1].x" -> supernodes, [1], x. Names are anything but '.', '[' and ']'.
std::vector<PathStep> keyPath(const ScenarioOverride& o) {
  const auto bad = [&o]() {
    throw OverrideError(o.text() +
                        ": KEY must be a dotted path of names, list items as name[i] "
                        "(e.g. network.pte, tracker.params.gate_chi2, supernodes[0].x)");
  };
  std::vector<PathStep> path;
  std::size_t i = 0;
  const std::string& key = o.key;
  while (true) {
    const std::size_t end = key.find_first_of(".[]", i);
    const std::string name = key.substr(i, end == std::string::npos ? std::string::npos : end - i);
    if (name.empty()) bad();
    path.push_back({name, 0});
    i = end;
    while (i != std::string::npos && key[i] == '[') {
      const std::size_t close = key.find(']', i);
      if (close == std::string::npos || close == i + 1) bad();
      std::size_t index = 0;
      const auto result = std::from_chars(key.data() + i + 1, key.data() + close, index);
      if (result.ec != std::errc{} || result.ptr != key.data() + close) bad();
      path.push_back({"", index});
      i = close + 1 < key.size() ? close + 1 : std::string::npos;
    }
    if (i == std::string::npos) break;
    if (key[i] != '.') bad();
    ++i;
  }
  return path;
}

/// The value as one YAML scalar, or null for an empty value.
YAML::Node overrideValue(const ScenarioOverride& o) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(o.value);
  } catch (const YAML::Exception& error) {
    throw OverrideError(o.text() + ": VALUE is not valid YAML (" + error.msg + "); quote it to make it a string");
  }
  if (documents.empty()) return YAML::Node(YAML::NodeType::Null);
  if (documents.size() > 1 || documents.front().IsMap() || documents.front().IsSequence())
    throw OverrideError(o.text() + ": VALUE must be a single value such as 0.4 or gnn, got " +
                        (documents.size() > 1 ? std::string("several YAML documents") : describe(documents.front())) +
                        "; lists and mappings belong in the scenario file");
  return documents.front();
}

/// Sets path[i..] below `container` to `value`; `where` is the dotted path of `container`.
/// Nodes are handles: a copy refers to the same node of the tree, so setting through one
/// changes the tree.
void setPath(YAML::Node container, const std::vector<PathStep>& path, std::size_t i, const YAML::Node& value,
             const std::string& where, const ScenarioOverride& o) {
  const PathStep& step = path[i];
  const bool last = i + 1 == path.size();
  const std::string here =
      step.key.empty() ? where + "[" + std::to_string(step.index) + "]" : (where.empty() ? "" : where + ".") + step.key;
  if (!step.key.empty()) {
    if (!container.IsMap())
      throw OverrideError(o.text() + ": '" + where + "' is " + describe(container) +
                          (container.IsSequence() ? "; address its items as " + where + "[0]" : ", not a mapping"));
    if (last) {
      container[step.key] = value;
      return;
    }
    // A section left out (or left empty) is created, as if the file had it; an unknown name
    // is then rejected by the loader with the list of the names it expects.
    if (!container[step.key].IsMap() && !container[step.key].IsSequence()) {
      if (container[step.key].IsScalar())
        throw OverrideError(o.text() + ": '" + here + "' is " + describe(container[step.key]) + ", not a mapping");
      container[step.key] = YAML::Node(YAML::NodeType::Map);
    }
    setPath(container[step.key], path, i + 1, value, here, o);
    return;
  }
  if (!container.IsSequence())
    throw OverrideError(o.text() + ": '" + where + "' is " + describe(container) + ", not a list");
  if (step.index >= container.size())
    throw OverrideError(o.text() + ": '" + where + "' has " + std::to_string(container.size()) +
                        " items (from [0]); a list can only be changed item by item, not extended");
  if (last) {
    container[step.index] = value;
    return;
  }
  setPath(container[step.index], path, i + 1, value, here, o);
}

void applyOverride(YAML::Node& root, const ScenarioOverride& o) {
  const std::vector<PathStep> path = keyPath(o);
  const YAML::Node value = overrideValue(o);
  if (!root.IsDefined() || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);  // an empty file
  setPath(root, path, 0, value, "", o);
}

/// "name:12: message" -> "message": the line of a validated tree that holds overrides points
/// into no file the user has.
std::string withoutLocation(const std::string& message, const std::string& name) {
  if (message.compare(0, name.size() + 1, name + ":") != 0) return message;
  std::size_t i = name.size() + 1;
  while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
  if (i == name.size() + 1 || message.compare(i, 2, ": ") != 0) return message;
  return message.substr(i + 2);
}

Scenario validateTree(const YAML::Node& root, const std::string& name, const ScenarioCheck& check) {
  Scenario s = validateTree(root, name);
  if (check) check(s);
  return s;
}

/// The message a tree fails validation with; nullopt when it is valid.
std::optional<std::string> failureOf(const YAML::Node& root, const std::string& name, const ScenarioCheck& check) {
  try {
    validateTree(root, name, check);
  } catch (const ScenarioError& error) {
    return std::string(error.what());
  }
  return std::nullopt;
}

}  // namespace

Scenario parseScenario(const std::string& yaml_text, const std::string& name_for_errors) {
  return validateTree(parseDocument(yaml_text, name_for_errors), name_for_errors);
}

Scenario loadScenario(const std::string& path) { return parseScenario(readScenarioFile(path), path); }

ScenarioOverride parseOverride(const std::string& key_equals_value) {
  const std::size_t equals = key_equals_value.find('=');
  if (equals == std::string::npos || equals == 0)
    throw OverrideError("--set " + key_equals_value + ": expected KEY=VALUE, e.g. --set network.pte=0.4");
  return {key_equals_value.substr(0, equals), key_equals_value.substr(equals + 1), ""};
}

Scenario applyOverrides(const std::string& yaml_text, const std::string& name_for_errors,
                        const std::vector<ScenarioOverride>& overrides, const ScenarioCheck& check) {
  // Each tree is parsed afresh rather than cloned: a clone loses the marks that give the lines
  // of the file's own problems.
  const auto overridden = [&](const ScenarioOverride* first, const ScenarioOverride* last) {
    YAML::Node tree = parseDocument(yaml_text, name_for_errors);
    if (tree.IsDefined() && !tree.IsNull() && !tree.IsMap()) validateTree(tree, name_for_errors);  // throws
    for (; first != last; ++first) applyOverride(tree, *first);
    return tree;
  };
  const ScenarioOverride* const begin = overrides.data();
  const ScenarioOverride* const end = begin + overrides.size();
  try {
    return validateTree(overridden(begin, end), name_for_errors, check);
  } catch (const OverrideError&) {
    throw;
  } catch (const ScenarioError& error) {
    const std::string message = error.what();
    // The file's own first problem reads the same with and without the overrides, line and all.
    const auto base_failure = failureOf(overridden(begin, begin), name_for_errors, check);
    if (base_failure == message) throw;
    // Otherwise name the overrides that fail the same way on their own, else those that fail
    // some other way on their own, else (only their combination fails) all of them.
    const std::string reason = withoutLocation(message, name_for_errors);
    std::vector<const ScenarioOverride*> same;
    std::vector<const ScenarioOverride*> other;
    for (const ScenarioOverride* o = begin; o != end; ++o) {
      std::optional<std::string> alone;
      try {
        alone = failureOf(overridden(o, o + 1), name_for_errors, check);
      } catch (const OverrideError&) {  // its path needs an earlier override
        continue;
      }
      if (!alone || alone == base_failure) continue;
      (withoutLocation(*alone, name_for_errors) == reason ? same : other).push_back(o);
    }
    std::vector<const ScenarioOverride*> named = !same.empty() ? same : other;
    if (named.empty())
      for (const ScenarioOverride* o = begin; o != end; ++o) named.push_back(o);
    std::string options;
    for (const auto* o : named) options += (options.empty() ? "" : " ") + o->text();
    throw OverrideError(options + ": " + reason);
  }
}

Scenario loadScenario(const std::string& path, const std::vector<ScenarioOverride>& overrides,
                      const ScenarioCheck& check) {
  return applyOverrides(readScenarioFile(path), path, overrides, check);
}

std::string resolvedScenarioYaml(const Scenario& s) {
  std::ostringstream out;
  out << "# wsntrack resolved scenario: every parameter written out with defaults filled in.\n"
      << "# Loading this file gives the same scenario. '# derived:' marks a value the file left out\n"
      << "# and the loader computed from others.\n";
  writeFields(out, "", schema::topLevel(), s);
  writeSection(out, "region", schema::region(), s.region);
  writeSection(out, "sensors", schema::sensors(), s.sensors);
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
  return out.str();
}

}  // namespace wsn::common

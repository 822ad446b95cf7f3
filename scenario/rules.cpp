// The scenario loader's cross-field rules (scenario/rules.hpp): each says what must hold between
// values of different keys, and the line to blame when it does not.
#include "scenario/rules.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace wsn::scenario {
namespace {

namespace config = common::config;
using common::PlacedSensorConfig;
using common::Rect;
using common::Scenario;
using common::SensorLayoutConfig;
using common::TargetSpec;
using common::Vec2;
using common::schema::kMaxBirthsPerTick;
using common::schema::kMaxNameLength;
using common::schema::kMaxSensors;
using config::compactNumber;
using config::Entry;
using config::Reader;
using config::Section;

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

}  // namespace

std::string regionText(const Rect& r) {
  return "[" + compactNumber(r.x_min) + ", " + compactNumber(r.x_max) + "] x [" + compactNumber(r.y_min) + ", " +
         compactNumber(r.y_max) + "]";
}

std::string pointText(Vec2 p) { return "(" + compactNumber(p.x) + ", " + compactNumber(p.y) + ")"; }

bool validName(const std::string& name) {
  if (name.empty() || name.size() > kMaxNameLength) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
           c == '.';
  });
}

void regionIsOrdered(const Reader& r, const Rect& region, int line) {
  if (!(region.x_min < region.x_max))
    r.fail(line, "'region' must have x_min < x_max, got x_min = " + compactNumber(region.x_min) +
                     ", x_max = " + compactNumber(region.x_max));
  if (!(region.y_min < region.y_max))
    r.fail(line, "'region' must have y_min < y_max, got y_min = " + compactNumber(region.y_min) +
                     ", y_max = " + compactNumber(region.y_max));
}

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

void birthsPerTickBounded(const Reader& r, const Scenario& s, int line) {
  const double births = s.targets.birth_rate * s.region.area();
  if (births > kMaxBirthsPerTick)
    r.fail(line, "'targets.birth_rate' " + compactNumber(s.targets.birth_rate) + " gives " + compactNumber(births) +
                     " expected births per tick over the region (area " + compactNumber(s.region.area()) +
                     "); expected at most " + compactNumber(kMaxBirthsPerTick));
}

std::vector<std::string> modelsReading(const std::string& key,
                                       std::vector<std::string> node::SensorModelSettingsSpec::*which) {
  std::vector<std::string> names;
  for (const auto& model : node::sensorModelRegistry())
    if (contains(model.settings.*which, key)) names.push_back(model.name);
  return names;
}

std::string kindsText(const std::vector<std::string>& kinds) {
  std::string text;
  for (const auto& kind : kinds)
    text += (text.empty() ? "'" : " or '") + std::string("sensor_model.kind: ") + kind + "'";
  return text;
}

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

void supernodeIsPlaced(const Reader& r, const Scenario& s, Vec2 p, const Section& sec) {
  if (!s.region.contains(p))
    r.fail(sec.line, "'" + sec.path + "' at " + pointText(p) + " is outside the region " + regionText(s.region));
  for (std::size_t j = 0; j < s.supernodes.size(); ++j)
    if (s.supernodes[j] == p)
      r.fail(sec.line, "'" + sec.path + "' at " + pointText(p) + " is at the same place as 'supernodes[" +
                           std::to_string(j) + "]'");
}

void noRepeatedPoint(const Reader& r, const std::vector<Vec2>& points, const Entry& list, const std::string& path) {
  for (std::size_t i = 1; i < points.size(); ++i)
    if (points[i] == points[i - 1]) {
      const int line = Reader::lineOf(list.value[i]) > 0 ? Reader::lineOf(list.value[i]) : Reader::lineOf(list);
      r.fail(line, "'" + path + "[" + std::to_string(i) + "]' " + pointText(points[i]) + " repeats the point before it; " +
                       "expected a leg of nonzero length");
    }
}

void nodeProcessesFitCells(const Reader& r, const Scenario& s, int line) {
  const double cells = layoutCellCount(s.region, s.sensor_model.sensing_range);
  if (static_cast<double>(s.run.node_processes) > cells)
    r.fail(line, "'run.node_processes' " + std::to_string(s.run.node_processes) + " exceeds the " +
                     compactNumber(cells) +
                     " cells of side 2 Rs = " + compactNumber(2.0 * s.sensor_model.sensing_range) +
                     " that node tiles are made of; expected at most " + compactNumber(cells));
}

}  // namespace wsn::scenario

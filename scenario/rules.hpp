// The scenario loader's cross-field rules: what must hold between values of different keys (a
// grid that fits the region, supernodes apart, a model's keys only with that model, ...), each
// failing with the line to blame. Internal to wsn_scenario: the section readers (loader.cpp) call
// them once the keys they involve are read.
#pragma once

#include <string>
#include <vector>

#include "common/config/yaml_reader.hpp"
#include "common/geometry.hpp"
#include "common/scenario_config.hpp"
#include "common/scenario_schema.hpp"
#include "node/sensor_model_registry.hpp"

namespace wsn::scenario {

// Pieces of messages and names shared by the rules and the readers.

/// "[x_min, x_max] x [y_min, y_max]".
std::string regionText(const common::Rect& r);
/// "(x, y)".
std::string pointText(common::Vec2 p);
/// 1 to kMaxNameLength characters from A-Z a-z 0-9 _ - . (a name that can name a file).
bool validName(const std::string& name);
bool contains(const std::vector<std::string>& names, const std::string& name);
/// The sensor models whose keys (`which`: of sensor_model or of a scripted target) include `key`.
std::vector<std::string> modelsReading(const std::string& key,
                                       std::vector<std::string> node::SensorModelSettingsSpec::*which);
/// "'sensor_model.kind: a'" or "'sensor_model.kind: a' or 'sensor_model.kind: b'".
std::string kindsText(const std::vector<std::string>& kinds);

// The rules. `r` names the file; `line` is the line to blame.

/// region: x_min < x_max and y_min < y_max.
void regionIsOrdered(const common::config::Reader& r, const common::Rect& region, int line);

/// sensors: a grid holds 1 to kMaxSensors sensors.
void gridFitsRegion(const common::config::Reader& r, const common::Scenario& s, int line);

/// sensors and sensor_model: a model with sensor types places them by a list, each item of one of
/// its types; a model without types places none.
void sensorTypesFitModel(const common::config::Reader& r, const common::Scenario& s,
                         const node::SensorModelSpec& model, int layout_line, int kind_line);

/// targets.birth_rate: at most kMaxBirthsPerTick expected births per tick over the region.
void birthsPerTickBounded(const common::config::Reader& r, const common::Scenario& s, int line);

/// A scripted target: disappearing after it appears, starting inside the region, and what its
/// sensor model asks of it.
void scriptedTargetIsValid(const common::config::Reader& r, const common::Scenario& s,
                           const node::SensorModelSpec& model, const common::TargetSpec& spec,
                           const common::config::Section& t);

/// A supernode inside the region and apart from every earlier one.
void supernodeIsPlaced(const common::config::Reader& r, const common::Scenario& s, common::Vec2 p,
                       const common::config::Section& sec);

/// A polyline's points: no two in a row equal, since a leg of length 0 has no direction.
void noRepeatedPoint(const common::config::Reader& r, const std::vector<common::Vec2>& points,
                     const common::config::Entry& list, const std::string& path);

/// run.node_processes: at most one tile per cell of side 2 Rs.
void nodeProcessesFitCells(const common::config::Reader& r, const common::Scenario& s, int line);

/// A feature's name: valid, and not one an earlier feature of the same list has.
template <typename Feature>
void nameIsNew(const common::config::Reader& r, const std::vector<Feature>& earlier, const Feature& feature,
               const common::config::Section& t, const std::string& list_path) {
  const int line = common::config::lineOr(t, "name", t.line);
  if (!validName(feature.name))
    r.fail(line, "'" + t.pathOf("name") + "' must be 1 to " + std::to_string(common::schema::kMaxNameLength) +
                     " characters from A-Z a-z 0-9 _ - ., got '" + feature.name + "'");
  for (std::size_t j = 0; j < earlier.size(); ++j)
    if (earlier[j].name == feature.name)
      r.fail(line, "'" + t.pathOf("name") + "' '" + feature.name + "' is already the name of '" + list_path + "[" +
                       std::to_string(j) + "]'; expected unique names");
}

}  // namespace wsn::scenario

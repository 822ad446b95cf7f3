// The field_sensors model's keys of `sensor_model` (ONERA's heterogeneous sensors, Table I): the
// speed below which no sensor detects a target and, under each type's name, that type's settings;
// their field tables and how the scenario loader reads and writes them.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/config/field_table.hpp"
#include "common/scenario_config.hpp"
#include "node/field_sensors/sensor_type.hpp"
#include "node/sensor_model_registry.hpp"

namespace wsn::node::field_sensors {

/// Every type's defaults (SensorType::defaults()), by name.
std::map<std::string, TypeSettings> defaultTypeSettings();

/// ONERA's sensors, each placed by a sensors.list item of its type.
struct FieldSensorsSettings : common::SensorModelSettingsOf<FieldSensorsSettings> {
  /// v_min: the spec's eq. 9 assumption, no sensor detects a target slower than this (per tick).
  double min_speed = 0.5;
  std::map<std::string, TypeSettings> types = defaultTypeSettings();
  friend bool operator==(const FieldSensorsSettings&, const FieldSensorsSettings&) = default;

  /// Every listed sensor's sector, PD and sight blockers, from its believed position.
  std::vector<common::SensorCoverage> coverage(const common::Scenario& scenario) const override;
};

const common::config::FieldTable<FieldSensorsSettings>& settingsTable();
/// The keys of sensor_model.<type>: the four every type reads and the type's own.
const common::config::FieldTable<TypeSettings>& typeTable(const SensorType& type);

/// The loader's view of these settings (for the registry).
SensorModelSettingsSpec settingsSpec();

}  // namespace wsn::node::field_sensors

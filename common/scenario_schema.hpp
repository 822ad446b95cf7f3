// The field tables of the scenario's sections: each key of scenario.yaml described once (member,
// unit, range, default, meaning). The loader, the resolved-scenario writer, `wsntrack components`
// and the key tables of scenarios/README.md are generated from these.
#pragma once

#include <string>
#include <vector>

#include "common/config/field_table.hpp"
#include "common/scenario_config.hpp"

namespace wsn::common::schema {

using config::FieldTable;

const FieldTable<Scenario>& topLevel();  ///< name
const FieldTable<Rect>& region();
const FieldTable<SensorLayoutConfig>& sensors();
const FieldTable<PlacedSensorConfig>& placedSensor();  ///< an item of sensors.list
const FieldTable<SensorModelConfig>& sensorModel();  ///< kind, sensing_range (the rest: the model's table)
const FieldTable<LocalisationConfig>& localisation();
const FieldTable<TargetsConfig>& targets();  ///< scalars (scripted: a list)
const FieldTable<TargetSpec>& scriptedTarget();
const FieldTable<WaypointStop>& waypointStop();  ///< targets.scripted[].stops[]
const FieldTable<DynamicsConfig>& dynamics();
const FieldTable<Vec2>& supernode();
const FieldTable<TerrainConfig>& terrain();  ///< roads, masks (lists)
const FieldTable<RoadLine>& road();          ///< terrain.roads[]
const FieldTable<Mask>& mask();              ///< terrain.masks[]
const FieldTable<FaultSpec>& fault();         ///< faults[]
const FieldTable<NetworkConfig>& network();
const FieldTable<TrackerConfig>& tracker();        ///< engine, window_size (params: the engine's table)
const FieldTable<AggregatorConfig>& aggregator();  ///< association (params: the association's table)
const FieldTable<MetricsConfig>& metrics();
const FieldTable<RunConfig>& run();

/// The top-level keys of a scenario file, in the order the resolved file writes them.
const std::vector<std::string>& sectionNames();

/// Every section table as Markdown under its dotted name ("sensor_model.acoustic"), for
/// scenarios/README.md; checked against the README by a test.
std::vector<std::pair<std::string, std::string>> markdownTables();

/// Every section's keys with unit, default, range and meaning, each under its dotted path
/// ("network.pte"), for `wsntrack components --json`.
std::vector<config::KeyTable> keyTables();

// Limits that are not paper values but keep a run finite and the numbers meaningful.
inline constexpr double kMaxCoordinate = 1e6;      ///< |region bounds| (sensor separations)
inline constexpr double kMaxSensors = 1e7;         ///< sensors a layout may create
inline constexpr double kMaxBirthsPerTick = 1000;  ///< birth_rate * region area
inline constexpr std::size_t kMaxSupernodes = 256;
inline constexpr std::size_t kMaxNameLength = 100;

}  // namespace wsn::common::schema

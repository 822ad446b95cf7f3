// The sensor-model plugin interface: the model's own keys of the scenario's `sensor_model`
// section (read, checked and written through the spec) and what a node tile runs each tick,
// whatever its sensors are (signal strength with neighbour fusion, acoustic Doppler, ...); and
// the registry that maps `sensor_model.kind` to a model. A new sensor model is a folder under
// node/ with one spec and one line in sensor_model_registry.cpp.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "common/config/yaml_reader.hpp"
#include "common/messages.hpp"
#include "common/registry.hpp"
#include "common/scenario_config.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/tiling.hpp"

namespace wsn::node {

/// What a tile's sensors are built from. References must outlive the model.
struct TileContext {
  const common::SensorModelConfig& sensor_model;  ///< kind, Rs and the model's own settings
  std::uint64_t seed = 1;                         ///< run.seed
  /// The scripted targets, for models with per-target keys (the acoustic model's sensing range).
  const std::vector<common::TargetSpec>& scripted_targets;
  const common::SensorLayout& layout;
  const Tile& tile;
  const common::Truth& truth;
  /// Roads and masks (the scenario's `terrain:`); null or empty: open ground, nothing hidden.
  const common::TerrainConfig* terrain = nullptr;
};

/// One tile's sensors. A tick runs in two phases so that models whose sensors fuse with their
/// neighbours (Oh eq. 6) can exchange readings across tile edges in between: sense() gives the
/// readings other tiles need, report() gets theirs. Outputs are a pure function of (scenario,
/// seed, tick): the same for every tiling.
class TileSensors {
 public:
  virtual ~TileSensors() = default;
  /// True when report() needs the other tiles' boundary readings; false lets the role skip the
  /// exchange (and its wait).
  virtual bool exchangesReadings() const = 0;
  /// Phase 1 of `tick`: senses, and returns the readings other tiles need (sorted by sensor id).
  virtual std::vector<common::SensorReading> sense(std::int32_t tick) = 0;
  /// Phase 2 of `tick`: this tile's reports, given every other tile's boundary readings.
  virtual std::vector<common::Report> report(std::int32_t tick, std::span<const common::SensorReading> foreign) = 0;
};

/// How a model owns its keys of `sensor_model` (all but kind and sensing_range): the scenario
/// loader reads, checks and writes them through these, with the same "file:line" messages as
/// every other section.
struct SensorModelSettingsSpec {
  /// Its keys of `sensor_model` (besides kind and sensing_range).
  std::vector<std::string> keys;
  /// The keys of a `targets.scripted[]` item it reads beyond position, velocity and lifetime.
  std::vector<std::string> target_keys;
  /// The `type`s a `sensors.list[]` item may have. A model with types needs `sensors.layout:
  /// list` (its sensors differ one by one); a model without takes no list.
  std::vector<std::string> sensor_types;
  /// Reads its keys from `sensor_model` as written (null when the file has no such section) and
  /// derives those left out; sensor_model.kind and sensing_range are read already.
  std::function<std::shared_ptr<const common::SensorModelSettings>(
      const common::config::Reader&, const common::config::Section* given, common::Scenario&)>
      read;
  /// Writes its keys two spaces in, for the resolved scenario.yaml.
  std::function<void(std::ostream&, const common::Scenario&)> write;
  /// Optional: a rule between a scripted target (`item` as written) and the model.
  std::function<void(const common::config::Reader&, const common::Scenario&, const common::TargetSpec&,
                     const common::config::Section& item)>
      check_target;
  /// Optional: a rule between the targets section (at `line`) and the model.
  std::function<void(const common::config::Reader&, const common::Scenario&, int line)> check_targets;
  /// Its key tables (units, defaults, ranges, meaning) for `wsntrack components` and, under their
  /// markers, scenarios/README.md.
  std::function<std::vector<common::config::KeyTable>()> key_tables;
};

/// One registered sensor model.
struct SensorModelSpec {
  std::string name;  ///< the value of sensor_model.kind
  std::string description;
  /// What its reports measure; engines declare the kinds they accept.
  std::vector<std::string> measurement_kinds;
  SensorModelSettingsSpec settings;
  std::function<std::unique_ptr<TileSensors>(const TileContext&)> create;
  /// Optional: what the scenario's own sensors report, a subset of measurement_kinds, for a model
  /// whose sensors differ by type (an engine then need not accept the kinds of absent types).
  std::function<std::vector<std::string>(const common::Scenario&)> scenario_measurement_kinds = {};
};

/// Every sensor model, in registration order.
const common::Registry<SensorModelSpec>& sensorModelRegistry();

/// Builds the tile's sensors of the scenario's model; throws std::invalid_argument for a kind no
/// model is registered for.
std::unique_ptr<TileSensors> makeTileSensors(const TileContext& context);

}  // namespace wsn::node

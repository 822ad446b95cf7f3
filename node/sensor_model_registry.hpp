// The sensor-model plugin interface: what a node tile runs each tick, whatever its sensors are
// (signal strength with neighbour fusion, acoustic Doppler, ...), and the registry that maps
// `sensor_model.kind` to a model. A new sensor model is a folder under node/ with one spec and
// one line in sensor_model_registry.cpp.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/messages.hpp"
#include "common/registry.hpp"
#include "common/scenario.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/tiling.hpp"

namespace wsn::node {

/// What a tile's sensors are built from. References must outlive the model.
struct TileContext {
  const common::Scenario& scenario;
  const common::SensorLayout& layout;
  const Tile& tile;
  const common::Truth& truth;
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

/// One registered sensor model.
struct SensorModelSpec {
  std::string name;  ///< the value of sensor_model.kind
  std::string description;
  /// The scenario keys it reads besides the layout (for `wsntrack components`).
  std::vector<std::string> config_sections;
  /// What its reports measure; engines declare the kinds they accept.
  std::vector<std::string> measurement_kinds;
  std::function<std::unique_ptr<TileSensors>(const TileContext&)> create;
};

/// Every sensor model, in registration order.
const common::Registry<SensorModelSpec>& sensorModelRegistry();

/// The name sensor_model.kind gives for `kind`.
std::string sensorModelName(common::SensorModelConfig::Kind kind);

/// Builds the tile's sensors of the scenario's model; throws std::invalid_argument for a kind no
/// model is registered for.
std::unique_ptr<TileSensors> makeTileSensors(const TileContext& context);

}  // namespace wsn::node

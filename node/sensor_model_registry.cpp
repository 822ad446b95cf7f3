#include "node/sensor_model_registry.hpp"

#include <stdexcept>

#include "node/acoustic/plugin.hpp"
#include "node/adman/plugin.hpp"
#include "node/field_sensors/plugin.hpp"
#include "node/magnetometer/plugin.hpp"
#include "node/signal_strength/plugin.hpp"

namespace wsn::node {

const common::Registry<SensorModelSpec>& sensorModelRegistry() {
  static const common::Registry<SensorModelSpec> registry("sensor model", {
      signal_strength::sensorModelSpec(),
      acoustic::sensorModelSpec(),
      magnetometer::sensorModelSpec(),
      adman::sensorModelSpec(),
      field_sensors::sensorModelSpec(),
      // A new model: its folder, and one line here.
  });
  return registry;
}

std::unique_ptr<TileSensors> makeTileSensors(const TileContext& context) {
  return sensorModelRegistry().at(context.sensor_model.kind).create(context);
}

}  // namespace wsn::node

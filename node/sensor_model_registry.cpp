#include "node/sensor_model_registry.hpp"

#include <stdexcept>

#include "common/scenario_schema.hpp"
#include "node/acoustic/plugin.hpp"
#include "node/signal_strength/plugin.hpp"

namespace wsn::node {

const common::Registry<SensorModelSpec>& sensorModelRegistry() {
  static const common::Registry<SensorModelSpec> registry("sensor model", {
      signal_strength::sensorModelSpec(),
      acoustic::sensorModelSpec(),
      // A new model: its folder, and one line here.
  });
  return registry;
}

std::string sensorModelName(common::SensorModelConfig::Kind kind) {
  common::SensorModelConfig config;
  config.kind = kind;
  return common::schema::sensorModel().find("kind")->get_text(config);
}

std::unique_ptr<TileSensors> makeTileSensors(const TileContext& context) {
  return sensorModelRegistry().at(sensorModelName(context.scenario.sensor_model.kind)).create(context);
}

}  // namespace wsn::node

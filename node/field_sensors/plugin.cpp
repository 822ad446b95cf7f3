#include "node/field_sensors/plugin.hpp"

#include <algorithm>
#include <string>

#include "node/field_sensors/config.hpp"
#include "node/field_sensors/field_sensors.hpp"

namespace wsn::node::field_sensors {
namespace {

/// Each sensor reports on its own (ONERA fuses at the supernode), so no readings cross tile edges.
class FieldSensorsTile final : public TileSensors {
 public:
  explicit FieldSensorsTile(const TileContext& context)
      : field_(common::settingsOf<FieldSensorsSettings>(context.sensor_model), context.seed, context.layout,
               context.tile, context.truth,
               context.terrain ? *context.terrain : common::TerrainConfig{}) {}

  bool exchangesReadings() const override { return false; }
  std::vector<common::SensorReading> sense(std::int32_t) override { return {}; }
  std::vector<common::Report> report(std::int32_t tick, std::span<const common::SensorReading>) override {
    return field_.detect(tick);
  }

 private:
  FieldSensors field_;
};

/// The kinds the types report, each once, in the order of common/measurement.hpp.
std::vector<std::string> kindsOf(const std::vector<const SensorType*>& types) {
  std::vector<common::MeasurementKind> kinds;
  for (const SensorType* type : types)
    if (std::find(kinds.begin(), kinds.end(), type->kind()) == kinds.end()) kinds.push_back(type->kind());
  std::sort(kinds.begin(), kinds.end());
  std::vector<std::string> names;
  for (const auto kind : kinds) names.emplace_back(common::measurementKindName(kind));
  return names;
}

std::vector<std::string> measurementKinds() {
  std::vector<const SensorType*> types;
  for (const auto& type : sensorTypes()) types.push_back(type.get());
  return kindsOf(types);
}

/// The kinds of the types the scenario's list places (the loader has checked every type).
std::vector<std::string> scenarioMeasurementKinds(const common::Scenario& s) {
  std::vector<const SensorType*> types;
  for (const auto& sensor : s.sensors.list)
    if (const SensorType* type = sensorTypeNamed(sensor.type)) types.push_back(type);
  return kindsOf(types);
}

}  // namespace

SensorModelSpec sensorModelSpec() {
  return {"field_sensors",
          "Pannetier, Dezert and Sella 2014 (ONERA) Table I: acoustic antennas and beacons, magnetic detectors, PIR, "
          "radars and cameras, each placed by a sensors.list item, reporting its own measurement (eq. 2-3) with the "
          "proposed PD, noise and false alarms of docs/ONERA.md",
          measurementKinds(),
          settingsSpec(),
          [](const TileContext& context) -> std::unique_ptr<TileSensors> {
            return std::make_unique<FieldSensorsTile>(context);
          },
          scenarioMeasurementKinds};
}

}  // namespace wsn::node::field_sensors

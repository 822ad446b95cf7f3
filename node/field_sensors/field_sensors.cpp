#include "node/field_sensors/field_sensors.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace wsn::node::field_sensors {

FieldSensor fieldSensorOf(const common::SensorLayout& layout, common::SensorId id,
                          const FieldSensorsSettings& settings) {
  const common::PlacedSensor& placed = layout.placedSensor(id);
  const SensorType* type = sensorTypeNamed(placed.type);
  const auto found = settings.types.find(placed.type);
  if (type == nullptr || found == settings.types.end())
    throw std::invalid_argument("field_sensors: sensor " + placed.name + " has type '" + placed.type +
                                "', which no sensor type has");
  const TypeSettings& s = found->second;
  FieldSensor sensor;
  sensor.id = id;
  sensor.position = layout.truePosition(id);
  const common::Vec2 believed = layout.believedPosition(id);
  sensor.heading = placed.heading;
  sensor.fov = placed.fov > 0.0 ? placed.fov : radians(s.fov_deg);
  sensor.range = placed.range > 0.0 ? placed.range : s.range;
  sensor.height = placed.height > 0.0 ? placed.height : s.height;
  sensor.pose = {believed.x, believed.y, placed.heading, sensor.height};
  sensor.type = type;
  sensor.settings = &s;
  return sensor;
}

std::vector<common::SensorCoverage> FieldSensorsSettings::coverage(const common::Scenario& scenario) const {
  const common::SensorLayout layout(common::sensorFieldConfig(scenario));
  std::vector<common::SensorCoverage> out;
  if (!layout.hasPlacedSensors()) return out;
  out.reserve(layout.size());
  for (common::SensorId id = 0; id < layout.size(); ++id) {
    const FieldSensor sensor = fieldSensorOf(layout, id, *this);
    out.push_back({id, {sensor.pose.x, sensor.pose.y}, sensor.heading, sensor.fov, sensor.range,
                   sensor.settings->detection_probability, sensor.type->blockers(), sensor.type->presence()});
  }
  return out;
}

FieldSensors::FieldSensors(const FieldSensorsSettings& settings, std::uint64_t seed, const common::SensorLayout& layout,
                           const Tile& tile, const common::Truth& truth, common::TerrainConfig terrain)
    : settings_(settings), seed_(seed), truth_(&truth), terrain_(std::move(terrain)) {
  if (!layout.hasPlacedSensors())
    throw std::invalid_argument("field_sensors: the layout places no typed sensors (sensors.layout: list)");
  for (const common::SensorId id : tileSensorIds(layout, tile, "FieldSensors"))
    sensors_.push_back(fieldSensorOf(layout, id, settings_));
}

bool FieldSensors::inLineOfSight(const FieldSensor& sensor, const common::TargetState& target) const {
  return !common::hiddenBy(&terrain_, sensor.type->blockers(), sensor.position, {target.x, target.y});
}

common::Report FieldSensors::reportOf(std::int32_t tick, const FieldSensor& sensor, std::vector<double> values,
                                      common::TargetId target, std::vector<double> class_likelihoods) const {
  common::Measurement m{sensor.type->kind(), std::move(values), sensor.type->noise(sensor), sensor.pose,
                        std::move(class_likelihoods)};
  // A sensor without false alarms still names a density (common::kClutterFloorTicks).
  const double rate = std::max(sensor.settings->false_alarms_per_tick, 1.0 / common::kClutterFloorTicks);
  m.clutter_density = rate / sensor.type->falseAlarmVolume(sensor);
  // common/messages.hpp: a report lies at its measured position, or at its sensor for other kinds.
  const double x = m.kind == common::MeasurementKind::position ? m.values[0] : sensor.pose.x;
  const double y = m.kind == common::MeasurementKind::position ? m.values[1] : sensor.pose.y;
  return {tick, sensor.id, x, y, target, 0, common::MeasurementRef(std::move(m))};
}

std::vector<common::Report> FieldSensors::detect(std::int32_t tick) const {
  std::vector<common::Report> out;
  const auto& targets = truth_->at(tick);
  for (const FieldSensor& sensor : sensors_) {
    const SensorType& type = *sensor.type;
    for (const common::TargetState& target : targets) {
      const TargetView view = viewOf(sensor, target);
      if (!covers(sensor, target, settings_.min_speed) || !inLineOfSight(sensor, target)) continue;
      const std::uint64_t pair = (static_cast<std::uint64_t>(sensor.id) << 32) | static_cast<std::uint32_t>(target.id);
      common::Stream draw(seed_, common::Purpose::kFieldSensorDetection, pair, tick);
      if (!draw.bernoulli(sensor.settings->detection_probability)) continue;
      // The declared class has a stream of its own, so that classifying changes no other draw.
      common::Stream class_draw(seed_, common::Purpose::kFieldSensorClass, pair, tick);
      out.push_back(reportOf(tick, sensor, type.perturb(type.measure(sensor, view), sensor, draw), target.id,
                             type.classLikelihoods(sensor, truth_->targetClass(target.id), class_draw)));
    }
    if (sensor.settings->false_alarms_per_tick <= 0.0) continue;
    common::Stream clutter(seed_, common::Purpose::kFieldSensorFalseAlarm, sensor.id, tick);
    const std::uint64_t count = clutter.poisson(sensor.settings->false_alarms_per_tick);
    for (std::uint64_t i = 0; i < count; ++i)
      out.push_back(reportOf(tick, sensor, type.falseAlarm(sensor, clutter), common::kFalseAlarm, {}));
  }
  return out;
}

}  // namespace wsn::node::field_sensors

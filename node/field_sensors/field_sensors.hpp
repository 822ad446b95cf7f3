// The field sensors of one tile (ONERA §II-A, Table I): each listed sensor of the tile, of its own
// type, detects the covered targets of a tick with its type's PD and measurement function (eq. 2-3)
// and adds its false alarms. Reports are a pure function of (scenario, seed, tick).
#pragma once

#include <cstdint>
#include <vector>

#include "common/messages.hpp"
#include "common/scenario_config.hpp"
#include "common/sensor_layout.hpp"
#include "common/terrain.hpp"
#include "common/truth.hpp"
#include "node/field_sensors/config.hpp"
#include "node/field_sensors/sensor_type.hpp"
#include "node/tiling.hpp"

namespace wsn::node::field_sensors {

/// Sensor `id` of a list layout with its type's defaults filled in where its entry gives none;
/// `settings` must outlive the result. Throws std::invalid_argument for a type no SensorType has.
FieldSensor fieldSensorOf(const common::SensorLayout& layout, common::SensorId id, const FieldSensorsSettings& settings);

/// The tile's sensors. At tick t, sensor s reports target k (in id order) when it covers k
/// (covers()), k is in its line of sight, and a draw of PD succeeds: z = h(x) + b from the stream
/// (seed, kFieldSensorDetection, s x 2^32 + k, t), and the class likelihoods of k's class (the
/// type's classLikelihoods()) from (seed, kFieldSensorClass, s x 2^32 + k, t). Then
/// Poisson(false_alarms_per_tick) false alarms from (seed, kFieldSensorFalseAlarm, s, t), with no
/// class likelihoods. Every draw is keyed by its sensor, so the reports do not depend on the tiling
/// or on the other targets.
class FieldSensors {
 public:
  FieldSensors(const FieldSensorsSettings& settings, std::uint64_t seed, const common::SensorLayout& layout,
               const Tile& tile, const common::Truth& truth, common::TerrainConfig terrain = {});
  // The sensors point into settings_: a copy would point into another object's.
  FieldSensors(const FieldSensors&) = delete;
  FieldSensors& operator=(const FieldSensors&) = delete;

  /// The tile's reports at `tick`, sorted by sensor id, each sensor's detections (by target id)
  /// before its false alarms.
  std::vector<common::Report> detect(std::int32_t tick) const;

  const std::vector<FieldSensor>& sensors() const { return sensors_; }

 private:
  /// Eq. 15's line of sight: no mask of a kind the sensor's type cannot see through lies between
  /// the sensor and the target.
  bool inLineOfSight(const FieldSensor& sensor, const common::TargetState& target) const;
  common::Report reportOf(std::int32_t tick, const FieldSensor& sensor, std::vector<double> values,
                          common::TargetId target, std::vector<double> class_likelihoods) const;

  FieldSensorsSettings settings_;
  std::uint64_t seed_;
  const common::Truth* truth_;
  common::Terrain terrain_;
  std::vector<FieldSensor> sensors_;  // the tile's, sorted by id; their settings point into settings_
};

}  // namespace wsn::node::field_sensors

// One type of field sensor of ONERA Table I (Pannetier, Dezert and Sella 2014) behind one small
// interface: its proposed settings (spec §1 PROP), its measurement function h (eq. 3) and its
// false alarms. A new type is one file defining a SensorType and one row in sensor_types.cpp.
#pragma once

#include <initializer_list>
#include <memory>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "common/class_evidence.hpp"
#include "common/geometry.hpp"
#include "common/measurement.hpp"
#include "common/messages.hpp"
#include "common/rng.hpp"
#include "common/sensor_coverage.hpp"
#include "common/truth.hpp"

namespace wsn::node::field_sensors {

/// A type's settings, overridable under sensor_model.<type>. Every type reads the first four; the
/// rest only the types whose keys() name them.
struct TypeSettings {
  double detection_probability = 0.9;  ///< PD of a covered target, each tick
  double false_alarms_per_tick = 0.0;  ///< Poisson mean per sensor and tick
  double range = 200.0;                ///< coverage radius when the sensor's entry gives none
  double fov_deg = 360.0;              ///< field of view when the sensor's entry gives none
  double height = 0.0;                 ///< mast height when the sensor's entry gives none
  double sigma_bearing_deg = 1.0;      ///< sigma_theta
  double sigma_elevation_deg = 0.1;    ///< sigma_phi
  double sigma_range = 5.0;            ///< sigma_rho
  double sigma_range_rate = 0.3;       ///< sigma_rho_dot, per tick
  double max_range_rate = 20.0;        ///< false alarms' rho_dot is uniform in +-this, per tick
  double sigma_position = 1.0;         ///< per axis, of a presence reported at the sensor
  friend bool operator==(const TypeSettings&, const TypeSettings&) = default;
};

class SensorType;

/// One placed sensor with its type's defaults filled in: what a type measures with.
struct FieldSensor {
  common::SensorId id = 0;
  common::Vec2 position;    ///< true position: where it measures from
  common::SensorPose pose;  ///< believed position and heading: what its reports carry
  double heading = 0.0;     ///< radians counter-clockwise from +x
  double fov = 0.0;         ///< radians, (0, 2 pi]
  double range = 0.0;
  double height = 0.0;
  const SensorType* type = nullptr;
  const TypeSettings* settings = nullptr;
};

/// A target as a sensor sees it from its true position: ground range, bearing from the heading in
/// (-pi, pi], range rate and speed (per tick).
struct TargetView {
  double rho = 0.0;
  double theta = 0.0;
  double rho_dot = 0.0;
  double speed = 0.0;
};

using common::wrapAngle;

TargetView viewOf(const FieldSensor& sensor, const common::TargetState& target);

/// Table I's coverage (common::inSector from the sensor's true position) and the spec's eq. 9
/// assumption that only a target moving at >= min_speed per tick is detectable. Line of sight is
/// not here: it belongs to the terrain.
bool covers(const FieldSensor& sensor, const common::TargetState& target, double min_speed);

/// One type of sensor.
class SensorType {
 public:
  virtual ~SensorType() = default;
  /// The value of `type` in a sensors.list item, and its sub-section of sensor_model.
  virtual std::string_view name() const = 0;
  virtual common::MeasurementKind kind() const = 0;
  /// For the key tables: what it is and where its values come from.
  virtual std::string_view description() const = 0;
  /// Spec §1 PROP with Delta = 1 tick = 1 s.
  virtual TypeSettings defaults() const = 0;
  /// The keys of TypeSettings it reads besides detection_probability, false_alarms_per_tick,
  /// range and fov_deg.
  virtual std::vector<std::string> ownKeys() const = 0;
  /// h(x) without noise (eq. 3); angles from the heading, in (-pi, pi].
  virtual std::vector<double> measure(const FieldSensor& sensor, const TargetView& view) const = 0;
  /// R, row-major.
  virtual std::vector<double> noise(const FieldSensor& sensor) const = 0;
  /// z = h(x) + b, b ~ N(0, R) (eq. 2). The default draws b per axis of a diagonal R and re-wraps
  /// the angles.
  virtual std::vector<double> perturb(std::vector<double> h, const FieldSensor& sensor, common::Stream& draw) const;
  /// One false alarm's values, uniform over the sensor's measurement space within its coverage.
  virtual std::vector<double> falseAlarm(const FieldSensor& sensor, common::Stream& draw) const = 0;
  /// The volume of the space falseAlarm() draws from (rad for a bearing, m x rad x m/s for a radar,
  /// m^2 for a presence): the false alarms per tick over it are the clutter density its reports carry.
  virtual double falseAlarmVolume(const FieldSensor& sensor) const = 0;
  /// c_k of a detection of a target of class `truth` (ONERA eq. 19-20, spec §4 PROP): c = CM[., d]
  /// with the declared class d ~ CM[truth, .] drawn from `draw`. Empty for a type that does not
  /// classify (the default) and for a target of unknown class.
  virtual std::vector<double> classLikelihoods(const FieldSensor&, common::TargetClass /*truth*/,
                                               common::Stream& /*draw*/) const {
    return {};
  }
  /// The masks that hide a target from it (eq. 15's line of sight); presence and acoustic
  /// sensors are hidden by none.
  virtual common::SightBlockers blockers() const { return common::SightBlockers::none; }
  /// Whether its report only says that a target is within its coverage (PresenceType).
  virtual bool presence() const { return false; }
};

/// The value of z = h at a presence type's sensor: its believed position, which is what ONERA's
/// h_mag is. Such types report no noise on it: R describes where the target is around the sensor.
class PresenceType : public SensorType {
 public:
  common::MeasurementKind kind() const override { return common::MeasurementKind::position; }
  bool presence() const override { return true; }
  std::vector<double> measure(const FieldSensor& sensor, const TargetView&) const override {
    return {sensor.pose.x, sensor.pose.y};
  }
  std::vector<double> perturb(std::vector<double> h, const FieldSensor&, common::Stream&) const override { return h; }
  std::vector<double> falseAlarm(const FieldSensor& sensor, common::Stream&) const override {
    return {sensor.pose.x, sensor.pose.y};
  }
  /// A false presence stands for a target anywhere in the sensor's disc.
  double falseAlarmVolume(const FieldSensor& sensor) const override {
    return std::numbers::pi * sensor.range * sensor.range;
  }
};

/// c = CM[., d], d ~ CM[truth, .] by one uniform of `draw`, with the PROP confusion matrix of
/// `classifier` (common/class_evidence.hpp): what a classifying type's classLikelihoods() returns.
/// Empty for Classifier::kNone and for a truth of kUnknown.
std::vector<double> declaredClassLikelihoods(common::Classifier classifier, common::TargetClass truth,
                                             common::Stream& draw);

/// Degrees to radians.
constexpr double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

/// A diagonal R, row-major, from the standard deviations.
std::vector<double> diagonalNoise(std::initializer_list<double> sigmas);

/// Every type, in table order (sensor_types.cpp).
const std::vector<std::unique_ptr<const SensorType>>& sensorTypes();
/// The type called `name`, or nullptr.
const SensorType* sensorTypeNamed(std::string_view name);

// The types of Table I, one file each.
std::unique_ptr<const SensorType> makeAcousticAntenna();
std::unique_ptr<const SensorType> makeAcousticBeacon();
std::unique_ptr<const SensorType> makeMagnetic();
std::unique_ptr<const SensorType> makePir();
std::unique_ptr<const SensorType> makeRadar();
std::unique_ptr<const SensorType> makeCamera();

}  // namespace wsn::node::field_sensors

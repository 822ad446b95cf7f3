// Camera (Table I: micro-cameras, FIR, JIM LR, Cham: theta, phi and classes; fields of view 5° to
// 50°, < 100 or 200 m) on a mast of height h looking at targets on the ground.
#include <cmath>
#include <numbers>

#include "node/field_sensors/sensor_type.hpp"

namespace wsn::node::field_sensors {
namespace {

class Camera final : public SensorType {
 public:
  std::string_view name() const override { return "camera"; }
  std::vector<double> classLikelihoods(const FieldSensor&, common::TargetClass truth,
                                       common::Stream& draw) const override {
    return declaredClassLikelihoods(common::Classifier::kCamera, truth, draw);  // spec §4 PROP: a = 0.85
  }
  common::MeasurementKind kind() const override { return common::MeasurementKind::azimuth_elevation; }
  // An optical sensor: buildings and vegetation both hide a target.
  common::SightBlockers blockers() const override { return common::SightBlockers::buildings_and_vegetation; }
  std::string_view description() const override {
    return "camera: (θ, φ) from a mast, φ = atan2(−h, ρ) (Table I: 5° to 50°, < 100 or 200 m); σθ = σφ = 0.1°, a 3 m "
           "mast, PD 0.9 and 0.01 false alarms per tick proposed";
  }
  TypeSettings defaults() const override {
    TypeSettings s;
    s.detection_probability = 0.9;
    s.false_alarms_per_tick = 0.01;
    s.range = 200.0;
    s.fov_deg = 30.0;
    s.height = 3.0;
    s.sigma_bearing_deg = 0.1;
    s.sigma_elevation_deg = 0.1;
    return s;
  }
  std::vector<std::string> ownKeys() const override { return {"height", "sigma_bearing_deg", "sigma_elevation_deg"}; }
  std::vector<double> measure(const FieldSensor& sensor, const TargetView& view) const override {
    return {view.theta, std::atan2(-sensor.height, view.rho)};
  }
  std::vector<double> noise(const FieldSensor& sensor) const override {
    const TypeSettings& s = *sensor.settings;
    return diagonalNoise({radians(s.sigma_bearing_deg), radians(s.sigma_elevation_deg)});
  }
  /// Uniform over the azimuths of the field of view and the elevations of the ground within range,
  /// from straight down to atan2(-h, range).
  std::vector<double> falseAlarm(const FieldSensor& sensor, common::Stream& draw) const override {
    const double theta = wrapAngle(draw.uniform(-0.5 * sensor.fov, 0.5 * sensor.fov));
    const double phi = draw.uniform(-0.5 * std::numbers::pi, std::atan2(-sensor.height, sensor.range));
    return {theta, phi};
  }
  double falseAlarmVolume(const FieldSensor& sensor) const override {
    return sensor.fov * (std::atan2(-sensor.height, sensor.range) + 0.5 * std::numbers::pi);
  }
};

}  // namespace

std::unique_ptr<const SensorType> makeCamera() { return std::make_unique<Camera>(); }

}  // namespace wsn::node::field_sensors

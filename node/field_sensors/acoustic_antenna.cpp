// Acoustic antenna (Table I: theta and classes, spherical coverage < 200 m): a small microphone
// array's direction of arrival.
#include "node/field_sensors/sensor_type.hpp"

namespace wsn::node::field_sensors {
namespace {

class AcousticAntenna final : public SensorType {
 public:
  std::string_view name() const override { return "acoustic_antenna"; }
  std::vector<double> classLikelihoods(const FieldSensor&, common::TargetClass truth,
                                       common::Stream& draw) const override {
    return declaredClassLikelihoods(common::Classifier::kAcoustic, truth, draw);  // spec §4 PROP: a = 0.6
  }
  common::MeasurementKind kind() const override { return common::MeasurementKind::bearing; }
  std::string_view description() const override {
    return "acoustic antenna: bearing θ (Table I, < 200 m, all round); σθ 3° (small arrays give 2–5°), PD 0.8 and "
           "0.01 false alarms per tick with uniform θ proposed";
  }
  TypeSettings defaults() const override {
    TypeSettings s;
    s.detection_probability = 0.8;
    s.false_alarms_per_tick = 0.01;
    s.range = 200.0;
    s.fov_deg = 360.0;
    s.sigma_bearing_deg = 3.0;
    return s;
  }
  std::vector<std::string> ownKeys() const override { return {"sigma_bearing_deg"}; }
  std::vector<double> measure(const FieldSensor&, const TargetView& view) const override { return {view.theta}; }
  std::vector<double> noise(const FieldSensor& sensor) const override {
    return diagonalNoise({radians(sensor.settings->sigma_bearing_deg)});
  }
  std::vector<double> falseAlarm(const FieldSensor& sensor, common::Stream& draw) const override {
    return {wrapAngle(draw.uniform(-0.5 * sensor.fov, 0.5 * sensor.fov))};
  }
  double falseAlarmVolume(const FieldSensor& sensor) const override { return sensor.fov; }
};

}  // namespace

std::unique_ptr<const SensorType> makeAcousticAntenna() { return std::make_unique<AcousticAntenna>(); }

}  // namespace wsn::node::field_sensors

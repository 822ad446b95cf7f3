// Passive infrared detector (Table I: theta, mono or multi beam, < 200 m): it knows only that the
// target is in its beam, so its bearing's spread is the beam's, sigma = fov / sqrt 12.
#include <cmath>

#include "node/field_sensors/sensor_type.hpp"

namespace wsn::node::field_sensors {
namespace {

class Pir final : public SensorType {
 public:
  std::string_view name() const override { return "pir"; }
  common::MeasurementKind kind() const override { return common::MeasurementKind::bearing; }
  // An optical sensor: buildings and vegetation both hide a target.
  common::SightBlockers blockers() const override { return common::SightBlockers::buildings_and_vegetation; }
  std::string_view description() const override {
    return "PIR: bearing θ of a target in its beam (Table I, < 200 m) with σθ = fov/√12 (a uniform spread over the "
           "beam: 2.9° for 10°); PD 0.9 and no false alarms (§V) proposed";
  }
  TypeSettings defaults() const override {
    TypeSettings s;
    s.detection_probability = 0.9;
    s.false_alarms_per_tick = 0.0;
    s.range = 200.0;
    s.fov_deg = 10.0;
    return s;
  }
  std::vector<std::string> ownKeys() const override { return {}; }
  std::vector<double> measure(const FieldSensor&, const TargetView& view) const override { return {view.theta}; }
  std::vector<double> noise(const FieldSensor& sensor) const override {
    return diagonalNoise({sensor.fov / std::sqrt(12.0)});
  }
  std::vector<double> falseAlarm(const FieldSensor& sensor, common::Stream& draw) const override {
    return {wrapAngle(draw.uniform(-0.5 * sensor.fov, 0.5 * sensor.fov))};
  }
  double falseAlarmVolume(const FieldSensor& sensor) const override { return sensor.fov; }
};

}  // namespace

std::unique_ptr<const SensorType> makePir() { return std::make_unique<Pir>(); }

}  // namespace wsn::node::field_sensors

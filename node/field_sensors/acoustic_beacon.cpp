// Acoustic beacon (Table I: "volume" and classes, spherical coverage < 200 m): it says only that a
// target is within its range, reported as a position at the sensor.
#include "node/field_sensors/sensor_type.hpp"

namespace wsn::node::field_sensors {
namespace {

class AcousticBeacon final : public PresenceType {
 public:
  std::string_view name() const override { return "acoustic_beacon"; }
  std::vector<double> classLikelihoods(const FieldSensor&, common::TargetClass truth,
                                       common::Stream& draw) const override {
    return declaredClassLikelihoods(common::Classifier::kAcoustic, truth, draw);  // spec §4 PROP: a = 0.6
  }
  std::string_view description() const override {
    return "acoustic beacon: presence within range (Table I, < 200 m), reported at the sensor with R = (range/2)² I "
           "(a uniform disc's); PD 0.8 and 0.01 false alarms per tick proposed";
  }
  TypeSettings defaults() const override {
    TypeSettings s;
    s.detection_probability = 0.8;
    s.false_alarms_per_tick = 0.01;
    s.range = 200.0;
    s.fov_deg = 360.0;
    return s;
  }
  std::vector<std::string> ownKeys() const override { return {}; }
  std::vector<double> noise(const FieldSensor& sensor) const override {
    return diagonalNoise({0.5 * sensor.range, 0.5 * sensor.range});
  }
};

}  // namespace

std::unique_ptr<const SensorType> makeAcousticBeacon() { return std::make_unique<AcousticBeacon>(); }

}  // namespace wsn::node::field_sensors

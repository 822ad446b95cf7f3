// Magnetic detector (Table I: "volume" and classes, spherical coverage < 2 m; eq. 3's h_mag is the
// sensor's own position).
#include "node/field_sensors/sensor_type.hpp"

namespace wsn::node::field_sensors {
namespace {

class Magnetic final : public PresenceType {
 public:
  std::string_view name() const override { return "magnetic"; }
  std::vector<double> classLikelihoods(const FieldSensor&, common::TargetClass truth,
                                       common::Stream& draw) const override {
    return declaredClassLikelihoods(common::Classifier::kMagnetic, truth, draw);  // spec §4 PROP: a = 0.9 per block
  }
  std::string_view description() const override {
    return "magnetic detector: presence within range (Table I, < 2 m), reported at the sensor (eq. 3: h_mag) with "
           "R = σ² I; σ 1 m, PD 0.95 (vehicles) and no false alarms (§V) proposed";
  }
  TypeSettings defaults() const override {
    TypeSettings s;
    s.detection_probability = 0.95;
    s.false_alarms_per_tick = 0.0;
    s.range = 2.0;
    s.fov_deg = 360.0;
    s.sigma_position = 1.0;
    return s;
  }
  std::vector<std::string> ownKeys() const override { return {"sigma_position"}; }
  std::vector<double> noise(const FieldSensor& sensor) const override {
    return diagonalNoise({sensor.settings->sigma_position, sensor.settings->sigma_position});
  }
};

}  // namespace

std::unique_ptr<const SensorType> makeMagnetic() { return std::make_unique<Magnetic>(); }

}  // namespace wsn::node::field_sensors

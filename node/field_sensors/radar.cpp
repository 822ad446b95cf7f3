// Ground radar (Table I: rho, theta, rho_dot over a 90° sector, < 1000 m).
#include "node/field_sensors/sensor_type.hpp"

namespace wsn::node::field_sensors {
namespace {

class Radar final : public SensorType {
 public:
  std::string_view name() const override { return "radar"; }
  common::MeasurementKind kind() const override { return common::MeasurementKind::range_bearing_rate; }
  // Its waves pass through foliage, not through buildings (docs/ONERA.md §9).
  common::SightBlockers blockers() const override { return common::SightBlockers::buildings; }
  std::string_view description() const override {
    return "radar: (ρ, θ, ρ̇) over a 90° sector to 1000 m (Table I); σρ 5, σθ 1°, σρ̇ 0.3, PD 0.9 and 0.2 false "
           "alarms per scan uniform over sector × range × ρ̇ ∈ ±20 proposed";
  }
  TypeSettings defaults() const override {
    TypeSettings s;
    s.detection_probability = 0.9;
    s.false_alarms_per_tick = 0.2;
    s.range = 1000.0;
    s.fov_deg = 90.0;
    s.sigma_range = 5.0;
    s.sigma_bearing_deg = 1.0;
    s.sigma_range_rate = 0.3;
    s.max_range_rate = 20.0;
    return s;
  }
  std::vector<std::string> ownKeys() const override {
    return {"sigma_range", "sigma_bearing_deg", "sigma_range_rate", "max_range_rate"};
  }
  std::vector<double> measure(const FieldSensor&, const TargetView& view) const override {
    return {view.rho, view.theta, view.rho_dot};
  }
  std::vector<double> noise(const FieldSensor& sensor) const override {
    const TypeSettings& s = *sensor.settings;
    return diagonalNoise({s.sigma_range, radians(s.sigma_bearing_deg), s.sigma_range_rate});
  }
  std::vector<double> falseAlarm(const FieldSensor& sensor, common::Stream& draw) const override {
    const double rho = draw.uniform(0.0, sensor.range);
    const double theta = wrapAngle(draw.uniform(-0.5 * sensor.fov, 0.5 * sensor.fov));
    const double rho_dot = draw.uniform(-sensor.settings->max_range_rate, sensor.settings->max_range_rate);
    return {rho, theta, rho_dot};
  }
  double falseAlarmVolume(const FieldSensor& sensor) const override {
    return sensor.range * sensor.fov * 2.0 * sensor.settings->max_range_rate;
  }
};

}  // namespace

std::unique_ptr<const SensorType> makeRadar() { return std::make_unique<Radar>(); }

}  // namespace wsn::node::field_sensors

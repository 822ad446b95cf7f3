#include <cmath>

#include "node/field_sensors/sensor_type.hpp"

namespace wsn::node::field_sensors {

TargetView viewOf(const FieldSensor& sensor, const common::TargetState& target) {
  const double dx = target.x - sensor.position.x;
  const double dy = target.y - sensor.position.y;
  TargetView view;
  view.rho = std::hypot(dx, dy);
  view.theta = wrapAngle(std::atan2(dy, dx) - sensor.heading);
  view.rho_dot = view.rho > 0.0 ? (dx * target.vx + dy * target.vy) / view.rho : 0.0;
  view.speed = std::hypot(target.vx, target.vy);
  return view;
}

bool covers(const FieldSensor& sensor, const common::TargetState& target, double min_speed) {
  if (std::hypot(target.vx, target.vy) < min_speed) return false;
  return common::inSector(sensor.position, sensor.heading, sensor.fov, sensor.range, {target.x, target.y});
}

std::vector<double> diagonalNoise(std::initializer_list<double> sigmas) {
  const std::size_t n = sigmas.size();
  std::vector<double> r(n * n, 0.0);
  std::size_t i = 0;
  for (const double sigma : sigmas) {
    r[i * n + i] = sigma * sigma;
    ++i;
  }
  return r;
}

std::vector<double> SensorType::perturb(std::vector<double> h, const FieldSensor& sensor, common::Stream& draw) const {
  const std::vector<double> r = noise(sensor);
  const std::size_t n = h.size();
  for (std::size_t i = 0; i < n; ++i) h[i] += std::sqrt(r[i * n + i]) * draw.normal();
  // The angles of each kind, in its order (common/measurement.hpp).
  switch (kind()) {
    case common::MeasurementKind::bearing: h[0] = wrapAngle(h[0]); break;
    case common::MeasurementKind::range_bearing_rate: h[1] = wrapAngle(h[1]); break;
    case common::MeasurementKind::azimuth_elevation:
      h[0] = wrapAngle(h[0]);
      h[1] = wrapAngle(h[1]);
      break;
    default: break;
  }
  return h;
}

std::vector<double> declaredClassLikelihoods(common::Classifier classifier, common::TargetClass truth,
                                             common::Stream& draw) {
  if (classifier == common::Classifier::kNone || truth == common::TargetClass::kUnknown) return {};
  // The matrices are constants: built once, not at every detection.
  static const common::ConfusionMatrix camera = common::confusionMatrix(common::Classifier::kCamera);
  static const common::ConfusionMatrix acoustic = common::confusionMatrix(common::Classifier::kAcoustic);
  static const common::ConfusionMatrix magnetic = common::confusionMatrix(common::Classifier::kMagnetic);
  const common::ConfusionMatrix& cm = classifier == common::Classifier::kCamera     ? camera
                                      : classifier == common::Classifier::kAcoustic ? acoustic
                                                                                    : magnetic;
  return common::reportedClassLikelihoods(cm, truth, draw.uniform());
}

const std::vector<std::unique_ptr<const SensorType>>& sensorTypes() {
  static const std::vector<std::unique_ptr<const SensorType>> types = [] {
    std::vector<std::unique_ptr<const SensorType>> all;
    all.push_back(makeAcousticAntenna());
    all.push_back(makeAcousticBeacon());
    all.push_back(makeMagnetic());
    all.push_back(makePir());
    all.push_back(makeRadar());
    all.push_back(makeCamera());
    // A new type: its file, and one line here.
    return all;
  }();
  return types;
}

const SensorType* sensorTypeNamed(std::string_view name) {
  for (const auto& type : sensorTypes())
    if (type->name() == name) return type.get();
  return nullptr;
}

}  // namespace wsn::node::field_sensors

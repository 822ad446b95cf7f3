#include "supernode/sbmht/imm.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace wsn::supernode::sbmht {
namespace {

using common::GaussianState;
using common::kVx;
using common::kVy;
using common::kX;
using common::kY;
using common::StateMatrix;
using common::StateVector;

using NoiseGain = Eigen::Matrix<double, common::kStateDim, 2>;

/// Gamma of the paper's ref. [8] on [x, y, vx, vy]: a 2-D acceleration held over dt.
NoiseGain accelerationGain(double dt) {
  NoiseGain G = NoiseGain::Zero();
  G(kX, 0) = dt * dt / 2.0;
  G(kY, 1) = dt * dt / 2.0;
  G(kVx, 0) = dt;
  G(kVy, 1) = dt;
  return G;
}

StateMatrix constantVelocityTransition(double dt) {
  StateMatrix F = StateMatrix::Identity();
  F(kX, kVx) = dt;
  F(kY, kVy) = dt;
  return F;
}

StateMatrix symmetric(const StateMatrix& P) { return 0.5 * (P + P.transpose()); }

}  // namespace

MotionModel stopModel(double dt, double position_sigma) {
  MotionModel m;
  m.kind = MotionKind::stop;
  m.F = StateMatrix::Identity();
  m.F(kVx, kVx) = 0.0;
  m.F(kVy, kVy) = 0.0;
  m.Q(kX, kX) = position_sigma * position_sigma * dt;
  m.Q(kY, kY) = position_sigma * position_sigma * dt;
  return m;
}

MotionModel constantVelocityModel(double dt, double acceleration_sigma) {
  MotionModel m;
  m.kind = MotionKind::constant_velocity;
  m.F = constantVelocityTransition(dt);
  const NoiseGain G = accelerationGain(dt);
  m.Q = symmetric(G * (acceleration_sigma * acceleration_sigma) * G.transpose());
  return m;
}

MotionModel roadModel(double dt, double road_direction, double along_sigma, double across_sigma) {
  MotionModel m;
  m.kind = MotionKind::road;
  m.F = constantVelocityTransition(dt);
  Eigen::Matrix2d rotation;
  rotation << std::cos(road_direction), -std::sin(road_direction), std::sin(road_direction), std::cos(road_direction);
  const Eigen::Matrix2d acceleration_covariance =
      rotation * Eigen::Vector2d(along_sigma * along_sigma, across_sigma * across_sigma).asDiagonal() *
      rotation.transpose();
  const NoiseGain G = accelerationGain(dt);
  m.Q = symmetric(G * acceleration_covariance * G.transpose());
  return m;
}

TransitionMatrix transitionMatrix(double dt, std::span<const double> time_constants) {
  const auto n = static_cast<Eigen::Index>(time_constants.size());
  TransitionMatrix pi = TransitionMatrix::Identity(n, n);
  if (n < 2) return pi;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double stay = std::exp(-dt / time_constants[static_cast<std::size_t>(i)]);
    for (Eigen::Index j = 0; j < n; ++j) pi(i, j) = i == j ? stay : (1.0 - stay) / static_cast<double>(n - 1);
  }
  return pi;
}

GaussianState momentMatch(std::span<const GaussianState> components, const ModeVector& weights) {
  GaussianState out;
  for (std::size_t i = 0; i < components.size(); ++i) out.x += weights(static_cast<Eigen::Index>(i)) * components[i].x;
  for (std::size_t i = 0; i < components.size(); ++i) {
    const StateVector spread = components[i].x - out.x;
    out.P += weights(static_cast<Eigen::Index>(i)) * (components[i].P + spread * spread.transpose());
  }
  out.P = symmetric(out.P);
  return out;
}

ImmState ImmState::startAt(const GaussianState& estimate, const ModeVector& probabilities) {
  ImmState s;
  s.modes.assign(static_cast<std::size_t>(probabilities.size()), estimate);
  s.probabilities = probabilities;
  return s;
}

GaussianState ImmState::combined() const { return momentMatch(modes, probabilities); }
GaussianState ImmPrediction::combined() const { return momentMatch(modes, probabilities); }

Detectability Detectability::uniform(double detection_probability, double perceivability) {
  return {detection_probability, ModeVector::Constant(1, perceivability)};
}

double Detectability::perceivabilityOf(std::size_t model) const {
  if (perceivability.size() == 0) return 1.0;
  if (perceivability.size() == 1) return perceivability(0);
  return perceivability(static_cast<Eigen::Index>(model));
}

Imm::Imm(std::vector<MotionModel> models, TransitionMatrix transition)
    : models_(std::move(models)), transition_(std::move(transition)) {
  const auto n = static_cast<Eigen::Index>(models_.size());
  if (n == 0 || transition_.rows() != n || transition_.cols() != n)
    throw std::invalid_argument("Imm: Pi must be " + std::to_string(n) + " x " + std::to_string(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(transition_.row(i).array() >= 0.0).all() || std::abs(transition_.row(i).sum() - 1.0) > 1e-9)
      throw std::invalid_argument("Imm: row " + std::to_string(i) + " of Pi is not a probability distribution");
  }
}

ImmPrediction Imm::predict(const ImmState& state) const {
  const auto n = static_cast<Eigen::Index>(models_.size());
  if (state.modes.size() != models_.size() || state.probabilities.size() != n)
    throw std::invalid_argument("Imm::predict: the state has " + std::to_string(state.modes.size()) +
                                " modes for " + std::to_string(models_.size()) + " models");
  ImmPrediction out;
  out.probabilities = transition_.transpose() * state.probabilities;
  out.modes.reserve(models_.size());
  for (Eigen::Index j = 0; j < n; ++j) {
    const double cbar = out.probabilities(j);
    // A model nothing can switch into has no mixture to draw from; its own estimate is as good as any.
    GaussianState mixed = state.modes[static_cast<std::size_t>(j)];
    if (cbar > 0.0) {
      const ModeVector mixing = transition_.col(j).cwiseProduct(state.probabilities) / cbar;
      mixed = momentMatch(state.modes, mixing);
    }
    const MotionModel& model = models_[static_cast<std::size_t>(j)];
    GaussianState predicted;
    predicted.x = model.F * mixed.x;
    predicted.P = symmetric(model.F * mixed.P * model.F.transpose() + model.Q);
    out.modes.push_back(predicted);
  }
  return out;
}

ImmUpdate Imm::report(const ImmPrediction& prediction, const MeasurementModel& model, const MeasurementVector& z,
                      const MeasurementCovariance& R, const Detectability& detectability) const {
  checkSizes(prediction, detectability);
  const auto n = static_cast<Eigen::Index>(models_.size());
  std::vector<GaussianState> modes = prediction.modes;
  ModeVector likelihoods = ModeVector::Zero(n);
  double gate_distance = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto index = static_cast<std::size_t>(i);
    const auto updated = update(prediction.modes[index], model, z, R);
    if (!updated) continue;
    // The stop model takes the report too, so that its estimate stays near the data, but a
    // detection rules it out (eq. 9: {M^0, d = 1} is empty), so its weight becomes 0.
    modes[index] = updated->state;
    if (!models_[index].moving()) continue;
    gate_distance = std::min(gate_distance, updated->mahalanobis_squared);
    likelihoods(i) = detectability.detection_probability * updated->likelihood * detectability.perceivabilityOf(index);
  }
  ImmUpdate out = posterior(prediction, std::move(modes), std::move(likelihoods));
  out.gate_distance = gate_distance;
  return out;
}

ImmUpdate Imm::miss(const ImmPrediction& prediction, const Detectability& detectability) const {
  checkSizes(prediction, detectability);
  const auto n = static_cast<Eigen::Index>(models_.size());
  ModeVector likelihoods(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto index = static_cast<std::size_t>(i);
    const double pe = detectability.perceivabilityOf(index);
    likelihoods(i) =
        models_[index].moving() ? (1.0 - detectability.detection_probability) * pe + (1.0 - pe) : 1.0;
  }
  ImmUpdate out = posterior(prediction, prediction.modes, std::move(likelihoods));
  out.gate_distance = std::numeric_limits<double>::infinity();
  return out;
}

ImmUpdate Imm::stepWithReport(const ImmState& state, const MeasurementModel& model, const MeasurementVector& z,
                              const MeasurementCovariance& R, const Detectability& detectability) const {
  return report(predict(state), model, z, R, detectability);
}

ImmUpdate Imm::stepWithMiss(const ImmState& state, const Detectability& detectability) const {
  return miss(predict(state), detectability);
}

void Imm::checkSizes(const ImmPrediction& prediction, const Detectability& detectability) const {
  const auto n = static_cast<Eigen::Index>(models_.size());
  if (prediction.modes.size() != models_.size() || prediction.probabilities.size() != n)
    throw std::invalid_argument("Imm: the prediction has " + std::to_string(prediction.modes.size()) +
                                " modes for " + std::to_string(models_.size()) + " models");
  const Eigen::Index pe = detectability.perceivability.size();
  if (pe != 0 && pe != 1 && pe != n)
    throw std::invalid_argument("Imm: " + std::to_string(pe) + " perceivabilities for " + std::to_string(n) +
                                " models");
}

ImmUpdate Imm::posterior(const ImmPrediction& prediction, std::vector<GaussianState> modes,
                         ModeVector likelihoods) const {
  ImmUpdate out;
  const ModeVector weighted = likelihoods.cwiseProduct(prediction.probabilities);
  out.likelihood = weighted.sum();
  out.state.modes = std::move(modes);
  out.state.probabilities = out.likelihood > 0.0 ? ModeVector(weighted / out.likelihood) : prediction.probabilities;
  out.model_likelihoods = std::move(likelihoods);
  return out;
}

}  // namespace wsn::supernode::sbmht

// The interacting multiple model (IMM) estimator of ONERA §III-B/C/D: a stop model, constant-velocity
// and road-constrained motion models, Markov switching, and model likelihoods with perceivability (eq. 14).
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "common/kalman.hpp"
#include "supernode/sbmht/measurement_models.hpp"

namespace wsn::supernode::sbmht {

/// What a motion model assumes; the stop model is the one a detection rules out (eq. 9).
enum class MotionKind { stop, constant_velocity, road };

/// x_k = F x_{k-1} + w, w ~ N(0, Q), on common/kalman.hpp's state [x, y, vx, vy].
struct MotionModel {
  MotionKind kind = MotionKind::constant_velocity;
  common::StateMatrix F = common::StateMatrix::Identity();
  common::StateMatrix Q = common::StateMatrix::Zero();
  bool moving() const { return kind != MotionKind::stop; }
};

/// Model 0 (docs/ONERA.md §2): the velocity is zeroed and the position wanders by position_sigma per second.
/// docs/ONERA.md proposes Q0 = (0.1 m)^2 per 1 s scan; it grows with dt here so that two reports of the
/// same instant (dt = 0, scans ordered by sensor id) do not add noise twice.
MotionModel stopModel(double dt, double position_sigma = 0.1);

/// Constant velocity with white acceleration of acceleration_sigma per axis, Gamma = [dt^2/2, dt]'.
MotionModel constantVelocityModel(double dt, double acceleration_sigma);

/// Constant velocity on a road whose direction is road_direction (radians counter-clockwise from
/// +x), eq. 6: the acceleration covariance is R_theta diag(along^2, across^2) R_theta', so the
/// target speeds up and slows down along the road more easily than it leaves it.
MotionModel roadModel(double dt, double road_direction, double along_sigma, double across_sigma);

/// Pi(i, j) = P(model j now | model i before); each row sums to 1.
using TransitionMatrix = Eigen::MatrixXd;
/// One probability (or likelihood) per model.
using ModeVector = Eigen::VectorXd;

/// The proposed Pi (docs/ONERA.md §2) from mean sojourn times: p_ii = exp(-dt / tau_i), the rest of row i split evenly
/// among the other models (so Pi = I at dt = 0). One model gives [[1]].
TransitionMatrix transitionMatrix(double dt, std::span<const double> time_constants);

/// A track's IMM estimate: one Gaussian per model and the model probabilities mu.
struct ImmState {
  std::vector<common::GaussianState> modes;
  ModeVector probabilities;

  /// Every model starting from the same estimate.
  static ImmState startAt(const common::GaussianState& estimate, const ModeVector& probabilities);
  /// The moment-matched single Gaussian: what the track reports.
  common::GaussianState combined() const;
};

/// What every branch of a track starts from at a scan: the mixed and predicted estimate of each
/// model and cbar_j = sum_i pi_ij mu^i (= mu_{k|k-1} of eq. 10). One prediction serves the miss
/// branch and every gated report.
struct ImmPrediction {
  std::vector<common::GaussianState> modes;
  ModeVector probabilities;

  common::GaussianState combined() const;
};

/// Whether the target could have been seen: the reporting sensor's PD and the perceivability
/// Pe = P{O | Z, M^i} of eq. 15 at each model's predicted position (line of sight, ground
/// attenuation...). Pe of the stop model is not used: Lambda^0 = delta_{d,0} whatever Pe (docs/ONERA.md §2).
struct Detectability {
  double detection_probability = 1.0;
  /// One per model, or one for all; empty means perceivable for every model (Pe = 1).
  ModeVector perceivability;

  /// The same Pe for every model.
  static Detectability uniform(double detection_probability, double perceivability = 1.0);
  double perceivabilityOf(std::size_t model) const;
};

/// The IMM after a report or a miss.
struct ImmUpdate {
  ImmState state;
  /// Lambda^i of eq. 14 (with Lambda^0 = delta_{d,0} for the stop model).
  ModeVector model_likelihoods;
  /// Lambda_k = sum_i Lambda^i cbar_i (eq. 10): the track score's likelihood. 0 when no model
  /// can explain the report; mu then stays at cbar.
  double likelihood = 0.0;
  /// Smallest d^2 of the report over the moving models (+inf on a miss, or when no moving model
  /// could be updated): the report is in the track's gate when this is <= gateThreshold(M).
  double gate_distance = 0.0;
};

/// An IMM over a fixed model set and Pi. A variable-structure IMM (the road model follows the
/// segment) builds a new Imm for each scan; the estimates carry over as long as the model count does.
class Imm {
 public:
  /// Throws std::invalid_argument unless Pi is square, one row per model, non-negative, rows
  /// summing to 1.
  Imm(std::vector<MotionModel> models, TransitionMatrix transition);

  std::size_t size() const { return models_.size(); }
  const std::vector<MotionModel>& models() const { return models_; }
  const TransitionMatrix& transition() const { return transition_; }

  /// Interaction (moment-matched mixing with mu^{i|j} = pi_ij mu^i / cbar_j) and each model's time
  /// update. Throws std::invalid_argument if the state does not have one mode per model (as do
  /// report and miss for a prediction, or a perceivability vector of another length).
  ImmPrediction predict(const ImmState& state) const;

  /// Each model's EKF update by the report, its likelihood Lambda^i = PD p(z | M^i) Pe^i (0 for
  /// the stop model), mu^j = Lambda^j cbar_j / Lambda_k. A model whose EKF fails keeps its
  /// prediction and gets Lambda^i = 0.
  ImmUpdate report(const ImmPrediction& prediction, const MeasurementModel& model, const MeasurementVector& z,
                   const MeasurementCovariance& R, const Detectability& detectability) const;

  /// No report from the sensor at this scan: the estimates stay predicted; Lambda^0 = 1 and,
  /// for a moving model, Lambda^i = (1 - PD) Pe^i + (1 - Pe^i).
  ImmUpdate miss(const ImmPrediction& prediction, const Detectability& detectability) const;

  /// predict then report.
  ImmUpdate stepWithReport(const ImmState& state, const MeasurementModel& model, const MeasurementVector& z,
                           const MeasurementCovariance& R, const Detectability& detectability) const;
  /// predict then miss.
  ImmUpdate stepWithMiss(const ImmState& state, const Detectability& detectability) const;

 private:
  void checkSizes(const ImmPrediction& prediction, const Detectability& detectability) const;
  ImmUpdate posterior(const ImmPrediction& prediction, std::vector<common::GaussianState> modes,
                      ModeVector likelihoods) const;

  std::vector<MotionModel> models_;
  TransitionMatrix transition_;
};

/// The moment-matched Gaussian of a mixture: mean sum w_i x_i and covariance
/// sum w_i (P_i + (x_i - mean)(x_i - mean)'). The weights must sum to 1.
common::GaussianState momentMatch(std::span<const common::GaussianState> components, const ModeVector& weights);

}  // namespace wsn::supernode::sbmht

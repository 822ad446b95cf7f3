// The constant-velocity Kalman filter of Oh et al. eq. (8): fixed-size Eigen matrices and pure
// functions (predict, innovation, update, likelihood), shared by the GNN and MCMCDA engines and
// the aggregator's track fusion.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace wsn::common {

/// Dimension of the state x = [x1, x2, x1', x2']^T and of an observation y = [x1, x2]^T.
inline constexpr int kStateDim = 4;
inline constexpr int kMeasurementDim = 2;

/// Named indices into the state vector.
inline constexpr int kX = 0;
inline constexpr int kY = 1;
inline constexpr int kVx = 2;
inline constexpr int kVy = 3;

using StateVector = Eigen::Matrix<double, kStateDim, 1>;
using StateMatrix = Eigen::Matrix<double, kStateDim, kStateDim>;
using MeasurementVector = Eigen::Matrix<double, kMeasurementDim, 1>;
using MeasurementMatrix = Eigen::Matrix<double, kMeasurementDim, kMeasurementDim>;
using ObservationMatrix = Eigen::Matrix<double, kMeasurementDim, kStateDim>;
using GainMatrix = Eigen::Matrix<double, kStateDim, kMeasurementDim>;

/// A Gaussian state estimate N(x, P).
struct GaussianState {
  StateVector x = StateVector::Zero();
  StateMatrix P = StateMatrix::Zero();
};

/// Oh et al., eq. (8): x_{t+delta} = A_delta x_t + G_delta w_t, y_t = C x_t + v_t, with
/// w ~ N(0, diag(q^2, q^2)) and v ~ N(0, r^2 I). Symbols: F = A_delta, Q = G diag(q^2, q^2) G^T,
/// H = C, R = r^2 I.
struct ConstantVelocityModel {
  StateMatrix F = StateMatrix::Identity();
  StateMatrix Q = StateMatrix::Zero();
  ObservationMatrix H = ObservationMatrix::Zero();
  MeasurementMatrix R = MeasurementMatrix::Identity();

  /// delta: sampling interval; q: process-noise sigma (acceleration); r: observation sigma.
  ConstantVelocityModel(double delta, double q, double r) {
    F(kX, kVx) = delta;
    F(kY, kVy) = delta;
    Eigen::Matrix<double, kStateDim, 2> G = Eigen::Matrix<double, kStateDim, 2>::Zero();
    G(kX, 0) = delta * delta / 2.0;
    G(kY, 1) = delta * delta / 2.0;
    G(kVx, 0) = delta;
    G(kVy, 1) = delta;
    Q = G * (q * q) * G.transpose();
    H(0, kX) = 1.0;
    H(1, kY) = 1.0;
    R = (r * r) * MeasurementMatrix::Identity();
  }
};

/// The innovation nu = z - H x of an observation against a (predicted) state, and its
/// covariance S = H P H^T + R.
struct Innovation {
  MeasurementVector nu = MeasurementVector::Zero();
  MeasurementMatrix S = MeasurementMatrix::Identity();
};

/// P as the row-major 16 numbers that messages carry (TrackEstimate, TrackHandoff).
inline std::array<double, kStateDim * kStateDim> toRowMajor(const StateMatrix& P) {
  std::array<double, kStateDim * kStateDim> out{};
  Eigen::Map<Eigen::Matrix<double, kStateDim, kStateDim, Eigen::RowMajor>>(out.data()) = P;
  return out;
}

/// The inverse of toRowMajor.
inline StateMatrix fromRowMajor(const std::array<double, kStateDim * kStateDim>& values) {
  return Eigen::Map<const Eigen::Matrix<double, kStateDim, kStateDim, Eigen::RowMajor>>(values.data());
}

/// Time update: x <- F x, P <- F P F^T + Q (symmetrised).
inline GaussianState predict(const ConstantVelocityModel& model, const GaussianState& state) {
  GaussianState out;
  out.x = model.F * state.x;
  const StateMatrix P = model.F * state.P * model.F.transpose() + model.Q;
  out.P = 0.5 * (P + P.transpose());
  return out;
}

/// nu and S of observation z against `predicted`.
inline Innovation innovation(const ConstantVelocityModel& model, const GaussianState& predicted,
                             const MeasurementVector& z) {
  Innovation out;
  out.nu = z - model.H * predicted.x;
  const MeasurementMatrix S = model.H * predicted.P * model.H.transpose() + model.R;
  out.S = 0.5 * (S + S.transpose());
  return out;
}

namespace detail {
/// LDLT of S when S is symmetric positive definite (every pivot > 0), else nullopt.
inline std::optional<Eigen::LDLT<MeasurementMatrix>> positiveDefiniteLdlt(const MeasurementMatrix& S) {
  if (!S.allFinite()) return std::nullopt;
  Eigen::LDLT<MeasurementMatrix> ldlt(S);
  if (ldlt.info() != Eigen::Success) return std::nullopt;
  if (!(ldlt.vectorD().array() > 0.0).all()) return std::nullopt;
  return ldlt;
}
}  // namespace detail

/// S = H P H^T + R of one predicted state, factorised once so that many observations can be
/// scored against it (S does not depend on the observation).
class InnovationCovariance {
 public:
  InnovationCovariance(const ConstantVelocityModel& model, const GaussianState& predicted)
      : InnovationCovariance(symmetric(model.H * predicted.P * model.H.transpose() + model.R)) {}
  explicit InnovationCovariance(const MeasurementMatrix& S) : S_(S), ldlt_(detail::positiveDefiniteLdlt(S_)) {}

  const MeasurementMatrix& S() const { return S_; }
  bool positiveDefinite() const { return ldlt_.has_value(); }
  /// d^2 = nu^T S^-1 nu by an LDLT solve (never S.inverse()); +inf when S is not positive
  /// definite, so that the pair falls outside any gate.
  double mahalanobisSquared(const MeasurementVector& nu) const {
    if (!ldlt_) return std::numeric_limits<double>::infinity();
    return nu.dot(ldlt_->solve(nu));
  }
  /// ln det S from the LDLT pivots; +inf when S is not positive definite.
  double logDeterminant() const {
    if (!ldlt_) return std::numeric_limits<double>::infinity();
    return ldlt_->vectorD().array().log().sum();
  }

 private:
  static MeasurementMatrix symmetric(const MeasurementMatrix& S) { return 0.5 * (S + S.transpose()); }
  MeasurementMatrix S_;
  std::optional<Eigen::LDLT<MeasurementMatrix>> ldlt_;
};

/// Squared Mahalanobis distance d^2 = nu^T S^-1 nu; +inf when S is not positive definite.
inline double mahalanobisSquared(const Innovation& innovation) {
  return InnovationCovariance(innovation.S).mahalanobisSquared(innovation.nu);
}

/// ln det S; +inf when S is not positive definite.
inline double logDeterminant(const Innovation& innovation) { return InnovationCovariance(innovation.S).logDeterminant(); }

/// log N(z; H x, S) = -(d^2 + ln det S + m ln 2 pi) / 2 with m = 2; -inf when S is singular.
inline double logLikelihood(const Innovation& innovation) {
  const InnovationCovariance S(innovation.S);
  if (!S.positiveDefinite()) return -std::numeric_limits<double>::infinity();
  return -0.5 * (S.mahalanobisSquared(innovation.nu) + S.logDeterminant() +
                 kMeasurementDim * std::log(2.0 * std::numbers::pi));
}

/// Measurement update with gain K = P H^T S^-1 (LDLT solve) and the Joseph form
/// P <- (I - K H) P (I - K H)^T + K R K^T, which keeps P symmetric positive semidefinite
/// under rounding. Returns nullopt (and the caller keeps the prediction) when S is not
/// positive definite or the result is not finite.
inline std::optional<GaussianState> update(const ConstantVelocityModel& model, const GaussianState& predicted,
                                           const MeasurementVector& z) {
  if (!z.allFinite() || !predicted.x.allFinite() || !predicted.P.allFinite()) return std::nullopt;
  const Innovation inn = innovation(model, predicted, z);
  const auto ldlt = detail::positiveDefiniteLdlt(inn.S);
  if (!ldlt) return std::nullopt;
  // S symmetric: K^T = S^-1 (H P^T) = S^-1 (H P).
  const GainMatrix K = ldlt->solve(model.H * predicted.P).transpose();
  const StateMatrix I_KH = StateMatrix::Identity() - K * model.H;
  GaussianState out;
  out.x = predicted.x + K * inn.nu;
  const StateMatrix P = I_KH * predicted.P * I_KH.transpose() + K * model.R * K.transpose();
  out.P = 0.5 * (P + P.transpose());
  if (!out.x.allFinite() || !out.P.allFinite()) return std::nullopt;
  return out;
}

}  // namespace wsn::common

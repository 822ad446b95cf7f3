// The measurement functions h(x) of ONERA eq. 3 for every kind a field sensor reports, their
// Jacobians, angle-wrapped innovations, and the EKF update with its likelihood and gate distance.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "common/geometry.hpp"
#include "common/kalman.hpp"
#include "common/measurement.hpp"

namespace wsn::supernode::sbmht {

/// Largest dimension of a kind these models handle (range_bearing_rate). Vectors and matrices
/// below are dynamic up to it, so that one EKF serves every kind without a heap allocation.
inline constexpr int kMaxModelDimension = 3;

using MeasurementVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxModelDimension, 1>;
using MeasurementCovariance =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxModelDimension, kMaxModelDimension>;
using MeasurementJacobian =
    Eigen::Matrix<double, Eigen::Dynamic, common::kStateDim, 0, kMaxModelDimension, common::kStateDim>;

/// Below this distance (m) between target and sensor, bearings and range rate are undefined:
/// the model refuses to linearise there rather than divide by zero.
inline constexpr double kMinimumRange = 1e-6;

using common::wrapAngle;  // (-pi, pi], common/geometry.hpp

/// chi^2_M(0.99), the gate on d^2 of an M-dimensional report (docs/ONERA.md §3): 6.635, 9.210 and 11.345 for
/// M = 1, 2, 3 to four digits; +inf for any other M, which no report has.
double gateThreshold(int dimension);

/// The gate on d^2 of an M-dimensional report with the probability that gate_2d has for a 2-D one,
/// P_G = 1 - exp(-gate_2d / 2) (the chi^2 CDF with 2 degrees of freedom): the chi^2_M quantile of
/// P_G. gate_2d itself for M = 2, 0 for M = 0, +inf only where exp(-gate_2d / 2) underflows (gate_2d > ~1490).
double gateOfSameProbability(double gate_2d, int dimension);

/// The measurement function of one report: its kind and the sensor that made it. The state is
/// common/kalman.hpp's x = [x, y, vx, vy] (the paper's eq. 4 orders it [x, vx, y, vy]).
///
/// A camera's mast height h is its pose's height, carried with the report. The target is on the
/// ground, so phi = atan2(-h, rho) < 0, and h = 0 would leave phi without any information on the range.
struct MeasurementModel {
  common::MeasurementKind kind = common::MeasurementKind::position;
  /// Unused by position, which is already in the field frame; only azimuth_elevation reads height.
  common::SensorPose sensor;

  /// M: 2 (position), 1 (bearing), 3 (range_bearing_rate), 2 (azimuth_elevation).
  int dimension() const;
  /// False where h is not differentiable: a target within kMinimumRange of a sensor whose kind
  /// measures angles or range rate.
  bool linearisableAt(const common::StateVector& x) const;
  /// h(x); angles in (-pi, pi], counter-clockwise from the sensor's heading.
  MeasurementVector predict(const common::StateVector& x) const;
  /// dh/dx at x (M x 4); meaningful only where linearisableAt(x).
  MeasurementJacobian jacobian(const common::StateVector& x) const;
  /// nu = z - h(x), every angle wrapped to (-pi, pi] so that a bearing just across +-pi is a small
  /// innovation, not one of almost 2 pi.
  MeasurementVector innovation(const MeasurementVector& z, const common::StateVector& x) const;
};

/// Where one report alone puts a target, to start a track there: a position with its covariance
/// (R carried through the inverse of h) and, from a radar, the velocity along the line of sight.
struct PositionFix {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  /// Unit vector from the sensor to the target, when the report measured the range rate along it.
  std::optional<Eigen::Vector2d> line_of_sight;
  double range_rate = 0.0;
  double range_rate_variance = 0.0;
};

/// The fix of report z (noise R) under `model`: a position is its own; a radar's (rho, theta) and a
/// camera's (theta, phi) from a mast (rho = h / tan(-phi)) are inverted, R carried through the
/// inverse's Jacobian. Nullopt for a bearing (it gives a line, not a point), for a camera that looks
/// level or up (phi >= 0: no ground range), below the nadir (phi <= -pi/2) or from h = 0, and for a
/// non-finite result.
std::optional<PositionFix> positionFix(const MeasurementModel& model, const MeasurementVector& z,
                                       const MeasurementCovariance& R);

/// Where two bearings from two sensors put a target (ONERA §II-C's composite report, docs/ONERA.md
/// §8): the crossing of their rays, R carried through the inverse of the 2 x 2 Jacobian
/// J = d(theta_a, theta_b)/d(x, y), and |det J| = |sin gamma| / (r_a r_b), gamma the angle between
/// the lines of sight, r the ranges. |det J| maps a density over the field into one over the two
/// bearings: a track's score weighs the fix by it (the false-alarm density of the pair in the field).
struct BearingPairFix {
  PositionFix fix;
  double jacobian_determinant = 0.0;  ///< |det J|, in rad^2 per m^2
  double range_a = 0.0;               ///< r_a, from sensor a to the crossing
  double range_b = 0.0;
};

/// The crossing of bearing z_a (variance R_a, 1 x 1) of model_a with bearing z_b of model_b. Nullopt
/// unless both models are bearings with a positive variance, the rays cross in front of both sensors
/// (r > kMinimumRange) and |sin gamma| exceeds min_sine_angle (near-parallel rays cross far along both
/// or nowhere; near-opposed ones, a target on the line through both sensors, anywhere between them).
std::optional<BearingPairFix> bearingPairFix(const MeasurementModel& model_a, const MeasurementVector& z_a,
                                             const MeasurementCovariance& R_a, const MeasurementModel& model_b,
                                             const MeasurementVector& z_b, const MeasurementCovariance& R_b,
                                             double min_sine_angle);

/// The model of measurement m: its kind and pose (with the mast height).
/// Nullopt for a kind no field sensor reports with a state-dependent h (signal_strength, presence),
/// or when m lacks the pose its kind needs.
std::optional<MeasurementModel> modelOf(const common::Measurement& m);

/// m's values as z.
MeasurementVector valuesOf(const common::Measurement& m);

/// R as m's sensor gave it (row-major), or nullopt when it gave none and the engine's own noise
/// model applies.
std::optional<MeasurementCovariance> noiseOf(const common::Measurement& m);

/// One EKF measurement update of a predicted state.
struct EkfUpdate {
  common::GaussianState state;
  MeasurementVector innovation;
  MeasurementCovariance S;
  /// d^2 = nu' S^-1 nu, compared with gateThreshold(M).
  double mahalanobis_squared = 0.0;
  /// ln N(nu; 0, S); the IMM works with likelihood = exp of it.
  double log_likelihood = 0.0;
  double likelihood = 0.0;
};

/// The EKF update of `predicted` by report z with noise R, linearised at the prediction, Joseph
/// form. Nullopt when h cannot be linearised there, S is not positive definite, or the result is
/// not finite; the caller then keeps the prediction and gives the report no likelihood.
std::optional<EkfUpdate> update(const common::GaussianState& predicted, const MeasurementModel& model,
                                const MeasurementVector& z, const MeasurementCovariance& R);

/// The same for a common::Measurement: its kind and pose from m.
std::optional<EkfUpdate> update(const common::GaussianState& predicted, const common::Measurement& m,
                                const MeasurementCovariance& R);

}  // namespace wsn::supernode::sbmht

// The measurement functions h(x) of ONERA eq. 3 for every kind a field sensor reports, their
// Jacobians, angle-wrapped innovations, and the EKF update with its likelihood and gate distance.
#pragma once

#include <optional>

#include <Eigen/Core>

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

/// An angle brought into (-pi, pi].
double wrapAngle(double angle);

/// chi^2_M(0.99), the gate on d^2 of an M-dimensional report (docs/ONERA.md §3): 6.635, 9.210 and 11.345 for
/// M = 1, 2, 3 to four digits; +inf for any other M, which no report has.
double gateThreshold(int dimension);

/// The measurement function of one report: its kind and the sensor that made it. The state is
/// common/kalman.hpp's x = [x, y, vx, vy] (the paper's eq. 4 orders it [x, vx, y, vy]).
///
/// Measurement carries the sensor's pose but not its height, so a camera's mast height h is a
/// separate member: the engine looks it up by the reporting sensor (the scenario's sensor list,
/// docs/ONERA.md §7) when it builds the model. The target is on the ground, so phi = atan2(-h, rho) < 0,
/// and h = 0 would leave phi without any information on the range.
struct MeasurementModel {
  common::MeasurementKind kind = common::MeasurementKind::position;
  /// Unused by position, which is already in the field frame.
  common::SensorPose sensor;
  /// Camera height above the target's ground (m); only azimuth_elevation reads it.
  double mast_height = 0.0;

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

/// The model of measurement m: its kind and pose, plus the mast height that m cannot carry.
/// Nullopt for a kind no field sensor reports with a state-dependent h (signal_strength, presence),
/// or when m lacks the pose its kind needs.
std::optional<MeasurementModel> modelOf(const common::Measurement& m, double mast_height = 0.0);

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

/// The same for a common::Measurement: its pose from m.sensor, the mast height as modelOf takes it.
std::optional<EkfUpdate> update(const common::GaussianState& predicted, const common::Measurement& m,
                                const MeasurementCovariance& R, double mast_height = 0.0);

}  // namespace wsn::supernode::sbmht

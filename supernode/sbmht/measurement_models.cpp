#include "supernode/sbmht/measurement_models.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <boost/math/distributions/chi_squared.hpp>

namespace wsn::supernode::sbmht {
namespace {

using common::kVx;
using common::kVy;
using common::kX;
using common::kY;
using common::MeasurementKind;
using common::StateMatrix;
using common::StateVector;

using GainMatrix = Eigen::Matrix<double, common::kStateDim, Eigen::Dynamic, 0, common::kStateDim, kMaxModelDimension>;

/// Where the target is as the sensor sees it: offset, ground range and range rate.
struct Relative {
  double dx = 0.0;
  double dy = 0.0;
  double rho = 0.0;
  double rho_dot = 0.0;
};

Relative relative(const common::SensorPose& sensor, const StateVector& x) {
  Relative r;
  r.dx = x(kX) - sensor.x;
  r.dy = x(kY) - sensor.y;
  r.rho = std::hypot(r.dx, r.dy);
  r.rho_dot = r.rho > 0.0 ? (r.dx * x(kVx) + r.dy * x(kVy)) / r.rho : 0.0;
  return r;
}

double fieldBearingFromSensor(const common::SensorPose& sensor, const Relative& r) {
  return wrapAngle(std::atan2(r.dy, r.dx) - sensor.heading);
}

/// d theta / d(x, y) of theta = atan2(dy, dx); the heading is a constant offset.
void bearingRow(MeasurementJacobian& H, int row, const Relative& r) {
  const double rho2 = r.rho * r.rho;
  H(row, kX) = -r.dy / rho2;
  H(row, kY) = r.dx / rho2;
}

}  // namespace

double gateThreshold(int dimension) {
  // The 0.99 quantiles of chi^2 with 1, 2 and 3 degrees of freedom (2: -2 ln 0.01 exactly).
  switch (dimension) {
    case 1: return 6.6348966010212145;
    case 2: return 9.210340371976182;
    case 3: return 11.344866730144373;
    default: return std::numeric_limits<double>::infinity();
  }
}

double gateOfSameProbability(double gate_2d, int dimension) {
  if (dimension <= 0) return 0.0;
  if (dimension == 2) return gate_2d;
  // The upper tail exp(-gate_2d / 2) keeps its precision where 1 - tail would round to 1 (gate_2d > ~75).
  const double tail = std::exp(-0.5 * gate_2d);
  if (!(tail > 0.0)) return std::numeric_limits<double>::infinity();
  return boost::math::quantile(boost::math::complement(boost::math::chi_squared(dimension), tail));
}

int MeasurementModel::dimension() const {
  switch (kind) {
    case MeasurementKind::bearing: return 1;
    case MeasurementKind::range_bearing_rate: return 3;
    case MeasurementKind::position:
    case MeasurementKind::azimuth_elevation: return 2;
    default: return 0;
  }
}

bool MeasurementModel::linearisableAt(const StateVector& x) const {
  if (!x.allFinite() || dimension() == 0) return false;
  if (kind == MeasurementKind::position) return true;
  return relative(sensor, x).rho >= kMinimumRange;
}

MeasurementVector MeasurementModel::predict(const StateVector& x) const {
  MeasurementVector h(dimension());
  const Relative r = relative(sensor, x);
  switch (kind) {
    case MeasurementKind::position:
      h << x(kX), x(kY);
      break;
    case MeasurementKind::bearing:
      h << fieldBearingFromSensor(sensor, r);
      break;
    case MeasurementKind::range_bearing_rate:
      h << r.rho, fieldBearingFromSensor(sensor, r), r.rho_dot;
      break;
    case MeasurementKind::azimuth_elevation:
      h << fieldBearingFromSensor(sensor, r), std::atan2(-sensor.height, r.rho);
      break;
    default:
      break;
  }
  return h;
}

MeasurementJacobian MeasurementModel::jacobian(const StateVector& x) const {
  MeasurementJacobian H = MeasurementJacobian::Zero(dimension(), common::kStateDim);
  const Relative r = relative(sensor, x);
  switch (kind) {
    case MeasurementKind::position:
      H(0, kX) = 1.0;
      H(1, kY) = 1.0;
      break;
    case MeasurementKind::bearing:
      bearingRow(H, 0, r);
      break;
    case MeasurementKind::range_bearing_rate:
      H(0, kX) = r.dx / r.rho;
      H(0, kY) = r.dy / r.rho;
      bearingRow(H, 1, r);
      // rho_dot = (dx vx + dy vy) / rho: d/dx = (vx - rho_dot dx / rho) / rho, d/dvx = dx / rho.
      H(2, kX) = (x(kVx) - r.rho_dot * r.dx / r.rho) / r.rho;
      H(2, kY) = (x(kVy) - r.rho_dot * r.dy / r.rho) / r.rho;
      H(2, kVx) = r.dx / r.rho;
      H(2, kVy) = r.dy / r.rho;
      break;
    case MeasurementKind::azimuth_elevation: {
      bearingRow(H, 0, r);
      // phi = atan2(-h, rho): d phi / d rho = h / (rho^2 + h^2), and d rho / d(x, y) = (dx, dy) / rho.
      const double dphi_drho = sensor.height / (r.rho * r.rho + sensor.height * sensor.height);
      H(1, kX) = dphi_drho * r.dx / r.rho;
      H(1, kY) = dphi_drho * r.dy / r.rho;
      break;
    }
    default:
      break;
  }
  return H;
}

MeasurementVector MeasurementModel::innovation(const MeasurementVector& z, const StateVector& x) const {
  MeasurementVector nu = z - predict(x);
  switch (kind) {
    case MeasurementKind::bearing:
      nu(0) = wrapAngle(nu(0));
      break;
    case MeasurementKind::azimuth_elevation:
      nu(0) = wrapAngle(nu(0));
      nu(1) = wrapAngle(nu(1));
      break;
    case MeasurementKind::range_bearing_rate:
      nu(1) = wrapAngle(nu(1));
      break;
    default:
      break;
  }
  return nu;
}

std::optional<MeasurementModel> modelOf(const common::Measurement& m) {
  MeasurementModel model;
  model.kind = m.kind;
  if (model.dimension() == 0 || static_cast<int>(m.values.size()) != model.dimension()) return std::nullopt;
  if (m.kind != MeasurementKind::position) {
    if (!m.sensor) return std::nullopt;
    model.sensor = *m.sensor;
  }
  return model;
}

std::optional<PositionFix> positionFix(const MeasurementModel& model, const MeasurementVector& z,
                                       const MeasurementCovariance& R) {
  const int m = model.dimension();
  if (m == 0 || z.size() != m || R.rows() != m || R.cols() != m || !z.allFinite() || !R.allFinite())
    return std::nullopt;
  PositionFix fix;
  // p = s + rho (cos b, sin b), b = heading + theta: J = d p / d(rho, theta) or d(theta, phi).
  const auto polar = [&](double rho, double theta, double drho_dsecond, bool second_is_rho) {
    const double b = model.sensor.heading + theta;
    const Eigen::Vector2d u(std::cos(b), std::sin(b));
    const Eigen::Vector2d du(-std::sin(b), std::cos(b));
    fix.position = Eigen::Vector2d(model.sensor.x, model.sensor.y) + rho * u;
    Eigen::Matrix2d J;
    if (second_is_rho)  // (rho, theta)
      J << u, rho * du;
    else  // (theta, phi), rho a function of phi
      J << rho * du, drho_dsecond * u;
    return std::pair{J, u};
  };
  switch (model.kind) {
    case MeasurementKind::position:
      fix.position = z.head<2>();
      fix.covariance = R.topLeftCorner<2, 2>();
      break;
    case MeasurementKind::range_bearing_rate: {
      const auto [J, u] = polar(z(0), z(1), 0.0, true);
      fix.covariance = J * R.topLeftCorner<2, 2>() * J.transpose();
      fix.line_of_sight = u;
      fix.range_rate = z(2);
      fix.range_rate_variance = R(2, 2);
      break;
    }
    case MeasurementKind::azimuth_elevation: {
      const double h = model.sensor.height;
      const double phi = z(1);
      // Below -pi/2 the ray would point behind the camera (rho < 0).
      if (!(h > 0.0) || !(phi < 0.0) || !(phi > -0.5 * std::numbers::pi)) return std::nullopt;
      // rho = h / tan(-phi) = -h / tan(phi); d rho / d phi = h / sin^2(phi).
      const double rho = -h / std::tan(phi);
      const double s = std::sin(phi);
      const auto [J, u] = polar(rho, z(0), h / (s * s), false);
      fix.covariance = J * R * J.transpose();
      break;
    }
    default:
      return std::nullopt;
  }
  fix.covariance = 0.5 * (fix.covariance + fix.covariance.transpose());
  if (!fix.position.allFinite() || !fix.covariance.allFinite()) return std::nullopt;
  return fix;
}

std::optional<BearingPairFix> bearingPairFix(const MeasurementModel& model_a, const MeasurementVector& z_a,
                                             const MeasurementCovariance& R_a, const MeasurementModel& model_b,
                                             const MeasurementVector& z_b, const MeasurementCovariance& R_b,
                                             double min_sine_angle) {
  const auto isBearing = [](const MeasurementModel& m, const MeasurementVector& z, const MeasurementCovariance& R) {
    return m.kind == MeasurementKind::bearing && z.size() == 1 && R.rows() == 1 && R.cols() == 1 && z.allFinite() &&
           std::isfinite(R(0, 0)) && R(0, 0) > 0.0;
  };
  if (!isBearing(model_a, z_a, R_a) || !isBearing(model_b, z_b, R_b)) return std::nullopt;
  const double ba = model_a.sensor.heading + z_a(0);
  const double bb = model_b.sensor.heading + z_b(0);
  const Eigen::Vector2d ua(std::cos(ba), std::sin(ba));
  const Eigen::Vector2d ub(std::cos(bb), std::sin(bb));
  const Eigen::Vector2d sa(model_a.sensor.x, model_a.sensor.y);
  const Eigen::Vector2d sb(model_b.sensor.x, model_b.sensor.y);
  const auto cross = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) { return p.x() * q.y() - p.y() * q.x(); };
  const double sine = cross(ua, ub);  // sin gamma
  if (!(std::abs(sine) > min_sine_angle)) return std::nullopt;
  // sa + r_a ua = sb + r_b ub: cross both sides with ub, then with ua.
  const Eigen::Vector2d d = sb - sa;
  BearingPairFix out;
  out.range_a = cross(d, ub) / sine;
  out.range_b = cross(d, ua) / sine;
  if (!(out.range_a > kMinimumRange) || !(out.range_b > kMinimumRange)) return std::nullopt;
  out.fix.position = sa + out.range_a * ua;
  // Row i of J is d theta_i / d(x, y) = (-sin b_i, cos b_i) / r_i.
  Eigen::Matrix2d J;
  J << -ua.y() / out.range_a, ua.x() / out.range_a, -ub.y() / out.range_b, ub.x() / out.range_b;
  const Eigen::Matrix2d J_inverse = J.inverse();
  const Eigen::Vector2d R(R_a(0, 0), R_b(0, 0));
  out.fix.covariance = J_inverse * R.asDiagonal() * J_inverse.transpose();
  out.fix.covariance = 0.5 * (out.fix.covariance + out.fix.covariance.transpose());
  out.jacobian_determinant = std::abs(sine) / (out.range_a * out.range_b);
  if (!out.fix.position.allFinite() || !out.fix.covariance.allFinite()) return std::nullopt;
  return out;
}

MeasurementVector valuesOf(const common::Measurement& m) {
  MeasurementVector z(static_cast<Eigen::Index>(m.values.size()));
  for (std::size_t i = 0; i < m.values.size(); ++i) z(static_cast<Eigen::Index>(i)) = m.values[i];
  return z;
}

std::optional<MeasurementCovariance> noiseOf(const common::Measurement& m) {
  const auto n = static_cast<Eigen::Index>(m.values.size());
  if (!m.hasNoise() || m.noise.size() != m.values.size() * m.values.size() || n > kMaxModelDimension)
    return std::nullopt;
  MeasurementCovariance R(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) R(i, j) = m.noise[static_cast<std::size_t>(i * n + j)];
  return R;
}

std::optional<EkfUpdate> update(const common::GaussianState& predicted, const MeasurementModel& model,
                                const MeasurementVector& z, const MeasurementCovariance& R) {
  const int m = model.dimension();
  if (m == 0 || z.size() != m || R.rows() != m || R.cols() != m) return std::nullopt;
  if (!z.allFinite() || !R.allFinite() || !predicted.P.allFinite() || !model.linearisableAt(predicted.x))
    return std::nullopt;

  const MeasurementJacobian H = model.jacobian(predicted.x);
  EkfUpdate out;
  out.innovation = model.innovation(z, predicted.x);
  const MeasurementCovariance S = H * predicted.P * H.transpose() + R;
  out.S = 0.5 * (S + S.transpose());
  const Eigen::LDLT<MeasurementCovariance> ldlt(out.S);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().array() > 0.0).all()) return std::nullopt;

  out.mahalanobis_squared = out.innovation.dot(ldlt.solve(out.innovation));
  const double log_det_S = ldlt.vectorD().array().log().sum();
  out.log_likelihood = -0.5 * (out.mahalanobis_squared + log_det_S + m * std::log(2.0 * std::numbers::pi));
  out.likelihood = std::exp(out.log_likelihood);

  // S symmetric: K' = S^-1 (H P).
  const GainMatrix K = ldlt.solve(H * predicted.P).transpose();
  const StateMatrix I_KH = StateMatrix::Identity() - K * H;
  out.state.x = predicted.x + K * out.innovation;
  const StateMatrix P = I_KH * predicted.P * I_KH.transpose() + K * R * K.transpose();
  out.state.P = 0.5 * (P + P.transpose());
  if (!out.state.x.allFinite() || !out.state.P.allFinite()) return std::nullopt;
  return out;
}

std::optional<EkfUpdate> update(const common::GaussianState& predicted, const common::Measurement& m,
                                const MeasurementCovariance& R) {
  const auto model = modelOf(m);
  if (!model) return std::nullopt;
  return update(predicted, *model, valuesOf(m), R);
}

}  // namespace wsn::supernode::sbmht

#include "supernode/sbmht/measurement_models.hpp"

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

namespace wsn::supernode::sbmht {
namespace {

using common::GaussianState;
using common::kVx;
using common::kVy;
using common::kX;
using common::kY;
using common::MeasurementKind;
using common::SensorPose;
using common::StateMatrix;
using common::StateVector;

constexpr double kPi = std::numbers::pi;

StateVector state(double x, double y, double vx, double vy) {
  StateVector s;
  s << x, y, vx, vy;
  return s;
}

MeasurementModel modelOfKind(MeasurementKind kind, SensorPose sensor = {}, double mast_height = 0.0) {
  MeasurementModel m;
  m.kind = kind;
  m.sensor = sensor;
  m.sensor.height = mast_height;
  return m;
}

TEST_CASE("wrapAngle brings angles into the half-open interval from -pi to pi", "[sbmht]") {
  CHECK(wrapAngle(0.0) == 0.0);
  CHECK(wrapAngle(kPi) == Approx(kPi));
  // -pi is the same direction as pi, and the interval keeps pi.
  CHECK(wrapAngle(-kPi) == Approx(kPi));
  CHECK(wrapAngle(3.0 * kPi) == Approx(kPi));
  CHECK(wrapAngle(kPi + 0.1) == Approx(-kPi + 0.1));
  CHECK(wrapAngle(-kPi - 0.1) == Approx(kPi - 0.1));
  CHECK(wrapAngle(2.0 * kPi + 0.25) == Approx(0.25));
  CHECK(wrapAngle(-7.0 * kPi + 0.5) == Approx(-kPi + 0.5));
}

TEST_CASE("h of every field kind gives the hand-computed values", "[sbmht]") {
  // Position is already in the field frame: the pose plays no part.
  const auto position = modelOfKind(MeasurementKind::position, {5.0, 5.0, 1.0}).predict(state(3.0, -4.0, 1.0, 2.0));
  CHECK(position(0) == 3.0);
  CHECK(position(1) == -4.0);

  // A sensor at (10, 20) facing north (heading pi/2). A target due north is at theta = 0, one due
  // west at field bearing pi, i.e. pi/2 counter-clockwise from the heading.
  const SensorPose north{10.0, 20.0, kPi / 2};
  const auto bearing = modelOfKind(MeasurementKind::bearing, north);
  CHECK(bearing.predict(state(10.0, 120.0, 0.0, 0.0))(0) == Approx(0.0).margin(1e-12));
  CHECK(bearing.predict(state(0.0, 20.0, 0.0, 0.0))(0) == Approx(kPi / 2));
  // Due south is field bearing -pi/2, -pi from the heading: reported as +pi.
  CHECK(bearing.predict(state(10.0, 10.0, 0.0, 0.0))(0) == Approx(kPi));

  // Radar at the origin facing east; target at (3, 4): rho = 5, theta = atan2(4, 3) = 0.927295.
  // Its velocity is 2 m/s away, (1.2, 1.6), plus (-4, 3) across the line of sight, so
  // v = (-2.8, 4.6) and rho_dot = (3 * -2.8 + 4 * 4.6) / 5 = (-8.4 + 18.4) / 5 = 2.
  const auto radar = modelOfKind(MeasurementKind::range_bearing_rate, {0.0, 0.0, 0.0});
  const auto rbr = radar.predict(state(3.0, 4.0, -2.8, 4.6));
  CHECK(rbr(0) == Approx(5.0));
  CHECK(rbr(1) == Approx(std::atan2(4.0, 3.0)));
  CHECK(rbr(1) == Approx(0.927295218));
  CHECK(rbr(2) == Approx(2.0));

  // Camera on a 3 m mast at (1, 1) facing east; target 4 m east: theta = 0, phi = atan2(-3, 4)
  // = -0.643501 (looking down a 3-4-5 triangle).
  const auto camera = modelOfKind(MeasurementKind::azimuth_elevation, {1.0, 1.0, 0.0}, 3.0);
  const auto ae = camera.predict(state(5.0, 1.0, 0.0, 0.0));
  CHECK(ae(0) == Approx(0.0).margin(1e-12));
  CHECK(ae(1) == Approx(-0.643501109));
}

TEST_CASE("each Jacobian matches a central finite difference at several states", "[sbmht]") {
  const std::array<MeasurementModel, 4> models{
      modelOfKind(MeasurementKind::position),
      modelOfKind(MeasurementKind::bearing, {10.0, -20.0, 0.7}),
      modelOfKind(MeasurementKind::range_bearing_rate, {-5.0, 3.0, -2.0}),
      modelOfKind(MeasurementKind::azimuth_elevation, {2.0, 2.0, 3.0}, 3.0),
  };
  // Near the sensors, far away, and (for the first sensors) behind them, where the field bearing
  // crosses +-pi: the difference is wrapped so that it measures the change, not the jump.
  const std::array<StateVector, 5> states{state(40.0, 25.0, 3.0, -1.0), state(-300.0, 0.5, -10.0, 2.0),
                                          state(-300.0, -0.5, 0.0, 0.0), state(12.0, -19.0, 0.3, 0.4),
                                          state(-5.0, -2.0, -1.5, 6.0)};
  for (const auto& model : models) {
    for (const auto& x : states) {
      CAPTURE(static_cast<int>(model.kind), x.transpose());
      REQUIRE(model.linearisableAt(x));
      const MeasurementJacobian H = model.jacobian(x);
      REQUIRE(H.rows() == model.dimension());
      for (int j = 0; j < common::kStateDim; ++j) {
        const double step = 1e-5 * std::max(1.0, std::abs(x(j)));
        StateVector up = x;
        StateVector down = x;
        up(j) += step;
        down(j) -= step;
        const MeasurementVector difference = model.innovation(model.predict(up), down);
        for (int i = 0; i < model.dimension(); ++i) {
          CAPTURE(i, j);
          CHECK(H(i, j) == Approx(difference(i) / (2.0 * step)).margin(1e-7).epsilon(1e-5));
        }
      }
    }
  }
}

TEST_CASE("the innovation of a bearing just across pi is small", "[sbmht]") {
  // Sensor at the origin facing east, target at (-100, 0.5): h = atan2(0.5, -100) = pi - 0.005
  // (to 4e-8). A report of -pi + 0.003 lies 0.008 further counter-clockwise, not 2 pi - 0.008 back.
  const auto bearing = modelOfKind(MeasurementKind::bearing);
  const StateVector x = state(-100.0, 0.5, 0.0, 0.0);
  const double h = std::atan2(0.5, -100.0);
  CHECK(bearing.predict(x)(0) == Approx(h));
  MeasurementVector z(1);
  z << -kPi + 0.003;
  CHECK(bearing.innovation(z, x)(0) == Approx(0.003 + (kPi - h)));
  CHECK(bearing.innovation(z, x)(0) == Approx(0.008).margin(1e-6));

  // The same across the radar's theta; range and range rate are not wrapped.
  const auto radar = modelOfKind(MeasurementKind::range_bearing_rate);
  MeasurementVector z3(3);
  z3 << 100.0, -kPi + 0.003, -7.0;
  const MeasurementVector nu = radar.innovation(z3, x);
  CHECK(nu(0) == Approx(100.0 - std::hypot(100.0, 0.5)));
  CHECK(nu(1) == Approx(0.008).margin(1e-6));
  CHECK(nu(2) == Approx(-7.0));
}

TEST_CASE("a bearing EKF update gives the hand-computed state and likelihood", "[sbmht]") {
  // Sensor at (10, 20) facing north; predicted target due north at (10, 120), P = diag(100, 100,
  // 1, 1); report theta = 0.02 rad (west of north), R = (0.01 rad)^2.
  // h = 0, rho = 100, H = [-dy / rho^2, dx / rho^2, 0, 0] = [-0.01, 0, 0, 0].
  // S = 0.01^2 * 100 + 1e-4 = 0.0101. K = P H' / S = (-1 / 0.0101, 0, 0, 0) = (-99.0099, 0, 0, 0).
  // x+ = 10 + K nu = 10 - 99.0099 * 0.02 = 8.019802 (moved west); y, velocity untouched.
  // P_xx+ = (1 - K H)^2 P_xx + K^2 R = (0.009901)^2 * 100 + 9803.0 * 1e-4 = 0.990099.
  // d^2 = 0.02^2 / 0.0101 = 0.039604; N = exp(-d^2 / 2) / sqrt(2 pi S) = 3.891791.
  GaussianState predicted;
  predicted.x = state(10.0, 120.0, 0.0, 0.0);
  predicted.P = StateVector(100.0, 100.0, 1.0, 1.0).asDiagonal();
  common::Measurement m;
  m.kind = MeasurementKind::bearing;
  m.values = {0.02};
  m.sensor = SensorPose{10.0, 20.0, kPi / 2};
  MeasurementCovariance R(1, 1);
  R << 1e-4;

  const auto result = update(predicted, m, R);
  REQUIRE(result);
  CHECK(result->innovation(0) == Approx(0.02));
  CHECK(result->S(0, 0) == Approx(0.0101));
  CHECK(result->state.x(kX) == Approx(8.019802));
  CHECK(result->state.x(kY) == Approx(120.0));
  CHECK(result->state.x(kVx) == Approx(0.0).margin(1e-12));
  CHECK(result->state.P(kX, kX) == Approx(0.990099));
  CHECK(result->state.P(kY, kY) == Approx(100.0));
  CHECK(result->state.P(kVx, kVx) == Approx(1.0));
  CHECK(result->mahalanobis_squared == Approx(0.039604));
  CHECK(result->likelihood == Approx(3.891791));
  CHECK(result->log_likelihood == Approx(std::log(3.891791)));
}

TEST_CASE("the EKF refuses a target on top of a bearing sensor", "[sbmht]") {
  GaussianState predicted;
  predicted.x = state(10.0, 20.0, 1.0, 0.0);
  predicted.P = StateMatrix::Identity();
  const auto bearing = modelOfKind(MeasurementKind::bearing, {10.0, 20.0, 0.0});
  CHECK_FALSE(bearing.linearisableAt(predicted.x));
  MeasurementVector z(1);
  z << 0.0;
  CHECK_FALSE(update(predicted, bearing, z, MeasurementCovariance::Identity(1, 1)));
  // A position report has no such point.
  CHECK(modelOfKind(MeasurementKind::position, {10.0, 20.0, 0.0}).linearisableAt(predicted.x));
}

TEST_CASE("C6 the gate is chi2 at 0.99 and a 2-D report at d2 9.3 is rejected", "[sbmht]") {
  // chi^2_1(0.99) = 6.6349, chi^2_2(0.99) = -2 ln 0.01 = 9.2103, chi^2_3(0.99) = 11.3449 (bisection
  // on the closed-form CDFs: erf(sqrt(x/2)), 1 - e^{-x/2}, erf(sqrt(x/2)) - sqrt(2x/pi) e^{-x/2}).
  CHECK(gateThreshold(1) == Approx(6.635).margin(5e-4));
  CHECK(gateThreshold(2) == Approx(9.210).margin(5e-4));
  CHECK(gateThreshold(2) == Approx(-2.0 * std::log(0.01)));
  CHECK(gateThreshold(3) == Approx(11.345).margin(5e-4));
  CHECK(std::isinf(gateThreshold(4)));

  // P = 0 and R = I make S = I, so nu = (sqrt 9.3, 0) sits at d^2 = 9.3 > 9.2103.
  GaussianState predicted;
  const MeasurementModel position = modelOfKind(MeasurementKind::position);
  MeasurementVector z(2);
  z << std::sqrt(9.3), 0.0;
  const auto outside = update(predicted, position, z, MeasurementCovariance::Identity(2, 2));
  REQUIRE(outside);
  CHECK(outside->mahalanobis_squared == Approx(9.3));
  CHECK(outside->mahalanobis_squared > gateThreshold(2));
  z << std::sqrt(9.2), 0.0;
  const auto inside = update(predicted, position, z, MeasurementCovariance::Identity(2, 2));
  REQUIRE(inside);
  CHECK(inside->mahalanobis_squared <= gateThreshold(2));
}

TEST_CASE("modelOf takes the kind and pose of a measurement and its noise when given", "[sbmht]") {
  const auto plain = modelOf(common::Measurement::position(1.0, 2.0));
  REQUIRE(plain);
  CHECK(plain->dimension() == 2);
  CHECK_FALSE(noiseOf(common::Measurement::position(1.0, 2.0)));

  common::Measurement camera;
  camera.kind = MeasurementKind::azimuth_elevation;
  camera.values = {0.1, -0.05};
  camera.noise = {1e-6, 0.0, 0.0, 4e-6};
  camera.sensor = SensorPose{3.0, 4.0, 0.5, 3.0};
  const auto model = modelOf(camera);
  REQUIRE(model);
  CHECK(model->sensor == SensorPose{3.0, 4.0, 0.5, 3.0});  // the mast height comes with the pose
  const auto R = noiseOf(camera);
  REQUIRE(R);
  CHECK((*R)(0, 0) == 1e-6);
  CHECK((*R)(1, 1) == 4e-6);
  CHECK(valuesOf(camera)(1) == -0.05);

  // Every kind but position needs the pose; presence and signal strength have no h(x) here.
  camera.sensor.reset();
  CHECK_FALSE(modelOf(camera));
  common::Measurement presence;
  presence.kind = MeasurementKind::presence;
  presence.sensor = SensorPose{};
  CHECK_FALSE(modelOf(presence));
}

TEST_CASE("a radar plot fixes a position with R carried through the polar inverse", "[sbmht]") {
  // Radar at (10, 20) facing +y (heading pi/2); theta = -pi/2 from the heading is the field's +x,
  // so rho = 100 puts the target at (110, 20). J = d(x, y)/d(rho, theta) = [u, rho du] with
  // u = (1, 0), du = (0, 1): covariance diag(sigma_rho^2, rho^2 sigma_theta^2) = diag(25, 100^2 (pi/180)^2).
  const auto radar = modelOfKind(MeasurementKind::range_bearing_rate, SensorPose{10.0, 20.0, std::numbers::pi / 2});
  MeasurementVector z(3);
  z << 100.0, -std::numbers::pi / 2, -4.0;
  MeasurementCovariance R = MeasurementCovariance::Zero(3, 3);
  const double sigma_theta = std::numbers::pi / 180.0;
  R.diagonal() << 25.0, sigma_theta * sigma_theta, 0.09;
  const auto fix = positionFix(radar, z, R);
  REQUIRE(fix);
  CHECK(fix->position.x() == Approx(110.0));
  CHECK(fix->position.y() == Approx(20.0).margin(1e-9));
  CHECK(fix->covariance(0, 0) == Approx(25.0));
  CHECK(fix->covariance(1, 1) == Approx(1e4 * sigma_theta * sigma_theta));  // 3.0462
  CHECK(fix->covariance(0, 1) == Approx(0.0).margin(1e-9));
  REQUIRE(fix->line_of_sight);
  CHECK(fix->line_of_sight->x() == Approx(1.0));
  CHECK(fix->range_rate == -4.0);
  CHECK(fix->range_rate_variance == 0.09);
  // The fix is where h(x) returns the plot's range and bearing.
  const auto back = radar.predict(state(fix->position.x(), fix->position.y(), -4.0, 0.0));
  CHECK(back(0) == Approx(100.0));
  CHECK(back(1) == Approx(-std::numbers::pi / 2));
  CHECK(back(2) == Approx(-4.0));

  // An oblique line of sight, where J is not symmetric: facing +x, theta = pi/6 puts rho = 10 at
  // (10 cos 30, 10 sin 30) = (8.6603, 5). J = [[cos b, -rho sin b], [sin b, rho cos b]] with
  // R = diag(4, 0.01): cov = J R J' = [[4 cos^2 + 100 (0.01) sin^2, (4 - 1) sin cos], [., 4 sin^2 + 1 cos^2]]
  // = [[3.25, 1.2990], [1.2990, 1.75]] (sin 30 = 0.5, cos 30 = 0.86603).
  const auto ahead = modelOfKind(MeasurementKind::range_bearing_rate, SensorPose{0.0, 0.0, 0.0});
  z << 10.0, std::numbers::pi / 6, 0.0;
  R.diagonal() << 4.0, 0.01, 1.0;
  const auto oblique = positionFix(ahead, z, R);
  REQUIRE(oblique);
  CHECK(oblique->position.x() == Approx(8.66025));
  CHECK(oblique->position.y() == Approx(5.0));
  CHECK(oblique->covariance(0, 0) == Approx(3.25));
  CHECK(oblique->covariance(1, 1) == Approx(1.75));
  CHECK(oblique->covariance(0, 1) == Approx(1.29904));
}

TEST_CASE("a camera's angles from a mast fix a position, and a bearing fixes none", "[sbmht]") {
  // h = 3, phi = atan2(-3, 100): rho = h / tan(-phi) = 100, straight ahead of a camera at the origin
  // facing +x. d rho / d phi = h / sin^2(phi) = 3 x 10009 / 9 = 3336.33, so sigma_phi = 0.1 deg
  // (1.74533e-3 rad) gives 5.8230 m along the line of sight (variance 33.907) and rho sigma_theta =
  // 0.174533 m across it (variance 0.030462): the spec's "about 6 m at 100 m".
  const auto camera = modelOfKind(MeasurementKind::azimuth_elevation, SensorPose{0.0, 0.0, 0.0}, 3.0);
  const double sigma = 0.1 * std::numbers::pi / 180.0;
  MeasurementVector z(2);
  z << 0.0, std::atan2(-3.0, 100.0);
  const MeasurementCovariance R = MeasurementCovariance::Identity(2, 2) * sigma * sigma;
  const auto fix = positionFix(camera, z, R);
  REQUIRE(fix);
  CHECK(fix->position.x() == Approx(100.0));
  CHECK(fix->position.y() == Approx(0.0).margin(1e-9));
  CHECK(fix->covariance(0, 0) == Approx(33.907).epsilon(1e-4));
  CHECK(fix->covariance(1, 1) == Approx(0.030462).epsilon(1e-4));
  CHECK_FALSE(fix->line_of_sight);

  z(1) = 0.0;  // level: no ground range
  CHECK_FALSE(positionFix(camera, z, R));
  z(1) = -2.0;  // below the nadir: the ray would land behind the camera
  CHECK_FALSE(positionFix(camera, z, R));
  const auto ground_camera = modelOfKind(MeasurementKind::azimuth_elevation, SensorPose{0.0, 0.0, 0.0}, 0.0);
  z(1) = -0.1;
  CHECK_FALSE(positionFix(ground_camera, z, R));
  const auto antenna = modelOfKind(MeasurementKind::bearing, SensorPose{0.0, 0.0, 0.0});
  MeasurementVector theta(1);
  theta << 0.3;
  CHECK_FALSE(positionFix(antenna, theta, MeasurementCovariance::Identity(1, 1) * 1e-3));
}

TEST_CASE("two bearings cross at a fix with R carried through the inverse Jacobian", "[sbmht]") {
  // Antenna a at the origin sees the target at 45 deg, antenna b at (10, 0), facing +y, sees it 45 deg
  // to its left (135 deg in the field): the rays cross at (5, 5), r_a = r_b = sqrt(50). Row i of
  // J = d theta_i / d(x, y) is (-sin b_i, cos b_i) / r_i: J = [[-0.1, 0.1], [-0.1, -0.1]],
  // det J = 0.02 = sin 90 deg / (r_a r_b) = 1 / 50, J^-1 = [[-5, -5], [5, -5]]. With variances
  // 1e-4 and 4e-4, P = 1e-4 c1 c1' + 4e-4 c2 c2' (c the columns of J^-1, (-5, 5) and (-5, -5)):
  // [[0.0025 + 0.01, -0.0025 + 0.01], [., 0.0125]] = [[0.0125, 0.0075], [0.0075, 0.0125]].
  const auto a = modelOfKind(MeasurementKind::bearing, SensorPose{0.0, 0.0, 0.0});
  const auto b = modelOfKind(MeasurementKind::bearing, SensorPose{10.0, 0.0, kPi / 2});
  MeasurementVector za(1);
  MeasurementVector zb(1);
  za << kPi / 4;
  zb << kPi / 4;
  const MeasurementCovariance Ra = MeasurementCovariance::Identity(1, 1) * 1e-4;
  const MeasurementCovariance Rb = MeasurementCovariance::Identity(1, 1) * 4e-4;
  const auto pair = bearingPairFix(a, za, Ra, b, zb, Rb, 0.02);
  REQUIRE(pair);
  CHECK(pair->fix.position.x() == Approx(5.0));
  CHECK(pair->fix.position.y() == Approx(5.0));
  CHECK(pair->range_a == Approx(std::sqrt(50.0)));
  CHECK(pair->range_b == Approx(std::sqrt(50.0)));
  CHECK(pair->jacobian_determinant == Approx(0.02));
  CHECK(pair->fix.covariance(0, 0) == Approx(0.0125));
  CHECK(pair->fix.covariance(0, 1) == Approx(0.0075));
  CHECK(pair->fix.covariance(1, 0) == Approx(0.0075));
  CHECK(pair->fix.covariance(1, 1) == Approx(0.0125));
  CHECK_FALSE(pair->fix.line_of_sight);
  // The same bearings in the other order give the same point.
  const auto swapped = bearingPairFix(b, zb, Rb, a, za, Ra, 0.02);
  REQUIRE(swapped);
  CHECK(swapped->fix.position.x() == Approx(5.0));
  CHECK(swapped->fix.covariance(0, 1) == Approx(0.0075));

  // b looking the other way (-45 deg in the field): the lines meet at (5, 5) behind b, no fix.
  zb << -3 * kPi / 4;
  CHECK_FALSE(bearingPairFix(a, za, Ra, b, zb, Rb, 0.02));
  // Parallel rays (both at 45 deg), and rays 0.5 deg apart (|sin| 0.0087 < 0.02), cross nowhere useful.
  zb << -kPi / 4;
  CHECK_FALSE(bearingPairFix(a, za, Ra, b, zb, Rb, 0.02));
  za << kPi / 2 - 0.5 * kPi / 180;
  zb << 0.0;
  CHECK_FALSE(bearingPairFix(a, za, Ra, b, zb, Rb, 0.02));
  // A bearing of no error would make a singular fix.
  za << kPi / 4;
  zb << kPi / 4;
  CHECK_FALSE(bearingPairFix(a, za, MeasurementCovariance::Zero(1, 1), b, zb, Rb, 0.02));
  // A camera or a radar is not a bearing.
  const auto radar = modelOfKind(MeasurementKind::range_bearing_rate, SensorPose{10.0, 0.0, kPi / 2});
  za << kPi / 4;
  CHECK_FALSE(bearingPairFix(a, za, Ra, radar, zb, Rb, 0.02));
}

TEST_CASE("gates of other dimensions keep the probability of the 2-D gate", "[sbmht]") {
  // 9.2103 = -2 ln 0.01 is the 2-D gate of P_G = 0.99; its 1-D and 3-D quantiles are gateThreshold's.
  CHECK(gateOfSameProbability(gateThreshold(2), 1) == Approx(gateThreshold(1)).epsilon(1e-9));
  CHECK(gateOfSameProbability(gateThreshold(2), 3) == Approx(gateThreshold(3)).epsilon(1e-9));
  CHECK(gateOfSameProbability(5.0, 2) == 5.0);
  CHECK(gateOfSameProbability(5.0, 0) == 0.0);
  // P_G = 1 - exp(-1) = 0.63212 for gate 2: chi^2_1 quantile (Phi^-1(0.81606))^2 = 0.90045^2 = 0.81081.
  CHECK(gateOfSameProbability(2.0, 1) == Approx(0.81081).epsilon(1e-4));
  // A wide 2-D gate (tail exp(-50) = 1.9e-22, where 1 - tail rounds to 1) still maps to finite gates,
  // ordered as chi^2 quantiles of one tail are: fewer degrees of freedom, a smaller quantile.
  const double narrow = gateOfSameProbability(100.0, 1);
  const double wide = gateOfSameProbability(100.0, 3);
  CHECK(std::isfinite(narrow));
  CHECK(std::isfinite(wide));
  CHECK(narrow < 100.0);
  CHECK(wide > 100.0);
}

}  // namespace
}  // namespace wsn::supernode::sbmht

#include "common/kalman.hpp"

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "common/rng.hpp"

namespace wsn::common {
namespace {

TEST_CASE("the constant-velocity model has the matrices of Oh eq. 8", "[kalman]") {
  const ConstantVelocityModel m(1.0, 0.5, 2.0);
  // A_delta with delta = 1: position += velocity.
  CHECK(m.F(kX, kVx) == 1.0);
  CHECK(m.F(kY, kVy) == 1.0);
  CHECK(m.F(kX, kY) == 0.0);
  // Q = G diag(q^2, q^2) G^T with G per axis = (delta^2 / 2, delta) = (1/2, 1), q^2 = 1/4:
  // Q_pp = 1/4 * 1/4 = 1/16, Q_pv = 1/4 * 1/2 = 1/8, Q_vv = 1/4 * 1 = 1/4; axes uncoupled.
  CHECK(m.Q(kX, kX) == Approx(1.0 / 16).margin(1e-12));
  CHECK(m.Q(kX, kVx) == Approx(1.0 / 8).margin(1e-12));
  CHECK(m.Q(kVx, kVx) == Approx(1.0 / 4).margin(1e-12));
  CHECK(m.Q(kY, kY) == Approx(1.0 / 16).margin(1e-12));
  CHECK(m.Q(kX, kY) == 0.0);
  CHECK(m.Q(kX, kVy) == 0.0);
  // C picks the position; R = r^2 I = 4 I.
  CHECK(m.H(0, kX) == 1.0);
  CHECK(m.H(1, kY) == 1.0);
  CHECK(m.H(0, kVx) == 0.0);
  CHECK(m.R(0, 0) == 4.0);
  CHECK(m.R(0, 1) == 0.0);
}

TEST_CASE("predict and update give the hand-computed numbers of a one-axis case", "[kalman]") {
  // Without process noise the axes decouple; on x: state (p, v) = (0, 1), P = I.
  const ConstantVelocityModel m(1.0, 0.0, 1.0);
  GaussianState s;
  s.x << 0.0, 0.0, 1.0, 0.0;
  s.P = StateMatrix::Identity();

  const GaussianState predicted = predict(m, s);
  // p = 0 + 1 = 1. P = F P F^T with F = [[1, 1], [0, 1]] per axis: [[2, 1], [1, 1]].
  CHECK(predicted.x(kX) == Approx(1.0).margin(1e-12));
  CHECK(predicted.x(kVx) == Approx(1.0).margin(1e-12));
  CHECK(predicted.P(kX, kX) == Approx(2.0).margin(1e-12));
  CHECK(predicted.P(kX, kVx) == Approx(1.0).margin(1e-12));
  CHECK(predicted.P(kVx, kVx) == Approx(1.0).margin(1e-12));
  CHECK(predicted.P(kY, kY) == Approx(2.0).margin(1e-12));
  CHECK(predicted.P(kX, kY) == 0.0);

  const MeasurementVector z(2.0, 0.0);
  const Innovation inn = innovation(m, predicted, z);
  // nu = z - H x = (1, 0); S = P_pp + r^2 = 3 on each axis.
  CHECK(inn.nu(0) == Approx(1.0).margin(1e-12));
  CHECK(inn.S(0, 0) == Approx(3.0).margin(1e-12));
  CHECK(inn.S(1, 1) == Approx(3.0).margin(1e-12));
  // d^2 = 1^2 / 3; ln det S = ln 9; log N = -(1/3 + ln 9 + 2 ln 2 pi) / 2.
  CHECK(mahalanobisSquared(inn) == Approx(1.0 / 3).margin(1e-12));
  CHECK(logDeterminant(inn) == Approx(std::log(9.0)).margin(1e-12));
  CHECK(logLikelihood(inn) ==
        Approx(-0.5 * (1.0 / 3 + std::log(9.0) + 2.0 * std::log(2.0 * std::numbers::pi))).margin(1e-12));

  const auto updated = update(m, predicted, z);
  REQUIRE(updated.has_value());
  // K = P H^T / S = (2/3, 1/3); p = 1 + 2/3, v = 1 + 1/3.
  CHECK(updated->x(kX) == Approx(5.0 / 3).margin(1e-12));
  CHECK(updated->x(kVx) == Approx(4.0 / 3).margin(1e-12));
  CHECK(updated->x(kY) == Approx(0.0).margin(1e-12));
  CHECK(updated->x(kVy) == Approx(0.0).margin(1e-12));
  // (I - K H) P: P_pp = 2 - 2/3 * 2 = 2/3, P_pv = 1 - 2/3 * 1 = 1/3, P_vv = 1 - 1/3 * 1 = 2/3
  // (the Joseph form gives the same for the optimal gain).
  CHECK(updated->P(kX, kX) == Approx(2.0 / 3).margin(1e-12));
  CHECK(updated->P(kX, kVx) == Approx(1.0 / 3).margin(1e-12));
  CHECK(updated->P(kVx, kX) == Approx(1.0 / 3).margin(1e-12));
  CHECK(updated->P(kVx, kVx) == Approx(2.0 / 3).margin(1e-12));
  CHECK(updated->P(kY, kY) == Approx(2.0 / 3).margin(1e-12));
}

TEST_CASE("process noise adds Q to the predicted covariance", "[kalman]") {
  const ConstantVelocityModel m(1.0, 0.5, 1.0);
  GaussianState s;
  s.P = StateMatrix::Identity();
  const GaussianState predicted = predict(m, s);
  // [[2, 1], [1, 1]] + [[1/16, 1/8], [1/8, 1/4]].
  CHECK(predicted.P(kX, kX) == Approx(2.0625).margin(1e-12));
  CHECK(predicted.P(kX, kVx) == Approx(1.125).margin(1e-12));
  CHECK(predicted.P(kVx, kVx) == Approx(1.25).margin(1e-12));
}

TEST_CASE("the covariance stays symmetric positive semidefinite over many cycles", "[kalman]") {
  const ConstantVelocityModel m(1.0, 0.15, 0.5);
  GaussianState s;
  s.x << 10.0, 10.0, 0.0, 0.0;
  s.P = StateMatrix::Identity() * 4.0;
  Stream noise(42, Purpose::kTracker, 0, 0);
  for (int k = 0; k < 500; ++k) {
    s = predict(m, s);
    const MeasurementVector z(10.0 + k + 0.5 * noise.normal(), 10.0 + 0.5 * noise.normal());
    const auto updated = update(m, s, z);
    REQUIRE(updated.has_value());
    s = *updated;
    REQUIRE((s.P - s.P.transpose()).cwiseAbs().maxCoeff() == 0.0);  // symmetrised exactly
    const Eigen::SelfAdjointEigenSolver<StateMatrix> eig(s.P);
    REQUIRE(eig.eigenvalues().minCoeff() > 0.0);
  }
  // The track followed the unit-speed target.
  CHECK(s.x(kVx) == Approx(1.0).margin(0.2));
}

TEST_CASE("a non-finite observation or a singular innovation is refused", "[kalman]") {
  const ConstantVelocityModel m(1.0, 0.15, 0.5);
  GaussianState s;
  s.P = StateMatrix::Identity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_FALSE(update(m, s, MeasurementVector(nan, 0.0)).has_value());

  const ConstantVelocityModel exact(1.0, 0.0, 0.0);  // R = 0
  GaussianState certain;                              // P = 0, so S = 0
  Innovation inn = innovation(exact, certain, MeasurementVector(1.0, 0.0));
  CHECK(std::isinf(mahalanobisSquared(inn)));
  CHECK(std::isinf(logDeterminant(inn)));
  CHECK(logLikelihood(inn) == -std::numeric_limits<double>::infinity());
  CHECK_FALSE(update(exact, certain, MeasurementVector(1.0, 0.0)).has_value());
}

}  // namespace
}  // namespace wsn::common

TEST_CASE("covariances travel row-major and come back unchanged", "[kalman]") {
  wsn::common::StateMatrix P;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) P(r, c) = 10.0 * r + c;
  const auto values = wsn::common::toRowMajor(P);
  CHECK(values[1] == 1.0);   // row 0, column 1
  CHECK(values[4] == 10.0);  // row 1, column 0
  CHECK(wsn::common::fromRowMajor(values) == P);
}

#include "supernode/sbmht/imm.hpp"

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "supernode/sbmht/track_score.hpp"

namespace wsn::supernode::sbmht {
namespace {

using common::GaussianState;
using common::kVx;
using common::kVy;
using common::kX;
using common::kY;
using common::MeasurementKind;
using common::StateMatrix;
using common::StateVector;

StateVector state(double x, double y, double vx, double vy) {
  StateVector s;
  s << x, y, vx, vy;
  return s;
}

GaussianState gaussian(const StateVector& x, const StateVector& diagonal) {
  GaussianState g;
  g.x = x;
  g.P = diagonal.asDiagonal();
  return g;
}

ModeVector modes(std::initializer_list<double> values) {
  ModeVector v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double value : values) v(i++) = value;
  return v;
}

MeasurementModel positionModel() { return MeasurementModel{}; }

MeasurementVector positionReport(double x, double y) {
  MeasurementVector z(2);
  z << x, y;
  return z;
}

/// C1 and C2's tracker: [stop, CV] with the proposed Pi = [[.9, .1], [.05, .95]], a moving track
/// just after a detection (mu0 = 0).
struct StopAndGo {
  Imm imm{{stopModel(1.0), constantVelocityModel(1.0, 0.3)}, [] {
            TransitionMatrix pi(2, 2);
            pi << 0.9, 0.1, 0.05, 0.95;
            return pi;
          }()};
  ImmState track = ImmState::startAt(gaussian(state(0.0, 0.0, 5.0, 0.0), StateVector(4.0, 4.0, 1.0, 1.0)),
                                     modes({0.0, 1.0}));
};

TEST_CASE("the stop model zeroes the velocity and lets the position wander by 0.1 m per second", "[sbmht]") {
  const MotionModel stop = stopModel(1.0);
  CHECK_FALSE(stop.moving());
  const StateVector moved = stop.F * state(3.0, 4.0, 5.0, -6.0);
  CHECK(moved == state(3.0, 4.0, 0.0, 0.0));
  // Q0 = (0.1 m)^2 on each position axis per 1 s scan (docs/ONERA.md §2), nothing on the velocity.
  CHECK(stop.Q(kX, kX) == Approx(0.01));
  CHECK(stop.Q(kY, kY) == Approx(0.01));
  CHECK(stop.Q(kVx, kVx) == 0.0);
  CHECK(stop.Q(kX, kY) == 0.0);
  // Two reports of the same instant (dt = 0) add no noise between them.
  CHECK(stopModel(0.0).Q.isZero());
}

TEST_CASE("the constant-velocity model is the house one with Gamma per axis dt2 over 2 and dt", "[sbmht]") {
  const MotionModel cv = constantVelocityModel(2.0, 1.5);
  const common::ConstantVelocityModel house(2.0, 1.5, 1.0);
  CHECK(cv.moving());
  CHECK(cv.F.isApprox(house.F));
  CHECK(cv.Q.isApprox(house.Q));
  // Q_xx = (dt^2 / 2)^2 sigma^2 = 4 * 2.25 = 9, Q_xvx = dt^3 / 2 sigma^2 = 4 * 2.25 = 9, Q_vxvx = 4 * 2.25 = 9.
  CHECK(cv.Q(kX, kX) == Approx(9.0));
  CHECK(cv.Q(kX, kVx) == Approx(9.0));
  CHECK(cv.Q(kVx, kVx) == Approx(9.0));
}

TEST_CASE("the road model puts the along-road acceleration noise along the road as eq. 6 says", "[sbmht]") {
  // dt = 1: the position block of Q is (1/2)^2 R diag(sd^2, sn^2) R' and the velocity block 1^2 times it.
  const double along = 1.0;
  const double across = 0.1;
  const MotionModel east = roadModel(1.0, 0.0, along, across);
  CHECK(east.kind == MotionKind::road);
  CHECK(east.Q(kX, kX) == Approx(0.25 * along * along));
  CHECK(east.Q(kY, kY) == Approx(0.25 * across * across));
  CHECK(east.Q(kVx, kVx) == Approx(along * along));
  CHECK(east.Q(kX, kY) == Approx(0.0).margin(1e-15));

  const MotionModel north = roadModel(1.0, std::numbers::pi / 2, along, across);
  CHECK(north.Q(kX, kX) == Approx(0.25 * across * across));
  CHECK(north.Q(kY, kY) == Approx(0.25 * along * along));

  // At 45 degrees R diag(a, b) R' = [[a + b, a - b], [a - b, a + b]] / 2.
  const MotionModel diagonal = roadModel(1.0, std::numbers::pi / 4, along, across);
  CHECK(diagonal.Q(kX, kX) == Approx(0.25 * (1.0 + 0.01) / 2));
  CHECK(diagonal.Q(kX, kY) == Approx(0.25 * (1.0 - 0.01) / 2));
  CHECK(diagonal.Q(kVx, kVy) == Approx((1.0 - 0.01) / 2));
  CHECK(diagonal.F.isApprox(constantVelocityModel(1.0, 1.0).F));
}

TEST_CASE("the PROP Pi has diagonal exp of minus dt over tau and splits the rest evenly", "[sbmht]") {
  const std::array<double, 3> taus{20.0, 30.0, 10.0};
  const TransitionMatrix pi = transitionMatrix(1.0, taus);
  // e^{-1/20} = 0.951229, e^{-1/30} = 0.967216, e^{-1/10} = 0.904837 (docs/ONERA.md: .9512, .9672, .9048).
  CHECK(pi(0, 0) == Approx(0.951229));
  CHECK(pi(1, 1) == Approx(0.967216));
  CHECK(pi(2, 2) == Approx(0.904837));
  // Row 0's rest: (1 - 0.951229) / 2 = 0.024385 to each other model.
  CHECK(pi(0, 1) == Approx(0.024385));
  CHECK(pi(0, 2) == Approx(0.024385));
  CHECK(pi(2, 0) == Approx((1.0 - 0.904837) / 2));
  for (Eigen::Index i = 0; i < 3; ++i) CHECK(pi.row(i).sum() == Approx(1.0));
  // No time, no switching; one model has nowhere to go.
  CHECK(transitionMatrix(0.0, taus).isApprox(TransitionMatrix::Identity(3, 3)));
  const std::array<double, 1> single{20.0};
  CHECK(transitionMatrix(1.0, single) == TransitionMatrix::Identity(1, 1));
}

TEST_CASE("C1 misses drive a track into the stop mode at the proposed rates", "[sbmht]") {
  // On a miss (PD = .9, Pe = 1): Lambda^0 = 1, Lambda^1 = 1 - PD = .1, cbar = Pi' mu,
  // Lambda_k = cbar_0 + .1 cbar_1, mu0 = cbar_0 / Lambda_k. From mu0 = 0: cbar = (.05, .95),
  // Lambda_k = .145, mu0 = .05 / .145 = .344828, Delta L = ln .145 = -1.931022. Iterated (python):
  // mu0 = .344828, .839308, .969941, .985846, .987541; Delta L = -1.931022, -.894546, -.239437,
  // -.119905, -.106281. Fixed point: cbar_0 = .05 + .85 mu, cbar_1 = .95 - .85 mu, so
  // mu (.145 + .765 mu) = .05 + .85 mu, i.e. .765 mu^2 - .705 mu - .05 = 0:
  // mu0 = (.705 + sqrt(.650025)) / 1.53 = .9877394, Lambda_k = .145 + .765 mu0 = .900621,
  // Delta L = ln .900621 = -.1046712. The figures of docs/ONERA.md agree.
  StopAndGo t;
  const Detectability seen = Detectability::uniform(0.9, 1.0);
  const std::array<double, 5> mu0{0.344828, 0.839308, 0.969941, 0.985846, 0.987541};
  const std::array<double, 5> delta{-1.931022, -0.894546, -0.239437, -0.119905, -0.106281};
  ImmState s = t.track;
  for (std::size_t k = 0; k < mu0.size(); ++k) {
    const ImmUpdate u = t.imm.stepWithMiss(s, seen);
    CAPTURE(k);
    CHECK(u.state.probabilities(0) == Approx(mu0[k]).margin(1e-6));
    CHECK(missScoreIncrement(u.likelihood) == Approx(delta[k]).margin(1e-6));
    CHECK(u.model_likelihoods(0) == 1.0);
    CHECK(u.model_likelihoods(1) == Approx(0.1));
    s = u.state;
  }
  ImmUpdate u;
  for (int k = 0; k < 200; ++k) {
    u = t.imm.stepWithMiss(s, seen);
    s = u.state;
  }
  CHECK(u.state.probabilities(0) == Approx(0.9877394).margin(1e-7));
  CHECK(missScoreIncrement(u.likelihood) == Approx(-0.1046712).margin(1e-7));
  // The stop model has no velocity: the combined estimate slows down accordingly.
  CHECK(std::abs(s.combined().x(kVx)) < 0.2 * 5.0);

  // A detection rules the stop mode out entirely (eq. 9), however sure of it the track was.
  const GaussianState predicted = t.imm.predict(s).combined();
  const ImmUpdate detected =
      t.imm.stepWithReport(s, positionModel(), positionReport(predicted.x(kX), predicted.x(kY)),
                           MeasurementCovariance::Identity(2, 2), seen);
  CHECK(detected.state.probabilities(0) == 0.0);
  CHECK(detected.state.probabilities(1) == 1.0);
  CHECK(detected.model_likelihoods(0) == 0.0);
  CHECK(detected.likelihood > 0.0);
}

TEST_CASE("C1 with the PROP Pi a stopped track loses 0.0498 per scan and is dropped at its 136th miss",
          "[sbmht]") {
  // Pi from tau = (20, 30) s at dt = 1: [[.951229, .048771], [.032784, .967216]]. The miss
  // recursion of C1 converges (python, 5000 iterations) to mu0 = .994326, Delta L = -.049803
  // (docs/ONERA.md: .9943, -.0498). The notes' "about 200 scans" is 10 / .0498 = 201, the steady rate
  // only: the first misses cost more (-2.044, -1.082, -.253, -.073, ...; -3.50 after five), so
  // the confirmed track's score falls 10 below its best (the last detection) at the 136th miss
  // (sum after 135 misses: -9.979, after 136: -10.029). With the third PROP model (CV 1.5 m/s^2,
  // tau 10 s) it is the 135th from mode probabilities (0, .5, .5), the 122nd from (0, 1, 0).
  const std::array<double, 2> taus{20.0, 30.0};
  const Imm imm({stopModel(1.0), constantVelocityModel(1.0, 0.3)}, transitionMatrix(1.0, taus));
  const Detectability seen = Detectability::uniform(0.9, 1.0);
  const SprtThresholds sprt = SprtThresholds::fromErrorRates(1e-3, 0.1, 10.0);
  ImmState s = StopAndGo{}.track;
  TrackScore score = TrackScore::start(0.0).after(20.0, sprt);
  REQUIRE(score.status == TrackStatus::confirmed);
  int dropped_at = 0;
  ImmUpdate u;
  for (int k = 1; k <= 400 && dropped_at == 0; ++k) {
    u = imm.stepWithMiss(s, seen);
    s = u.state;
    score = score.after(missScoreIncrement(u.likelihood), sprt);
    if (score.status == TrackStatus::deleted) dropped_at = k;
  }
  CHECK(dropped_at == 136);
  CHECK(score.best_score - score.score == Approx(10.0286).margin(1e-3));
  for (int k = 0; k < 2000; ++k) {
    u = imm.stepWithMiss(s, seen);
    s = u.state;
  }
  CHECK(u.state.probabilities(0) == Approx(0.994326).margin(1e-6));
  CHECK(missScoreIncrement(u.likelihood) == Approx(-0.049803).margin(1e-6));
}

TEST_CASE("C2 a masked target keeps its score and its modes only follow Pi", "[sbmht]") {
  // Pe = 0: every Lambda^i = 1 (stop: delta_{d,0} = 1; moving: (1 - PD) * 0 + (1 - 0) = 1), so
  // Lambda_k = sum cbar = 1, Delta L = 0 and mu = Pi' mu: mu0 = .05, .05 * .9 + .95 * .05 = .0925,
  // .128625, .159331, .185432, ... towards Pi's stationary .05 / (.1 + .05) = 1/3.
  StopAndGo t;
  const Detectability masked = Detectability::uniform(0.9, 0.0);
  const std::array<double, 5> mu0{0.05, 0.0925, 0.128625, 0.159331, 0.185432};
  ImmState s = t.track;
  for (std::size_t k = 0; k < mu0.size(); ++k) {
    const ImmUpdate u = t.imm.stepWithMiss(s, masked);
    CAPTURE(k);
    CHECK(u.state.probabilities(0) == Approx(mu0[k]).margin(1e-6));
    CHECK(u.model_likelihoods(1) == 1.0);
    CHECK(missScoreIncrement(u.likelihood) == Approx(0.0).margin(1e-15));
    s = u.state;
  }
  for (int k = 0; k < 500; ++k) s = t.imm.stepWithMiss(s, masked).state;
  CHECK(s.probabilities(0) == Approx(1.0 / 3.0).margin(1e-9));
}

TEST_CASE("a miss weighs each moving model by its own perceivability as eq. 14 says", "[sbmht]") {
  StopAndGo t;
  const ImmPrediction p = t.imm.predict(t.track);
  // PD = .8 and Pe = (ignored, .25): Lambda^1 = .2 * .25 + .75 = .8; Lambda^0 = 1 whatever Pe.
  const ImmUpdate u = t.imm.miss(p, Detectability{0.8, modes({0.0, 0.25})});
  CHECK(u.model_likelihoods(0) == 1.0);
  CHECK(u.model_likelihoods(1) == Approx(0.8));
  // cbar = (.05, .95): Lambda_k = .05 + .8 * .95 = .81.
  CHECK(u.likelihood == Approx(0.81));
  CHECK(u.state.probabilities(0) == Approx(0.05 / 0.81));
  CHECK(std::isinf(u.gate_distance));
  CHECK_THROWS_AS(t.imm.miss(p, Detectability{0.8, modes({1.0, 1.0, 1.0})}), std::invalid_argument);
}

TEST_CASE("a two-model IMM step gives the hand-computed mixing update and mode probabilities", "[sbmht]") {
  // Models: CV with sigma_a = 0.1 (Q_xx = .0025, Q_xvx = .005, Q_vxvx = .01) and 2.0 (Q_xx = 1,
  // Q_xvx = 2, Q_vxvx = 4), dt = 1, Pi = [[.9, .1], [.2, .8]], mu = (.6, .4).
  // Mode 0: x = (0, 0, 1, 0), P = diag(4, 4, 1, 1); mode 1: x = (1, 0, 2, 0), P = diag(9, 9, 4, 4).
  // cbar = Pi' mu = (.54 + .08, .06 + .32) = (.62, .38).
  // Mixing into 0: mu^{i|0} = (.54, .08) / .62 = (.870968, .129032): x0 = (.129032, 0, 1.129032, 0),
  //   P0_xx = .870968 (4 + .129032^2) + .129032 (9 + .870968^2) = 4.757544, P0_xvx = .112383,
  //   P0_vxvx = 1.499480, P0_yy = 4.645161. Predicted: x = (1.258065, 0, 1.129032, 0),
  //   P_xx = 4.757544 + 2 * .112383 + 1.499480 + .0025 = 6.484290, P_yy = 4.645161 + 1.387097 + .0025 = 6.034758.
  // Mixing into 1: mu^{i|1} = (.06, .32) / .38 = (.157895, .842105): x0 = (.842105, 0, 1.842105, 0);
  //   predicted x = (2.684211, 0, 1.842105, 0), P_xx = 13.268698, P_yy = 12.736842.
  // Report z = (3, .5), R = I, PD = .8, Pe = 1 (python, plain lists):
  //   model 0: nu = (1.741935, .5), S = diag(7.484290, 7.034758), d^2 = .440966, N = .0175940;
  //   model 1: nu = (.315789, .5), S = diag(14.268698, 13.736842), d^2 = .025188, N = .0112257.
  //   Lambda = .8 N = (.0140752, .00898059); Lambda_k = .62 * .0140752 + .38 * .00898059 = .0121393;
  //   mu = (.718877, .281123).
  //   x+ (0) = (2.767254, .428924, 1.505350, .098944), x+ (1) = (2.977868, .463602, 1.970297, .201149);
  //   combined x = (2.826463, .438673, 1.636057, .127676), P_xx = .893211, P_vxvx = 2.369908.
  TransitionMatrix pi(2, 2);
  pi << 0.9, 0.1, 0.2, 0.8;
  const Imm imm({constantVelocityModel(1.0, 0.1), constantVelocityModel(1.0, 2.0)}, pi);
  ImmState s;
  s.modes = {gaussian(state(0.0, 0.0, 1.0, 0.0), StateVector(4.0, 4.0, 1.0, 1.0)),
             gaussian(state(1.0, 0.0, 2.0, 0.0), StateVector(9.0, 9.0, 4.0, 4.0))};
  s.probabilities = modes({0.6, 0.4});

  const ImmPrediction p = imm.predict(s);
  CHECK(p.probabilities(0) == Approx(0.62));
  CHECK(p.probabilities(1) == Approx(0.38));
  CHECK(p.modes[0].x(kX) == Approx(1.258065));
  CHECK(p.modes[0].x(kVx) == Approx(1.129032));
  CHECK(p.modes[0].P(kX, kX) == Approx(6.484290));
  CHECK(p.modes[0].P(kY, kY) == Approx(6.034758));
  CHECK(p.modes[1].x(kX) == Approx(2.684211));
  CHECK(p.modes[1].P(kX, kX) == Approx(13.268698));
  CHECK(p.modes[1].P(kY, kY) == Approx(12.736842));

  const ImmUpdate u = imm.report(p, positionModel(), positionReport(3.0, 0.5), MeasurementCovariance::Identity(2, 2),
                                 Detectability::uniform(0.8));
  CHECK(u.model_likelihoods(0) == Approx(0.0140752));
  CHECK(u.model_likelihoods(1) == Approx(0.00898059));
  CHECK(u.likelihood == Approx(0.0121393));
  CHECK(u.gate_distance == Approx(0.025188).margin(1e-6));
  CHECK(u.state.probabilities(0) == Approx(0.718877));
  CHECK(u.state.probabilities(1) == Approx(0.281123));
  CHECK(u.state.modes[0].x(kX) == Approx(2.767254));
  CHECK(u.state.modes[0].x(kVy) == Approx(0.098944));
  CHECK(u.state.modes[1].x(kVx) == Approx(1.970297));
  const GaussianState combined = u.state.combined();
  CHECK(combined.x(kX) == Approx(2.826463));
  CHECK(combined.x(kY) == Approx(0.438673));
  CHECK(combined.x(kVx) == Approx(1.636057));
  CHECK(combined.x(kVy) == Approx(0.127676));
  CHECK(combined.P(kX, kX) == Approx(0.893211));
  CHECK(combined.P(kVx, kVx) == Approx(2.369908));

  // The miss branch from the same prediction (PD = .8, Pe = .5): Lambda^i = .2 * .5 + .5 = .6 for
  // both, so mu stays at cbar and Lambda_k = .6.
  const ImmUpdate missed = imm.miss(p, Detectability::uniform(0.8, 0.5));
  CHECK(missed.likelihood == Approx(0.6));
  CHECK(missed.state.probabilities.isApprox(p.probabilities));
  CHECK(missed.state.modes[1].x == p.modes[1].x);
}

TEST_CASE("a report no model can explain leaves mu at its prediction with zero likelihood", "[sbmht]") {
  // A bearing sensor exactly at the predicted position: no model can linearise there.
  StopAndGo t;
  const ImmPrediction p = t.imm.predict(t.track);
  MeasurementModel bearing;
  bearing.kind = MeasurementKind::bearing;
  bearing.sensor = {p.modes[1].x(kX), p.modes[1].x(kY), 0.0};
  MeasurementVector z(1);
  z << 0.3;
  MeasurementCovariance R(1, 1);
  R << 1e-3;
  const ImmUpdate u = t.imm.report(p, bearing, z, R, Detectability::uniform(0.9));
  CHECK(u.likelihood == 0.0);
  CHECK(u.state.probabilities.isApprox(p.probabilities));
  CHECK(std::isinf(u.gate_distance));
}

TEST_CASE("the IMM rejects a Pi that does not fit its models", "[sbmht]") {
  TransitionMatrix bad(2, 2);
  bad << 0.9, 0.2, 0.05, 0.95;
  CHECK_THROWS_AS(Imm({stopModel(1.0), constantVelocityModel(1.0, 0.3)}, bad), std::invalid_argument);
  CHECK_THROWS_AS(Imm({stopModel(1.0)}, TransitionMatrix::Identity(2, 2)), std::invalid_argument);
  const Imm imm({constantVelocityModel(1.0, 0.3)}, TransitionMatrix::Identity(1, 1));
  CHECK_THROWS_AS(imm.predict(ImmState::startAt(GaussianState{}, modes({0.5, 0.5}))), std::invalid_argument);
}

}  // namespace
}  // namespace wsn::supernode::sbmht

// A sensor's finite reach as a constraint (supernode/sbmht/reach.hpp): the truncated-Gaussian
// moments by hand, and a track fed bearings alone that stays within the antenna's reach.
#include "supernode/sbmht/reach.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <set>
#include <vector>

#include "common/sensor_coverage.hpp"
#include "supernode/sbmht/sbmht_engine.hpp"
#include "tests/supernode/sbmht/sbmht_test_support.hpp"

namespace wsn::supernode::sbmht {
namespace {

using namespace support;
using common::kVx;
using common::kVy;
using common::kX;
using common::kY;
using common::Vec2;

TEST_CASE("reach truncates the distance along the line of sight at the sensor's range, by hand", "[sbmht]") {
  // Sensor at the origin, range 200; the estimate at (300, 0), var 100^2 along x, cov(x, vx) = 100.
  // Along u = (1, 0): d = 300, s = 100, b = (200 - 300) / 100 = -1; Phi(-1) = .158655,
  // phi(-1) = .241971, lambda = phi / Phi = 1.525135. Truncated mean 300 - 100 lambda = 147.4865,
  // variance 100^2 (1 - b lambda - lambda^2) = 10^4 (1 + 1.525135 - 2.326038) = 1990.977.
  // Conditioning: x += P c (147.4865 - 300) / 10^4, so vx = 2 + 100 (-.01525135) = .474865;
  // P -= P c c' P (10^4 - 1990.977) / 10^8 = P c c' P 8.009023e-5: var vx = 4 - 10^4 8.009023e-5 =
  // 3.199098, cov(x, vx) = 100 - 10^6 8.009023e-5 = 19.909767; y untouched.
  common::GaussianState e;
  e.x << 300.0, 0.0, 2.0, 0.0;
  e.P.setZero();
  e.P(kX, kX) = 1e4;
  e.P(kY, kY) = 1.0;
  e.P(kVx, kVx) = 4.0;
  e.P(kVy, kVy) = 1.0;
  e.P(kX, kVx) = e.P(kVx, kX) = 100.0;
  const ReachUpdate r = constrainToReach(e, {0.0, 0.0}, 200.0);
  CHECK(r.probability == Approx(0.158655).epsilon(1e-5));
  CHECK(r.state.x(kX) == Approx(147.4865).epsilon(1e-6));
  CHECK(r.state.x(kY) == 0.0);
  CHECK(r.state.x(kVx) == Approx(0.474865).epsilon(1e-5));
  CHECK(r.state.P(kX, kX) == Approx(1990.977).epsilon(1e-6));
  CHECK(r.state.P(kVx, kVx) == Approx(3.199098).epsilon(1e-6));
  CHECK(r.state.P(kX, kVx) == Approx(19.909767).epsilon(1e-6));
  CHECK(r.state.P(kY, kY) == 1.0);
}

TEST_CASE("reach works along any line and leaves what lies well inside alone", "[sbmht]") {
  // The same scalar problem along u = (.6, .8) from a sensor at (10, 20): the estimate at distance
  // 300, isotropic 10^4 on position. Its position goes to the sensor + 147.4865 u; the variance
  // along u becomes 1990.977, across u it stays 10^4.
  common::GaussianState e;
  e.x << 10.0 + 180.0, 20.0 + 240.0, 0.0, 0.0;
  e.P = common::StateMatrix::Identity();
  e.P(kX, kX) = e.P(kY, kY) = 1e4;
  const ReachUpdate r = constrainToReach(e, {10.0, 20.0}, 200.0);
  CHECK(r.state.x(kX) == Approx(10.0 + 0.6 * 147.4865).epsilon(1e-6));
  CHECK(r.state.x(kY) == Approx(20.0 + 0.8 * 147.4865).epsilon(1e-6));
  const Eigen::Vector2d u(0.6, 0.8);
  const Eigen::Vector2d n(-0.8, 0.6);
  const Eigen::Matrix2d P = r.state.P.topLeftCorner<2, 2>();
  CHECK(u.dot(P * u) == Approx(1990.977).epsilon(1e-6));
  CHECK(n.dot(P * n) == Approx(1e4).epsilon(1e-12));
  // 10 from the sensor with s = 1: b = 190, Phi(b) = 1 in doubles, nothing changes.
  common::GaussianState near;
  near.x << 16.0, 28.0, 1.0, 0.0;
  near.P = common::StateMatrix::Identity();
  const ReachUpdate inside = constrainToReach(near, {10.0, 20.0}, 200.0);
  CHECK(inside.probability == 1.0);
  CHECK(inside.state.x == near.x);
  CHECK(inside.state.P == near.P);
  // Far beyond reach, 1000 with s = 1 from a range of 5: Phi(-995) underflows, nothing is left of
  // the estimate within reach, and it is returned unchanged with probability 0.
  const ReachUpdate beyond = constrainToReach(near, {10.0, 20.0 - 1000.0}, 5.0);
  CHECK(beyond.probability == 0.0);
  CHECK(beyond.state.x == near.x);
  // Far beyond reach with no spread left: impossible.
  near.P.setZero();
  CHECK(constrainToReach(near, {10.0, 20.0}, 5.0).probability == 0.0);
}

TEST_CASE("sbmht keeps a track fed bearings alone within the antenna's reach", "[sbmht]") {
  // An all-round antenna at A = (10, 10) hears up to 50. A second sensor, not in the list (its
  // silence is no evidence), places the target for 10 ticks while it moves out along the diagonal
  // at 1 a tick; then it turns back and creeps towards the antenna at 0.3 a tick, heard by the
  // antenna alone. Its bearing never changes, so nothing in the bearings says it turned: with the
  // constraint switched off in the code, the track ran on outwards to 70 from A by tick 60 (this
  // test then fails). Each bearing proves the target within 50 of A, and the track stays there,
  // confirmed under its id.
  const Vec2 antenna{10.0, 10.0};
  const common::SensorId kAntenna = 1;
  const common::SensorId kLocator = 2;
  Harness h(sbmhtScenario(), [&](EngineContext& c) {
    c.coverage = {common::SensorCoverage{kAntenna, antenna, 0.0, 2.0 * std::numbers::pi, 50.0, 0.9,
                                         common::SightBlockers::none}};
  });
  const Vec2 u{std::sqrt(0.5), std::sqrt(0.5)};
  auto range = [](std::int32_t t) { return t <= 10 ? 10.0 + t : 20.0 - 0.3 * (t - 10); };
  auto speed = [](std::int32_t t) { return t <= 10 ? 1.0 : -0.3; };
  const double sigma = 3.0 * kDegree;
  std::set<common::TrackId> ids;
  for (std::int32_t t = 1; t <= 60; ++t) {
    const Vec2 p{antenna.x + range(t) * u.x, antenna.y + range(t) * u.y};
    const Vec2 v{speed(t) * u.x, speed(t) * u.y};
    std::vector<common::Observation> reports{sensed(t, kAntenna, {antenna.x, antenna.y, 0.0, 0.0},
                                                    common::MeasurementKind::bearing, p, v, {sigma * sigma},
                                                    0.01 / (2.0 * std::numbers::pi))};
    if (t <= 10)
      reports.push_back(sensed(t, kLocator, {90.0, 90.0, 0.0, 0.0}, common::MeasurementKind::position, p, v,
                               {1.0, 1.0}, 1e-4));
    h.step(t, reports);
    const auto tracks = h.engine.confirmedTracks();
    for (const auto& track : tracks) ids.insert(track.track);
    if (t <= 10) continue;
    REQUIRE(tracks.size() == 1);
    INFO("tick " << t << ": the track is " << distance(tracks[0], antenna) << " from the antenna");
    CHECK(distance(tracks[0], antenna) <= 50.0);
  }
  CHECK(ids.size() == 1);
}

}  // namespace
}  // namespace wsn::supernode::sbmht

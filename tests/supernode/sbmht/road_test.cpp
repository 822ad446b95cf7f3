#include "supernode/sbmht/road.hpp"

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
using common::StateMatrix;
using common::StateVector;

GaussianState at(double x, double y, double vx, double vy, const StateMatrix& P = StateMatrix::Identity()) {
  GaussianState g;
  g.x << x, y, vx, vy;
  g.P = P;
  return g;
}

/// East 100 m, then north 100 m.
const Road kBend{{{0.0, 0.0}, {100.0, 0.0}, {100.0, 100.0}}};

TEST_CASE("the foot point lies on the nearest segment of a polyline", "[sbmht]") {
  // (30, 4): 4 m from the first segment, 70 m from the second.
  const auto first = footPoint(kBend, {30.0, 4.0});
  REQUIRE(first);
  CHECK(first->segment == 0);
  CHECK(first->point == common::Vec2{30.0, 0.0});
  CHECK(first->distance == Approx(4.0));
  CHECK(first->heading() == Approx(0.0));

  // (97, 60): 3 m from the second segment.
  const auto second = footPoint(kBend, {97.0, 60.0});
  REQUIRE(second);
  CHECK(second->segment == 1);
  CHECK(second->point.x == Approx(100.0));
  CHECK(second->point.y == Approx(60.0));
  CHECK(second->distance == Approx(3.0));
  CHECK(second->heading() == Approx(std::numbers::pi / 2));

  // Beyond the road's start, the foot is the end point (clamped), 5 m away.
  const auto before = footPoint(kBend, {-3.0, 4.0});
  REQUIRE(before);
  CHECK(before->point == common::Vec2{0.0, 0.0});
  CHECK(before->distance == Approx(5.0));

  // Outside the bend, both segments are nearest at the shared vertex: the first one wins.
  const auto corner = footPoint(kBend, {110.0, -10.0});
  REQUIRE(corner);
  CHECK(corner->segment == 0);
  CHECK(corner->point == common::Vec2{100.0, 0.0});

  // A zero-length segment is skipped; a road without a segment has no foot point.
  const Road repeated{{{0.0, 0.0}, {0.0, 0.0}, {0.0, 10.0}}};
  const auto foot = footPoint(repeated, {2.0, 5.0});
  REQUIRE(foot);
  CHECK(foot->segment == 1);
  CHECK_FALSE(footPoint(Road{{{1.0, 1.0}, {1.0, 1.0}}}, {0.0, 0.0}));
  CHECK_FALSE(footPoint(Road{}, {0.0, 0.0}));
}

TEST_CASE("C8 projection moves the position to the foot point and keeps the speed along the road", "[sbmht]") {
  // At (30, 4) with v = (3, 4): |v| = 5 at atan2(4, 3) = 53.13 degrees off the road (east), cos = .6,
  // so v becomes 5 * .6 = 3 along the segment: (3, 0).
  const auto projected = projectOntoRoad(at(30.0, 4.0, 3.0, 4.0), kBend, 0.0);
  REQUIRE(projected);
  CHECK(projected->x(kX) == Approx(30.0));
  CHECK(projected->x(kY) == Approx(0.0).margin(1e-12));
  CHECK(projected->x(kVx) == Approx(3.0));
  CHECK(projected->x(kVy) == Approx(0.0).margin(1e-12));

  // Driving the other way: v = (-3, 4) has cos = -.6, i.e. 3 m/s against the segment's direction.
  const auto back = projectOntoRoad(at(30.0, 4.0, -3.0, 4.0), kBend, 0.0);
  REQUIRE(back);
  CHECK(back->x(kVx) == Approx(-3.0));

  // A diagonal road y = x: (10, 0) has foot (5, 5); v = (2, 0) is 45 degrees off, so
  // 2 cos 45 = sqrt 2 along u = (1, 1) / sqrt 2: v = (1, 1).
  const Road diagonal{{{0.0, 0.0}, {100.0, 100.0}}};
  const auto onto = projectOntoRoad(at(10.0, 0.0, 2.0, 0.0), diagonal, 0.0);
  REQUIRE(onto);
  CHECK(onto->x(kX) == Approx(5.0));
  CHECK(onto->x(kY) == Approx(5.0));
  CHECK(onto->x(kVx) == Approx(1.0));
  CHECK(onto->x(kVy) == Approx(1.0));
  CHECK(std::hypot(onto->x(kVx), onto->x(kVy)) == Approx(2.0 * std::cos(std::numbers::pi / 4)));
}

TEST_CASE("moving onto the road moves the mean as the projection does and keeps the covariance", "[sbmht]") {
  // The C8 case above: (30, 4), v = (3, 4) on the road east goes to (30, 0), v = (3, 0); P = I stays.
  const auto foot = footPoint(kBend, {30.0, 4.0});
  REQUIRE(foot);
  const GaussianState moved = moveOntoRoad(at(30.0, 4.0, 3.0, 4.0), *foot);
  CHECK(moved.x(kX) == Approx(30.0));
  CHECK(moved.x(kY) == Approx(0.0).margin(1e-12));
  CHECK(moved.x(kVx) == Approx(3.0));
  CHECK(moved.x(kVy) == Approx(0.0).margin(1e-12));
  CHECK(moved.P == at(30.0, 4.0, 3.0, 4.0).P);
}

TEST_CASE("projection keeps only the along-road covariance plus the road's own location error", "[sbmht]") {
  // Road east, P = I: T = diag(u u', u u') with u u' = diag(1, 0), so T P T' = diag(1, 0, 1, 0).
  const auto foot = footPoint(kBend, {30.0, 4.0});
  REQUIRE(foot);
  const GaussianState exact = projectOntoRoad(at(30.0, 4.0, 3.0, 4.0), *foot, 0.0);
  CHECK(exact.P.isApprox(StateVector(1.0, 0.0, 1.0, 0.0).asDiagonal().toDenseMatrix()));
  // A 1 m GIS error puts 1 m^2 back across the road on the position only: diag(1, 1, 1, 0).
  const GaussianState gis = projectOntoRoad(at(30.0, 4.0, 3.0, 4.0), *foot, 1.0);
  CHECK(gis.P.isApprox(StateVector(1.0, 1.0, 1.0, 0.0).asDiagonal().toDenseMatrix()));

  // Diagonal road, P = I: u u' = [[.5, .5], [.5, .5]] (idempotent, so T P T' = T); the GIS term
  // sigma^2 n n' = [[.5, -.5], [-.5, .5]] completes the position block to I.
  const Road diagonal{{{0.0, 0.0}, {100.0, 100.0}}};
  const auto projected = projectOntoRoad(at(10.0, 0.0, 2.0, 0.0), diagonal, 1.0);
  REQUIRE(projected);
  CHECK(projected->P(kX, kX) == Approx(1.0));
  CHECK(projected->P(kX, kY) == Approx(0.0).margin(1e-12));
  CHECK(projected->P(kVx, kVx) == Approx(0.5));
  CHECK(projected->P(kVx, kVy) == Approx(0.5));
  CHECK(projected->P(kX, kVx) == Approx(0.0).margin(1e-12));

  // Correlations along the road survive: P_x,vx = .7 on an east road stays .7.
  StateMatrix P = StateMatrix::Identity();
  P(kX, kVx) = P(kVx, kX) = 0.7;
  P(kY, kVy) = P(kVy, kY) = 0.4;
  const GaussianState correlated = projectOntoRoad(at(30.0, 4.0, 3.0, 4.0, P), *foot, 0.0);
  CHECK(correlated.P(kX, kVx) == Approx(0.7));
  CHECK(correlated.P(kY, kVy) == Approx(0.0).margin(1e-12));
}

}  // namespace
}  // namespace wsn::supernode::sbmht

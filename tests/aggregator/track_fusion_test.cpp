#include "aggregator/track_fusion.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <array>
#include <vector>

using wsn::aggregator::covarianceIntersection;
using wsn::aggregator::fuseTrackEstimates;
using wsn::aggregator::GaussianEstimate;
using wsn::common::TrackEstimate;

namespace {

std::array<double, 16> diagonal(double a, double b, double c, double d) {
  return {a, 0, 0, 0, 0, b, 0, 0, 0, 0, c, 0, 0, 0, 0, d};
}

TrackEstimate track(wsn::common::TrackId id, double x, double y, const std::array<double, 16>& covariance, int seen) {
  TrackEstimate t;
  t.track = id;
  t.x = x;
  t.y = y;
  t.vx = 1.0;
  t.vy = 0.0;
  t.covariance = covariance;
  t.last_seen_tick = seen;
  return t;
}

}  // namespace

TEST_CASE("Covariance intersection of two equal-quality estimates halves the way and keeps their covariance",
          "[aggregator][track_fusion]") {
  // P1 = P2 = P: det(w P^-1 + (1 - w) P^-1) is flat in w, and for any w P_ci = P and x = the weighted mean;
  // the search's middle w = 0.5 gives the midpoint.
  const GaussianEstimate a{{0, 0, 1, 0}, diagonal(1, 1, 0.1, 0.1), 1.0};
  const GaussianEstimate b{{2, 4, 1, 0}, diagonal(1, 1, 0.1, 0.1), 1.0};
  const auto fused = covarianceIntersection(a, b);
  CHECK(fused.weight == Approx(0.5).margin(1e-6));
  CHECK(fused.state[0] == Approx(1.0));
  CHECK(fused.state[1] == Approx(2.0));
  CHECK(fused.covariance[0] == Approx(1.0));
  CHECK(fused.covariance[10] == Approx(0.1));
}

TEST_CASE("Covariance intersection takes the estimate that is better in every direction",
          "[aggregator][track_fusion]") {
  // P1 = P2 / 4: det(w I1 + (1 - w) I2) = det(I2) (4w + 1 - w)^4 grows with w, so w = 1 and the fused
  // estimate is the first one exactly: CI never claims more than the better estimate knows.
  const GaussianEstimate good{{10, 20, 1, -1}, diagonal(0.25, 0.25, 0.025, 0.025), 1.0};
  const GaussianEstimate poor{{11, 21, 0, 0}, diagonal(1, 1, 0.1, 0.1), 1.0};
  const auto fused = covarianceIntersection(good, poor);
  CHECK(fused.weight == 1.0);
  CHECK(fused.state[0] == Approx(10.0));
  CHECK(fused.state[3] == Approx(-1.0));
  CHECK(fused.covariance[0] == Approx(0.25));
}

TEST_CASE("Covariance intersection of complementary estimates is sharper in each one's good direction",
          "[aggregator][track_fusion]") {
  // a knows x well (var 0.1) and y poorly (var 1), b the opposite. By symmetry w = 0.5: the fused
  // information is the mean, diag(5.5, 5.5, ...), so var 1/5.5 = 0.1818 on both axes, and the state
  // is x = (0.5 * 10 * 0 + 0.5 * 1 * 1) / 5.5 = 0.0909 (nearer a's x), y = 0.9091 (nearer b's y).
  const GaussianEstimate a{{0, 0, 0, 0}, diagonal(0.1, 1, 1, 1), 1.0};
  const GaussianEstimate b{{1, 1, 0, 0}, diagonal(1, 0.1, 1, 1), 1.0};
  const auto fused = covarianceIntersection(a, b);
  CHECK(fused.weight == Approx(0.5).margin(1e-6));
  CHECK(fused.covariance[0] == Approx(1.0 / 5.5));
  CHECK(fused.covariance[5] == Approx(1.0 / 5.5));
  CHECK(fused.state[0] == Approx(0.5 / 5.5));
  CHECK(fused.state[1] == Approx(5.0 / 5.5));
  // Consistent whatever the correlation: the fused covariance is never smaller than the optimal
  // fusion of independent estimates (its information never exceeds I1 + I2).
  Eigen::Matrix4d p = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(fused.covariance.data());
  const Eigen::Vector4d independent_information{11.0, 11.0, 2.0, 2.0};
  const Eigen::Matrix4d gap = Eigen::Matrix4d(independent_information.asDiagonal()) - p.inverse();
  CHECK(gap.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff() >= -1e-9);
}

TEST_CASE("One supernode track passes through as published", "[aggregator][track_fusion]") {
  TrackEstimate only = track(7, 3.0, 4.0, diagonal(0.01, 0.01, 0.02, 0.02), 5);
  only.class_probabilities = {0.25, 0.75};
  only.stop_probability = 0.1;
  const TrackEstimate* members[] = {&only};
  const auto fused = fuseTrackEstimates(42, members);
  TrackEstimate expected = only;
  expected.track = 42;
  CHECK(fused == expected);
}

TEST_CASE("Several supernode tracks fuse by covariance intersection, the latest observation kept",
          "[aggregator][track_fusion]") {
  const TrackEstimate a = track(1, 0.0, 0.0, diagonal(1, 1, 0.1, 0.1), 8);
  const TrackEstimate b = track(2, 2.0, 4.0, diagonal(1, 1, 0.1, 0.1), 9);
  const TrackEstimate* members[] = {&a, &b};
  const auto fused = fuseTrackEstimates(5, members);
  CHECK(fused.track == 5);
  CHECK(fused.x == Approx(1.0));
  CHECK(fused.y == Approx(2.0));
  CHECK(fused.vx == Approx(1.0));
  CHECK(fused.last_seen_tick == 9);
  CHECK(fused.covariance[0] == Approx(1.0));
}

TEST_CASE("Tracks without a covariance are averaged, and left out when another has one", "[aggregator][track_fusion]") {
  const TrackEstimate a = track(1, 0.0, 0.0, {}, 3);
  const TrackEstimate b = track(2, 2.0, 4.0, {}, 3);
  const TrackEstimate* none[] = {&a, &b};
  const auto mean = fuseTrackEstimates(5, none);
  CHECK(mean.x == Approx(1.0));
  CHECK(mean.y == Approx(2.0));
  const TrackEstimate c = track(3, 10.0, 10.0, diagonal(1, 1, 1, 1), 3);
  const TrackEstimate* mixed[] = {&a, &c};
  const auto known = fuseTrackEstimates(5, mixed);
  CHECK(known.x == Approx(10.0));
  CHECK(known.covariance[0] == Approx(1.0));
}

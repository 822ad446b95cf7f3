#include "aggregator/track_fusion.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/class_evidence.hpp"
#include "common/kalman.hpp"

namespace wsn::aggregator {
namespace {

using common::StateMatrix;
using common::StateVector;

/// The information matrix of a covariance, or none when it is not positive definite.
std::optional<StateMatrix> informationOf(const std::array<double, 16>& covariance) {
  const StateMatrix p = common::fromRowMajor(covariance);
  if (!p.allFinite()) return std::nullopt;
  const Eigen::LLT<StateMatrix> llt(0.5 * (p + p.transpose()));
  if (llt.info() != Eigen::Success) return std::nullopt;
  return llt.solve(StateMatrix::Identity());
}

/// The weight w in [0, 1] of the first estimate that minimises det P of their intersection.
double intersectionWeight(const StateMatrix& i1, const StateMatrix& i2) {
  // det P = 1 / det(w I1 + (1 - w) I2), and log det of the information is concave in w: its
  // derivative g(w) = tr((w I1 + (1 - w) I2)^-1 (I1 - I2)) falls with w, so the optimum is where g
  // changes sign, or an end of [0, 1] when it does not. When g is 0 throughout (the two estimates
  // are equally good: every w gives the same P) the middle is taken, the estimates' plain mean.
  const StateMatrix difference = i1 - i2;
  const auto slope = [&](double w) { return (w * i1 + (1.0 - w) * i2).llt().solve(difference).trace(); };
  const double at_zero = slope(0.0);
  const double at_one = slope(1.0);
  if (at_zero <= 0.0 && at_one >= 0.0) return 0.5;  // g falls, so it is 0 throughout
  if (at_one >= 0.0) return 1.0;                     // g > 0 on [0, 1]: the first is better everywhere
  if (at_zero <= 0.0) return 0.0;                    // g < 0 on [0, 1]: the second is
  double low = 0.0;
  double high = 1.0;
  for (int step = 0; step < 60; ++step) {
    const double w = 0.5 * (low + high);
    (slope(w) > 0.0 ? low : high) = w;
  }
  return 0.5 * (low + high);
}

/// The covariance intersection of two estimates whose information matrices the caller has.
GaussianEstimate intersect(const GaussianEstimate& first, const StateMatrix& i1, const GaussianEstimate& second,
                           const StateMatrix& i2) {
  GaussianEstimate out;
  out.weight = intersectionWeight(i1, i2);
  const double w = out.weight;
  const StateMatrix covariance = (w * i1 + (1.0 - w) * i2).llt().solve(StateMatrix::Identity());
  const StateVector x1 = Eigen::Map<const StateVector>(first.state.data());
  const StateVector x2 = Eigen::Map<const StateVector>(second.state.data());
  Eigen::Map<StateVector>(out.state.data()) = covariance * (w * i1 * x1 + (1.0 - w) * i2 * x2);
  out.covariance = common::toRowMajor(0.5 * (covariance + covariance.transpose()));
  return out;
}

/// Sets `fused`'s state and covariance from the members': covariance intersection of those that
/// have a covariance, else the plain mean.
void fuseStates(common::TrackEstimate& fused, std::span<const common::TrackEstimate* const> members) {
  std::optional<GaussianEstimate> folded;
  for (const auto* member : members) {
    const auto information = informationOf(member->covariance);
    if (!information) continue;
    const GaussianEstimate estimate{{member->x, member->y, member->vx, member->vy}, member->covariance, 1.0};
    if (!folded) {
      folded = estimate;
      continue;
    }
    // The folded covariance is an LLT solve's, positive definite but for rounding at extremes: one
    // that can no longer be inverted gives way to the member.
    if (const auto folded_information = informationOf(folded->covariance))
      folded = intersect(*folded, *folded_information, estimate, *information);
    else
      folded = estimate;
  }
  if (folded) {
    fused.x = folded->state[0];
    fused.y = folded->state[1];
    fused.vx = folded->state[2];
    fused.vy = folded->state[3];
    fused.covariance = folded->covariance;
    return;
  }
  // No member says how good it is: every one counts the same.
  fused.x = fused.y = fused.vx = fused.vy = 0.0;
  for (const auto* member : members) {
    fused.x += member->x;
    fused.y += member->y;
    fused.vx += member->vx;
    fused.vy += member->vy;
  }
  const auto n = static_cast<double>(members.size());
  fused.x /= n;
  fused.y /= n;
  fused.vx /= n;
  fused.vy /= n;
}

}  // namespace

GaussianEstimate covarianceIntersection(const GaussianEstimate& first, const GaussianEstimate& second) {
  const auto i1 = informationOf(first.covariance);
  const auto i2 = informationOf(second.covariance);
  if (!i1 || !i2) throw std::invalid_argument("covarianceIntersection: a covariance is not positive definite");
  return intersect(first, *i1, second, *i2);
}

bool sameTarget(const common::TrackEstimate& a, const common::TrackEstimate& b, double gate_chi2) {
  const Eigen::Matrix2d sum =
      common::fromRowMajor(a.covariance).topLeftCorner<2, 2>() + common::fromRowMajor(b.covariance).topLeftCorner<2, 2>();
  if (!sum.allFinite()) return true;
  const Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (sum + sum.transpose()));
  if (llt.info() != Eigen::Success) return true;
  const Eigen::Vector2d difference{a.x - b.x, a.y - b.y};
  return difference.dot(llt.solve(difference)) <= gate_chi2;
}

common::TrackEstimate fuseTrackEstimates(common::TrackId id, std::span<const common::TrackEstimate* const> members) {
  if (members.empty()) throw std::invalid_argument("fuseTrackEstimates: no member");
  common::TrackEstimate fused = *members.front();
  fused.track = id;
  if (members.size() == 1) return fused;
  fuseStates(fused, members);
  std::vector<std::span<const double>> classes;
  std::vector<std::optional<double>> stopped;
  for (const auto* member : members) {
    fused.last_seen_tick = std::max(fused.last_seen_tick, member->last_seen_tick);
    classes.emplace_back(member->class_probabilities);
    stopped.push_back(member->stop_probability);
  }
  fused.class_probabilities = common::fuseClassVectors(classes);
  fused.stop_probability = common::fuseStopProbabilities(stopped);
  return fused;
}

}  // namespace wsn::aggregator

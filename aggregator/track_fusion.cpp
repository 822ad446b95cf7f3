#include "aggregator/track_fusion.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/class_evidence.hpp"

namespace wsn::aggregator {
namespace {

using Matrix4 = Eigen::Matrix4d;
using Vector4 = Eigen::Vector4d;

Matrix4 matrixOf(const std::array<double, 16>& values) {
  return Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(values.data());
}

std::array<double, 16> valuesOf(const Matrix4& m) {
  std::array<double, 16> values{};
  Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(values.data()) = m;
  return values;
}

/// The information matrix of a covariance, or none when it is not positive definite.
std::optional<Matrix4> informationOf(const std::array<double, 16>& covariance) {
  const Matrix4 p = matrixOf(covariance);
  if (!p.allFinite()) return std::nullopt;
  const Eigen::LLT<Matrix4> llt(0.5 * (p + p.transpose()));
  if (llt.info() != Eigen::Success) return std::nullopt;
  return llt.solve(Matrix4::Identity());
}

bool positiveDefinite(const std::array<double, 16>& covariance) { return informationOf(covariance).has_value(); }

}  // namespace

namespace {

/// Sets `fused`'s state and covariance from the members': covariance intersection of those that
/// have a covariance, else the plain mean.
void fuseStates(common::TrackEstimate& fused, std::span<const common::TrackEstimate* const> members) {
  std::optional<GaussianEstimate> folded;
  for (const auto* member : members) {
    if (!positiveDefinite(member->covariance)) continue;
    const GaussianEstimate estimate{{member->x, member->y, member->vx, member->vy}, member->covariance, 1.0};
    folded = folded ? covarianceIntersection(*folded, estimate) : estimate;
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
  // det P = 1 / det(w I1 + (1 - w) I2), and log det of the information is concave in w: its
  // derivative g(w) = tr((w I1 + (1 - w) I2)^-1 (I1 - I2)) falls with w, so the optimum is where g
  // changes sign, or an end of [0, 1] when it does not. When g is 0 throughout (the two estimates
  // are equally good: every w gives the same P) the middle is taken, the estimates' plain mean.
  const Matrix4 difference = *i1 - *i2;
  const auto slope = [&](double w) {
    return (w * *i1 + (1.0 - w) * *i2).llt().solve(difference).trace();
  };
  const double at_zero = slope(0.0);
  const double at_one = slope(1.0);
  double w = 0.5;  // g = 0 throughout
  if (at_zero > 0.0 && at_one >= 0.0) {
    w = 1.0;
  } else if (at_zero <= 0.0 && at_one < 0.0) {
    w = 0.0;
  } else if (at_zero > 0.0 && at_one < 0.0) {
    double low = 0.0;
    double high = 1.0;
    for (int step = 0; step < 60; ++step) {
      w = 0.5 * (low + high);
      (slope(w) > 0.0 ? low : high) = w;
    }
    w = 0.5 * (low + high);
  }
  const Matrix4 information = w * *i1 + (1.0 - w) * *i2;
  const Matrix4 covariance = information.llt().solve(Matrix4::Identity());
  const Vector4 x1 = Eigen::Map<const Vector4>(first.state.data());
  const Vector4 x2 = Eigen::Map<const Vector4>(second.state.data());
  const Vector4 x = covariance * (w * *i1 * x1 + (1.0 - w) * *i2 * x2);
  GaussianEstimate out;
  Eigen::Map<Vector4>(out.state.data()) = x;
  out.covariance = valuesOf(0.5 * (covariance + covariance.transpose()));
  out.weight = w;
  return out;
}

bool sameTarget(const common::TrackEstimate& a, const common::TrackEstimate& b, double gate_chi2) {
  const Eigen::Matrix2d sum = matrixOf(a.covariance).topLeftCorner<2, 2>() + matrixOf(b.covariance).topLeftCorner<2, 2>();
  const Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (sum + sum.transpose()));
  if (!sum.allFinite() || llt.info() != Eigen::Success) return true;
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

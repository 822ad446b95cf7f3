// Track-to-track fusion at the aggregator: the estimates several supernodes publish of one target,
// combined from their states and covariances as published, never re-filtered as if they were reports.
#pragma once

#include <array>
#include <span>

#include "common/messages.hpp"

namespace wsn::aggregator {

/// The covariance intersection of two Gaussian estimates (Julier & Uhlmann 1997):
///   P^-1 = w P1^-1 + (1 - w) P2^-1,   x = P (w P1^-1 x1 + (1 - w) P2^-1 x2),
/// with w in [0, 1] minimising det P. Consistent whatever the two estimates' cross-correlation,
/// which is unknown here: two supernodes' tracks of one target share its process noise, and during
/// a handoff the receiver's track starts from the sender's state.
struct GaussianEstimate {
  std::array<double, 4> state{};        ///< x, y, vx, vy
  std::array<double, 16> covariance{};  ///< row-major 4x4
  double weight = 1.0;                  ///< w given to the first estimate (1 when there was one)
};
GaussianEstimate covarianceIntersection(const GaussianEstimate& first, const GaussianEstimate& second);

/// The track-to-track association test (Bar-Shalom 1981): two estimates of one tick are of one
/// target when their positions differ by at most the chi-square gate (2 degrees of freedom) under
/// the sum of their position covariances, Mahalanobis d^2 = dp^T (P1 + P2)^-1 dp <= gate. Their
/// errors' correlation, unknown here, only makes the true sum smaller, so the test is lenient.
/// Without positive-definite covariances the test cannot say no: true.
/// The gate: 99.99 % of a chi-square with 2 degrees of freedom, so that one target's two estimates
/// fail it once in 10,000 ticks; another target linked over a long gap lies far outside it.
inline constexpr double kSameTargetGateChi2 = 18.42;
bool sameTarget(const common::TrackEstimate& a, const common::TrackEstimate& b, double gate_chi2 = kSameTargetGateChi2);

/// One global track from the supernode tracks that hold its target at this tick, in the order
/// given (callers pass them in id order, so that the result is canonical):
///  - one member: its estimate as published (state, covariance, last_seen_tick, class, stop);
///  - several with covariances: their covariance intersection, folded in order; a member whose
///    covariance is not positive definite (an engine that publishes none) is left out of it,
///    unless no member has one: then the mean of the states;
///  - last_seen_tick: the latest member's; class and stop probability fused as
///    common/class_evidence.hpp fuses them.
/// `members` must not be empty; the result's id is `id`.
common::TrackEstimate fuseTrackEstimates(common::TrackId id, std::span<const common::TrackEstimate* const> members);

}  // namespace wsn::aggregator

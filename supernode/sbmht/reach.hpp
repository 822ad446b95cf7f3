// A sensor's finite reach as a constraint on a track (docs/ONERA.md §8): a report of a sensor that
// sees no farther than `range` proves the target within that range. For a bearing, which says
// nothing along its line, this is the only bound on how far along the line the estimate may drift.
#pragma once

#include "common/geometry.hpp"
#include "common/kalman.hpp"

namespace wsn::supernode::sbmht {

/// A Gaussian estimate conditioned on the target lying within reach of a sensor.
struct ReachUpdate {
  common::GaussianState state;
  /// P(within reach) under the estimate before it: the factor the report's likelihood gains.
  double probability = 1.0;
};

/// The constraint |p - sensor| <= range, taken along the line from the sensor through the
/// estimate's position (u), is u'(p - sensor) <= range: a half-plane. The estimate's distance along
/// u is N(d, s^2) with d = |p - sensor|, s^2 = u' P_pos u; truncated at `range` (Simon and Simon,
/// "Constrained Kalman filtering via density function truncation for turbofan engine health
/// estimation", Int. J. Systems Science 41(2), 2010) it has mean d - s lambda and variance
/// s^2 (1 - b lambda - lambda^2), with b = (range - d) / s and lambda = phi(b) / Phi(b). The whole
/// state follows by Gaussian conditioning on that scalar: x += P c (mean - d) / s^2 and
/// P -= P c c' P (s^2 - variance) / s^4, c = (u, 0, 0). probability is Phi(b); 0 (the state
/// unchanged) when the estimate lies so far beyond reach that Phi(b) underflows. An estimate at
/// the sensor, or one with no spread along u, is returned as it is, with probability 1 or 0 by
/// whether it is within reach.
ReachUpdate constrainToReach(const common::GaussianState& estimate, common::Vec2 sensor, double range);

}  // namespace wsn::supernode::sbmht

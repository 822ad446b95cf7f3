// The per-sensor signal model of Oh et al. eq. (5) and the noise-only exceedance statistics
// that let a tile skip every sensor no target is near.
#pragma once

#include <cstdint>
#include <vector>

#include "common/rng.hpp"
#include "node/signal_strength/config.hpp"

namespace wsn::node {

/// Oh et al., eq. 5: the noise-free signal beta / (1 + gamma d^alpha) of a target at distance d
/// (the caller applies the range test d <= Rs).
double signalStrength(const signal_strength::SignalStrengthSettings& model, double distance);

/// q = P(sigma w >= eta), w ~ N(0, 1): the probability that a sensor no target is near reports
/// a false detection. sigma = 0 gives 1 when eta <= 0 (z = 0 passes) and 0 otherwise.
double noiseExceedanceProbability(const signal_strength::SignalStrengthSettings& model);

/// One draw of w ~ N(0, 1) conditioned on w >= a. For a >= 0: Robert (1995) exponential
/// rejection, proposal a + Exp(lambda) with lambda = (a + sqrt(a^2 + 4)) / 2, accepted with
/// probability exp(-(w - lambda)^2 / 2) (exact; acceptance >= 0.76 for every a >= 0, and it
/// never loses precision deep in the tail as inversion of the CDF would). For a < 0: plain
/// rejection from N(0, 1) (acceptance >= 1/2). Consumes a data-dependent but deterministic
/// number of draws from `stream`.
double sampleNormalTail(common::Stream& stream, double a);

/// Geometric(q) skips: the number of Bernoulli(q) failures before the next success, drawn by
/// inversion floor(log U / log(1 - q)) from one uniform U of the stream, the same formula as
/// common::Stream::geometric with log(1 - q) computed once.
class GeometricSkips {
 public:
  /// q outside [0, 1] is clamped; q = 0 never succeeds.
  explicit GeometricSkips(double q);

  /// One draw; UINT64_MAX when q = 0.
  std::uint64_t draw(common::Stream& stream) const;

  /// min(draw(stream), limit), consuming the same uniform: when U <= (1 - q)^limit the draw is
  /// certainly >= limit and the logarithm is skipped. This is the common case when walking a
  /// few sensors with small q (a cell of 9 sensors is all misses with probability 0.81).
  std::uint64_t drawUpTo(common::Stream& stream, std::uint64_t limit) const;

 private:
  std::uint64_t fromUniform(double u) const;
  double q_ = 0.0;
  double log_miss_ = 0.0;
  /// (1 - q)^n, shrunk by a relative 1e-12 so that the shortcut never disagrees with the
  /// logarithm by rounding.
  std::vector<double> all_miss_;
};

}  // namespace wsn::node

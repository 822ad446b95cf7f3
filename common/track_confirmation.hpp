// How much evidence a track needs before it is reported, and how many misses before it is given
// up, from the clutter and detection statistics of a scenario (common/observation_statistics.hpp).
// Engines use these to derive their confirmation and deletion parameters.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace wsn::common {

/// Expected number of chains of n false reports per tick that look like a new track: a false
/// report starts one (lambda_f * area per tick), a second lies in the first gate (area
/// first_gate), each later one in the tracking gate (area later_gate). Clutter is Poisson and
/// independent between ticks, so each link is a gate's expected count.
inline double falseTrackRate(std::int32_t n, double lambda_f, double area, double first_gate, double later_gate) {
  double rate = lambda_f * area;
  if (n >= 2) rate *= lambda_f * first_gate;
  for (std::int32_t k = 3; k <= n; ++k) rate *= lambda_f * later_gate;
  return rate;
}

/// Ticks a target waits, after its first report, for n reports in all when each tick brings one
/// with probability pd (negative binomial mean: (n - 1) / pd).
inline double ticksForReports(std::int32_t n, double pd) { return (n - 1) / std::max(pd, 1e-3); }

/// Ticks a target waits, after its first report, for n reports on consecutive ticks when each
/// tick brings one with probability p: the mean number of trials to a run of n successes,
/// (1 - p^n) / ((1 - p) p^n), less the first.
inline double ticksForConsecutiveReports(std::int32_t n, double p) {
  p = std::clamp(p, 1e-3, 1.0);
  if (p >= 1.0) return n - 1.0;
  const double pn = std::pow(p, n);
  return (1.0 - pn) / ((1.0 - p) * pn) - 1.0;
}

/// The evidence n in [min_n, max_n] that costs the fewest wrong track-ticks per tick: chains of
/// clutter confirmed at n (false_tracks(n) per tick, each reported for about false_life ticks)
/// against the ticks every true target waits before it is reported (wait(n) at births_per_tick).
/// Ties go to the smaller n. With no clutter this is min_n: a single report is decisive when
/// nothing else could have made it.
template <typename FalseTracks, typename Wait>
std::int32_t leastCostConfirmation(FalseTracks false_tracks, double false_life, double births_per_tick, Wait wait,
                                   std::int32_t min_n, std::int32_t max_n) {
  std::int32_t best = min_n;
  double best_cost = INFINITY;
  for (std::int32_t n = min_n; n <= max_n; ++n) {
    const double cost = false_tracks(n) * false_life + births_per_tick * wait(n);
    if (cost < best_cost) {
      best = n;
      best_cost = cost;
    }
  }
  return best;
}

/// The smallest k >= 1 with (1 - pd)^k <= tolerance: k consecutive misses of a live target are
/// that rare. Capped at max_k.
inline std::int32_t rareMissRun(double pd, double tolerance, std::int32_t max_k) {
  if (pd >= 1.0) return 1;
  if (pd <= 0.0) return max_k;
  const double k = std::ceil(std::log(tolerance) / std::log(1.0 - pd) - 1e-9);
  return static_cast<std::int32_t>(std::clamp(k, 1.0, static_cast<double>(max_k)));
}

/// How unlikely a run of misses must be, for a live target, before a track is given up (1 %): the
/// tolerance of every derived miss count (common::liveEdgeMissDerivation).
inline constexpr double kRareMissRun = 0.01;

/// The smallest k >= 1 such that a live target shows no report at any of the newest k ticks, as an
/// engine sees them when it decides at the newest tick, with probability <= tolerance:
/// prod_{j < k} (1 - pd_by_lag[j]), where pd_by_lag[j] is the probability that the report of the
/// tick j ticks back has arrived by then (sensed, and delivered with a delay <= j); past the last
/// lag, the last value. A report that is only late is then not taken for a miss. With every lag at
/// one pd this is rareMissRun(pd). Capped at max_k.
inline std::int32_t rareLiveEdgeMissRun(const std::vector<double>& pd_by_lag, double tolerance, std::int32_t max_k) {
  if (pd_by_lag.empty()) return max_k;
  double run = 1.0;
  for (std::int32_t k = 1; k <= max_k; ++k) {
    const std::size_t lag = std::min(static_cast<std::size_t>(k - 1), pd_by_lag.size() - 1);
    run *= 1.0 - std::clamp(pd_by_lag[lag], 0.0, 1.0);
    if (run <= tolerance * (1.0 + 1e-12)) return k;
  }
  return max_k;
}

/// Area of the chi-square gate g of a 2-D Gaussian innovation with per-axis variance s2:
/// pi g sqrt(det S) = pi g s2.
inline double gateArea(double gate_chi2, double s2) { return 3.14159265358979323846 * gate_chi2 * s2; }

/// True births per tick over `area`: at least one target per run, so that a scenario with no
/// births still weighs the wait of the targets it has.
inline double birthsPerTick(double birth_density, double area, std::int32_t run_ticks) {
  return std::max(birth_density * area, 1.0 / std::max(1, run_ticks));
}

/// The gates a new constant-velocity track's next reports fall in (Oh eq. 8, R = r^2 I).
struct NewTrackGates {
  double first = 0.0;  ///< the second report: a track born at rest, 2 r^2 + v^2 delta^2 per axis
  double later = 0.0;  ///< once two reports fix its velocity (predicted 2 z2 - z1: 5 r^2, plus r^2)
};
inline NewTrackGates newTrackGates(double gate_chi2, double measurement_sigma, double velocity_sigma,
                                   double process_noise_sigma, double delta) {
  const double r2 = measurement_sigma * measurement_sigma;
  const double q = process_noise_sigma * delta * delta / 2.0;  // a tick's acceleration noise in position
  return {gateArea(gate_chi2, 2.0 * r2 + velocity_sigma * velocity_sigma * delta * delta + q * q),
          gateArea(gate_chi2, 6.0 * r2 + q * q)};
}

}  // namespace wsn::common

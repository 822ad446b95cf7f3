// Scoring of a run against ground truth: Oh et al. §VII eq. (9) εK and eq. (10) εX, and OSPA
// (Schuhmacher, Vo & Vo, "A consistent metric for performance evaluation of multi-object
// filters", IEEE TSP 56(8), 2008).
//
// How the paper's definitions are read here (quotes from Oh et al. §VII):
//
// εK, eq. (9). "Let K*_t be the number of targets at time t and K_t be the estimated number of
//   targets at time t. We define εK as  εK = 1/(Σ K*_t) Σ_{t=1}^{T} |K_t − K*_t|."
//   - K*_t = number of truth targets alive at tick t; K_t = number of (global) tracks reported at
//     tick t. Both sums run over every tick given to add() (the run's ticks 1..T), the
//     normaliser Σ K*_t over the same ticks: one ratio over the whole run, not a mean of ratios.
//   - Undefined case: Σ K*_t = 0 (no target in the whole run). Then eps_k is reported as 0 and
//     eps_k_defined as false; sum_abs_k_error still shows any false tracks.
//
// εX, eq. (10). "The computation of εX is done when it makes sense. At any t, there can be at
//   most M_t = min(K_t, K*_t) common tracks. We find M_t matches between true tracks and
//   estimated tracks based on positions at t − 1, t, t + 1. For each match i, let x*_t(i) and
//   x_t(i) be the position of the true track and the estimated track at t, respectively. We
//   define εX as  εX² = 1/(Σ M_t) Σ_{t=1}^{T} Σ_{i=1}^{M_t} ‖x_t(i) − x*_t(i)‖²."
//   - "true track" = a truth target followed by its id, "estimated track" = a global track
//     followed by its track id; x is the position (x, y), velocities are not scored.
//   - At each tick exactly M_t = min(K_t, K*_t) pairs are formed (no gate: the paper has none),
//     by the minimum-total-cost assignment (common/assignment.hpp) with
//       cost(j, i) = mean over s ∈ {t − 1, t, t + 1} of ‖x_s(i) − x*_s(j)‖²,
//     the mean taken over those s at which both target j and track i exist (s = t always
//     qualifies; t − 1 is absent at the first tick, t + 1 at the last, and either is absent when
//     the target or the track was born or ended there). The mean, rather than the sum, keeps a
//     pair that coexists at fewer of the three ticks from being favoured for that alone. Squared
//     distances are used because eq. (10) scores squared errors.
//   - Only positions at t enter the error of a match ("x_t(i) ... at t"); t ± 1 only steer the
//     matching. εX is the square root of the pooled mean: one ratio over the run.
//   - "When it makes sense": ticks with M_t = 0 contribute nothing to either sum. Undefined case:
//     Σ M_t = 0 (never a target and a track at the same tick). Then eps_x is 0 and
//     eps_x_defined false.
//   - eps_x_gated: the same matches, but only those whose error at t is below eps_x_gate enter
//     either sum (a pair of an unrelated track and target 20–45 apart otherwise dominates εX);
//     eps_x_gated_defined is false when no match is that close.
//   - Because t + 1 is needed, matching is done in finish() over the stored ticks; a tick's
//     neighbours are the ticks numbered t − 1 and t + 1 if they were added.
//
// OSPA. For X = {x_1..x_m}, Y = {y_1..y_n} with m ≤ n (else swap), cut-off c > 0, order p ≥ 1,
//   d^(c)(x, y) = min(c, ‖x − y‖):
//     d_p^(c)(X, Y) = ( (1/n) ( min_π Σ_{i=1}^{m} d^(c)(x_i, y_π(i))^p + c^p (n − m) ) )^(1/p),
//   0 when both sets are empty (so c when exactly one is). Per tick on positions of truth vs
//   tracks; ospa_mean is the plain mean over the ticks added.
//
// Tracks with a non-finite field are ignored (counted in tracks_ignored_nonfinite).
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/geometry.hpp"
#include "common/messages.hpp"
#include "common/scenario_config.hpp"
#include "common/truth.hpp"

namespace wsn::aggregator {

/// The scores of a run; see the header comment for the definitions.
struct MetricsSummary {
  std::int64_t ticks_scored = 0;
  std::int32_t first_tick = 0;  ///< 0 when no tick was scored
  std::int32_t last_tick = 0;

  double eps_k = 0.0;  ///< Oh eq. (9)
  bool eps_k_defined = false;  ///< false when Σ K*_t = 0
  std::int64_t sum_k = 0;  ///< Σ K_t
  std::int64_t sum_k_true = 0;  ///< Σ K*_t
  std::int64_t sum_abs_k_error = 0;  ///< Σ |K_t − K*_t|
  double mean_k = 0.0;  ///< Σ K_t / ticks
  double mean_k_true = 0.0;  ///< Σ K*_t / ticks

  double eps_x = 0.0;  ///< Oh eq. (10)
  bool eps_x_defined = false;  ///< false when Σ M_t = 0
  std::int64_t sum_matches = 0;  ///< Σ M_t
  double sum_squared_position_error = 0.0;  ///< Σ_t Σ_i ‖x_t(i) − x*_t(i)‖²
  double eps_x_gate = 0.0;
  double eps_x_gated = 0.0;  ///< eq. (10) over the matches with error < eps_x_gate
  bool eps_x_gated_defined = false;  ///< false when no match is closer than the gate
  std::int64_t sum_matches_gated = 0;
  double sum_squared_position_error_gated = 0.0;

  double ospa_c = 0.0;
  double ospa_p = 0.0;
  double ospa_mean = 0.0;  ///< mean of ospa_per_tick (0 without ticks)
  std::vector<double> ospa_per_tick;  ///< first_tick..last_tick, in tick order

  std::int64_t track_ids = 0;  ///< distinct global track ids seen over the run
  std::int64_t tracks_ignored_nonfinite = 0;

  bool operator==(const MetricsSummary&) const = default;
};

/// What add() returns: the values of that tick and the running scores over the ticks added so
/// far (the live view; εX needs t + 1 and is only in finish()).
struct MetricsTick {
  std::int64_t k_true = 0;  ///< K*_t
  std::int64_t k = 0;  ///< K_t (finite tracks)
  double ospa = 0.0;  ///< OSPA_t
  double eps_k_running = 0.0;  ///< eq. (9) over the ticks added so far; 0 while Σ K*_t = 0
  double ospa_mean_running = 0.0;  ///< mean OSPA over the ticks added so far
};

/// OSPA distance between two finite point sets (Schuhmacher, Vo & Vo 2008, eq. (3)), cut-off
/// `c` > 0, order `p` >= 1. Both empty: 0; exactly one empty: c.
double ospaDistance(const std::vector<common::Vec2>& x, const std::vector<common::Vec2>& y, double c, double p);

/// Collects truth and global tracks tick by tick and scores the run at the end.
class MetricsAccumulator {
 public:
  /// Throws std::invalid_argument unless ospa_c > 0, ospa_p >= 1 and eps_x_gate > 0 (all finite).
  explicit MetricsAccumulator(const common::MetricsConfig& config);

  /// Records tick `tick`: the truth targets alive and the global tracks reported. Any order of
  /// either vector gives the same scores. Adding a tick twice throws std::invalid_argument.
  MetricsTick add(std::int32_t tick, const std::vector<common::TargetState>& truth,
           const std::vector<common::TrackEstimate>& tracks);

  /// Scores everything added so far (εX needs t + 1, so all of it is computed here).
  MetricsSummary finish() const;

 private:
  struct TickRecord {
    std::vector<common::TargetState> truth;  // sorted by id (then state)
    std::vector<common::TrackEstimate> tracks;  // finite only, sorted by id (then state)
    double ospa = 0.0;
  };

  common::MetricsConfig config_;
  std::map<std::int32_t, TickRecord> ticks_;
  std::set<common::TrackId> track_ids_;
  std::int64_t ignored_nonfinite_ = 0;
  // Running sums for MetricsTick; finish() recomputes everything from ticks_.
  std::int64_t running_abs_k_error_ = 0;
  std::int64_t running_k_true_ = 0;
  double running_ospa_ = 0.0;
};

}  // namespace wsn::aggregator

// GOSPA, the generalised optimal sub-pattern assignment metric with alpha = 2 (Rahmathullah,
// García-Fernández & Svensson, "Generalized optimal sub-pattern assignment metric", FUSION 2017),
// per tick on 2-D positions, split into localisation, missed-target and false-target parts.
//
// How the paper's definition is read here. For X = {x_1..x_m} (truth), Y = {y_1..y_n} (tracks),
// cut-off c > 0, order 1 <= p < inf, alpha = 2, d^(c)(x, y) = min(c, ‖x − y‖), the paper
// defines GOSPA as an optimum over permutations; for alpha = 2 it shows that this equals the
// optimum over assignments γ (sets of disjoint truth-track pairs):
//     d_p^(c,2)(X, Y)^p = min_γ ( Σ_{(i,j)∈γ} ‖x_i − y_j‖^p + (c^p / 2) (|X| − |γ| + |Y| − |γ|) ),
//   where only pairs with ‖x_i − y_j‖ < c may be in γ. Every unassigned truth is a missed
//   target, every unassigned track a false target, each costing c^p / 2.
//   - Computed as that partial assignment: each truth left out costs c^p (its own c^p/2 and
//     that of the track it leaves over), so pairs with d >= c are never needed and the problem
//     splits into clusters of nearby truths and tracks (common/assignment.hpp). A pair at
//     exactly d = c is counted as missed + false (a convention: either way costs c^p).
//   - The parts are in the units of d^p, so localisation + missed + false = distance^p: this is
//     the decomposition the paper gives for alpha = 2 (for p = 1 they add up to the distance).
//   - Both sets empty: 0. No normalisation by the set sizes (unlike OSPA): GOSPA grows with the
//     number of targets, which the paper intends.
#pragma once

#include <cstdint>
#include <vector>

#include "common/geometry.hpp"

namespace wsn::aggregator {

/// GOSPA at one tick; the three parts are in the units of distance^p and add up to it.
struct GospaResult {
  double distance = 0.0;  ///< d_p^(c,2)(X, Y)
  double localisation = 0.0;  ///< Σ ‖x − y‖^p over the assigned pairs (all with d < c)
  double missed = 0.0;  ///< (c^p / 2) · missed_targets
  double false_targets = 0.0;  ///< (c^p / 2) · false_tracks
  std::int64_t assigned = 0;  ///< |γ|
  std::int64_t missed_targets = 0;  ///< |X| − |γ|
  std::int64_t false_tracks = 0;  ///< |Y| − |γ|
};

/// GOSPA with alpha = 2 between truth positions `truth` and track positions `tracks`, cut-off
/// `c` > 0, order `p` >= 1 (both finite, else std::invalid_argument). Points must be finite.
GospaResult gospaDistance(const std::vector<common::Vec2>& truth, const std::vector<common::Vec2>& tracks, double c,
                          double p);

/// Plain means over a run's ticks of each field of GospaResult (the counts as reals); all zero
/// without ticks. The issue asks for GOSPA "per tick and averaged": this is the average.
struct GospaMean {
  std::int64_t ticks = 0;
  double distance = 0.0;
  double localisation = 0.0;
  double missed = 0.0;
  double false_targets = 0.0;
  double missed_targets = 0.0;
  double false_tracks = 0.0;
};

/// Means of `per_tick` (one entry per scored tick).
GospaMean meanGospa(const std::vector<GospaResult>& per_tick);

}  // namespace wsn::aggregator

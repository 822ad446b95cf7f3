// CLEAR-MOT scores of a run (Bernardin & Stiefelhagen, "Evaluating multiple object tracking
// performance: the CLEAR MOT metrics", EURASIP J. Image and Video Processing, 2008): MOTA, MOTP,
// identity switches (the paper's mismatches), fragmentations, misses and false positives.
//
// How the paper's mapping procedure is read here, tick by tick, with match threshold T:
//   1. Every correspondence (target o, track h) of the previous tick is kept if o and h both
//      still exist and ‖o − h‖ < T ("the mapping is still valid"): this keeps an identity
//      through a crossing even when the other track is momentarily closer.
//   2. The remaining targets and tracks are matched by the minimum-total-distance assignment
//      (common/assignment.hpp, Munkres-equivalent) over the pairs with ‖o − h‖ < T; pairs at
//      or beyond T are forbidden. The solver first maximises the number of matches, then
//      minimises the summed Euclidean distance.
//   3. Mismatch (identity switch): a target matched to a track other than the one it was last
//      matched to, at any earlier tick (so a target lost and re-found by another track also
//      counts: the paper counts a mismatch when a target's hypothesis changes, and a gap does
//      not reset which hypothesis it had; py-motmetrics reads it the same way).
//   4. Unmatched targets are misses m_t, unmatched tracks false positives fp_t; g_t is the
//      number of targets, c_t the matches and d_t^i the Euclidean distance of match i.
//   MOTA = 1 − Σ_t (m_t + fp_t + mme_t) / Σ_t g_t; undefined when Σ g_t = 0, then
//          reported as 0 with mota_defined = false.
//   MOTP = Σ_{i,t} d_t^i / Σ_t c_t, the distance itself, not its square; undefined
//          when no match was made, then 0 with motp_defined = false.
//
// Fragmentation is not defined in the paper (it comes from the later MOT literature); here it
// is the number of times a target's matched trajectory is interrupted and resumed: over the
// ticks at which the target exists, each maximal run of unmatched ticks that has a matched tick
// both before and after it counts once (matched → unmatched … → matched). A target that is
// never re-found after a gap, or is missed only at its start, adds no fragmentation; a resumed
// match with a different track counts as both a fragmentation and an identity switch.
//
// Ticks must be added in increasing order; tracks with a non-finite position are ignored
// (counted in tracks_ignored_nonfinite). Track ids are assumed unique within a tick.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "common/messages.hpp"
#include "common/truth.hpp"

namespace wsn::aggregator {

/// CLEAR-MOT counts and scores; see the header comment for the definitions.
struct ClearMotSummary {
  std::int64_t ticks = 0;
  std::int64_t ground_truth = 0;  ///< Σ g_t
  std::int64_t matches = 0;  ///< Σ c_t
  std::int64_t misses = 0;  ///< Σ m_t
  std::int64_t false_positives = 0;  ///< Σ fp_t
  std::int64_t id_switches = 0;  ///< Σ mme_t
  std::int64_t fragmentations = 0;
  double sum_distance = 0.0;  ///< Σ d_t^i over matches (metres)
  double mota = 0.0;
  bool mota_defined = false;  ///< false when Σ g_t = 0
  double motp = 0.0;  ///< metres
  bool motp_defined = false;  ///< false when Σ c_t = 0
  std::int64_t tracks_ignored_nonfinite = 0;
};

/// One correspondence of a tick's CLEAR-MOT mapping.
struct ClearMotMatch {
  common::TargetId target = 0;
  common::TrackId track = 0;
  double distance = 0.0;  ///< metres
};

/// What one tick's mapping decided, for scores that attribute its events to places or times
/// (boundary.hpp) without matching a second time.
struct ClearMotTick {
  std::vector<ClearMotMatch> matches;  ///< in the order of the truth given
  std::vector<common::TargetId> misses;  ///< unmatched targets
  std::vector<common::TrackEstimate> false_positives;  ///< unmatched finite tracks, in input order
  std::vector<common::TargetId> id_switches;  ///< targets counted as a mismatch at this tick
  std::vector<common::TargetId> fragmentations;  ///< targets whose match resumed after a gap here
};

/// Runs the CLEAR-MOT matching tick by tick and accumulates the counts.
class ClearMotAccumulator {
 public:
  /// `match_threshold` is T in metres: a target and a track can correspond only when their
  /// distance is < T. Throws std::invalid_argument unless it is finite and > 0.
  explicit ClearMotAccumulator(double match_threshold);

  /// Scores tick `tick` (strictly greater than the previous tick added, else
  /// std::invalid_argument). The order of either vector does not matter. Returns the tick's
  /// mapping and events; the counts are accumulated either way.
  ClearMotTick add(std::int32_t tick, const std::vector<common::TargetState>& truth,
           const std::vector<common::TrackEstimate>& tracks);

  /// The scores of every tick added so far.
  ClearMotSummary summary() const;

 private:
  /// What is remembered about a target between ticks.
  struct TargetHistory {
    bool has_last_track = false;  // matched at some earlier tick
    common::TrackId last_track = 0;  // the track of its latest match
    bool in_gap = false;  // unmatched since its latest match
  };

  double threshold_;
  bool any_tick_ = false;
  std::int32_t last_tick_ = 0;
  std::map<common::TargetId, common::TrackId> previous_;  // M_{t-1}
  std::map<common::TargetId, TargetHistory> history_;
  ClearMotSummary sums_;
};

}  // namespace wsn::aggregator

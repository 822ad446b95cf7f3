// Per-target track quality of a run: root square error RSE and track length ratio TLR
// (seeds/003, §V "Performance evaluation") and the mean track position error ⟨dx⟩ (An et al.).
//
// How the papers are read here:
//
// Association (003 §V): "an important step is to decide at each time which track to compare
//   with which target ... The assignment is required to be unique, i.e. at most one track can be
//   associated with one target at any time, and at most one target can be associated with one
//   track. To solve this assignment, Munkres algorithm has been used. The tracks not associated
//   or correlated to a target despite the assignment are considered as false tracks."
//   - At every tick independently, the minimum-total-distance assignment (common/assignment.hpp,
//     equivalent to Munkres) between the targets alive and the tracks, on the Euclidean
//     position distance. The paper gives no gate, but without one a track on the far side of
//     the field would be "associated" to a target it has nothing to do with, so pairs farther
//     apart than `association_gate` (metres, may be +inf for none) are forbidden. Unassociated
//     tracks count as false-track ticks.
//
// RSE (003 §V): "The root square error is the most well-known MOP. It provides an information on
//   the track precision in location and velocity." No formula is given; read as the root mean
//   square error over the ticks at which the target is associated, separately for position and
//   velocity (per target, the way the paper's Table II lists it):
//     RSE_pos(j) = sqrt( (1/A_j) Σ_{t: j associated} ‖x̂_t − x*_t(j)‖² ), likewise RSE_vel on (vx, vy).
//
// TLR (003 §V): "a ratio between the track length associated to a target with the length of the
//   target trajectory. It informs on the track continuity performances." Lengths are read as
//   durations: TLR(j) = A_j / L_j, with A_j the number of ticks target j is associated with some
//   track (any track: continuity, not identity) and L_j the number of ticks it is alive. 1 is a
//   target tracked all its life.
//   The paper's words ("associated track length / trajectory length") are also read literally,
//   as path lengths: TLR_len(j) = P^A_j / P_j, with P_j = Σ ‖x*_t(j) − x*_{t−1}(j)‖ over the pairs
//   of consecutive ticks (consecutive add() calls) at which j is alive, and P^A_j the same sum over
//   the pairs whose later tick t has j associated. A tick's segment is the one that ends at it.
//   The two differ when the target's speed varies: ticks of a slow or stopped target weigh as much
//   as fast ones in TLR but little or nothing in TLR_len. A target that never moves (P_j = 0,
//   including one alive a single tick) has no trajectory length to divide by: its TLR_len is
//   defined as its duration TLR.
//
// ⟨dx⟩ (An et al., seeds/000 §5.2 and seeds/002): "the averaged position track error, ⟨dx⟩",
//   given per target and per run without a formula. Read as the mean Euclidean position error
//   (not squared) of the target's associated track over the ticks it is associated:
//     ⟨dx⟩(j) = (1/A_j) Σ_{t: j associated} ‖x̂_t − x*_t(j)‖.
//
// A target never associated (A_j = 0) has RSE and ⟨dx⟩ reported as 0 with `errors_defined`
// false, and TLR 0. Tracks with a non-finite field are ignored (tracks_ignored_nonfinite).
//
// Run means (a one-line summary for sweeps; the papers tabulate per target): RSE and ⟨dx⟩ are
// averaged over the targets with errors_defined, each target weighing the same however long it
// lived (so a short-lived badly tracked target is not drowned by long easy ones); TLR over every
// target, since a never-tracked target is exactly what TLR should penalise.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "common/messages.hpp"
#include "common/truth.hpp"

namespace wsn::aggregator {

/// The quality of one target's tracking over the run.
struct TargetQuality {
  common::TargetId id = 0;
  std::int64_t ticks_alive = 0;  ///< L_j
  std::int64_t ticks_associated = 0;  ///< A_j
  bool errors_defined = false;  ///< false when A_j = 0
  double rse_position = 0.0;  ///< metres
  double rse_velocity = 0.0;  ///< metres per second
  double tlr = 0.0;  ///< A_j / L_j
  double path_length = 0.0;  ///< P_j, metres
  double path_length_associated = 0.0;  ///< P^A_j, metres
  double tlr_length = 0.0;  ///< P^A_j / P_j, or tlr when P_j = 0
  double mean_position_error = 0.0;  ///< ⟨dx⟩, metres
};

/// Per-target quality of a run, targets in increasing id order.
struct TrackQualitySummary {
  std::vector<TargetQuality> targets;
  bool means_defined = false;  ///< false when no target was ever associated
  double mean_rse_position = 0.0;  ///< over targets with errors_defined
  double mean_rse_velocity = 0.0;
  double mean_position_error = 0.0;
  double mean_tlr = 0.0;  ///< over every target; 0 without targets
  double mean_tlr_length = 0.0;  ///< likewise
  std::int64_t false_track_ticks = 0;  ///< track-ticks left unassociated
  std::int64_t tracks_ignored_nonfinite = 0;
};

/// The paper's unique assignment of one tick: for each target of `truth`, the index of its track in
/// `tracks` (finite ones), or -1; pairs farther apart than `gate` metres are never made.
std::vector<int> associateTargetsWithTracks(const std::vector<common::TargetState>& truth,
                                                     const std::vector<common::TrackEstimate>& tracks, double gate);

/// Associates tracks to targets tick by tick and accumulates the per-target errors.
class TrackQualityAccumulator {
 public:
  /// `association_gate` in metres: pairs farther apart are never associated. Must be > 0 (it
  /// may be +infinity), else std::invalid_argument.
  explicit TrackQualityAccumulator(double association_gate);

  /// Scores one tick: the targets alive and the tracks reported. Ticks must come in time order
  /// (as RunScorer guarantees): the path-length TLR sums the target's moves between consecutive
  /// calls; every other score is independent of the order.
  void add(const std::vector<common::TargetState>& truth, const std::vector<common::TrackEstimate>& tracks);

  /// The per-target scores of everything added so far.
  TrackQualitySummary summary() const;

 private:
  struct Sums {
    std::int64_t alive = 0;
    std::int64_t associated = 0;
    double squared_position = 0.0;
    double squared_velocity = 0.0;
    double position = 0.0;
    double path = 0.0;
    double path_associated = 0.0;
    /// The add() call (0, 1, ...) at which the target was last alive; -2 before its first, so that
    /// its first tick (even call 0) ends no segment.
    std::int64_t last_call = -2;
    double last_x = 0.0;
    double last_y = 0.0;
  };

  double gate_;
  std::map<common::TargetId, Sums> sums_;
  std::int64_t false_track_ticks_ = 0;
  std::int64_t ignored_nonfinite_ = 0;
  std::int64_t calls_ = 0;  ///< add() calls so far
};

}  // namespace wsn::aggregator

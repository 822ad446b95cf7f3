// What the online MCMCDA engine keeps between ticks: its tracks, each an anchor that summarises the
// committed past plus its observations in the window, and one tick's association problem with the
// map from the problem's elements back to those tracks and their reports.
#pragma once

#include <compare>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/track_id.hpp"
#include "supernode/mcmcda/problem.hpp"

namespace wsn::supernode::mcmcda {

/// An observation's identity across windows (a late arrival shifts slot indices, not this).
struct ObservationKey {
  std::int32_t tick = 0;
  common::SensorId sensor = 0;
  double x = 0.0;
  double y = 0.0;
  auto operator<=>(const ObservationKey&) const = default;
};

/// A track as the engine keeps it between ticks. Invariant: a track without observations in the
/// window has an anchor.
struct LiveTrack {
  common::TrackId id = 0;
  std::optional<ProblemObservation> anchor;  ///< the track's past, summarised
  std::int32_t anchor_misses = 0;            ///< ticks the target was unseen before a handed-over anchor
  std::vector<ObservationKey> observations;  ///< in the window, tick order
  std::vector<TrackState> states;            ///< filtered state at each of them
  std::int32_t past_observations = 0;        ///< before the window (and at the sender, if handed over)

  /// Tick at which the target was last observed.
  std::int32_t lastSeenTick() const {
    return observations.empty() ? anchor.value().tick - anchor_misses : observations.back().tick;
  }
  const TrackState& lastState() const { return states.empty() ? anchor.value().prior : states.back(); }
  std::int32_t totalObservations() const { return past_observations + static_cast<std::int32_t>(observations.size()); }
  /// A track of one report in the window and no past (confirmation at one report): ω̂ cannot hold
  /// it, since a track of eq. (3) has two elements at least.
  bool isOneReport() const { return !anchor && past_observations == 0 && observations.size() == 1; }
  /// A report in a window starting at `oldest` could still continue the track: one generated up to
  /// d-bar (`max_gap`) ticks after the last may arrive late, as long as its slot is in the window.
  bool canContinue(std::int32_t oldest, std::int32_t max_gap) const { return lastSeenTick() + max_gap >= oldest; }
};

/// One tick's association problem and what maps its elements back to tracks and reports.
struct WindowProblem {
  Problem problem;
  std::vector<ObservationKey> keys;       ///< per element (meaningless for anchors)
  std::vector<std::int32_t> anchor_of;    ///< per element: index into the tracks of its anchor's track, or -1
  std::vector<std::int32_t> anchor_index; ///< per track: its anchor's element, or -1
};

}  // namespace wsn::supernode::mcmcda

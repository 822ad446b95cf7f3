// The sliding-window MCMCDA supernode engine ("mcmcda", Oh et al. §VI): each tick it rebuilds the
// association problem of the window, starts the chain from the previous best partition plus
// handed-over tracks and a greedy guess for the newest tick, runs nmc iterations and keeps ω̂.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "supernode/engine.hpp"
#include "supernode/mcmcda/live_track.hpp"
#include "supernode/mcmcda/mcmcda_params.hpp"
#include "supernode/mcmcda/problem.hpp"
#include "supernode/mcmcda/sampler.hpp"
#include "supernode/mcmcda/start_state.hpp"

namespace wsn::supernode::mcmcda {

/// The engine's registration: name "mcmcda", parameters with defaults and ranges, factory.
EngineSpec engineSpec();

/// Online MCMCDA. Association is revised inside the window only: when an observation leaves the
/// window, its track's filtered state there becomes the track's *anchor* (Problem's prior element),
/// so the chain continues the track under its id without re-deciding the past. With confirmation
/// at one report a track of one report is one too: it lives on while eq. (3) prefers a target to a
/// false alarm for its report, and is anchored when its report leaves, so a target seen once in a
/// while under heavy loss keeps its track from window to window. Output is the filtered (not
/// smoothed) state of each confirmed track, predicted to the newest tick, for every track that may
/// still continue (a report of the window could still follow its last observation within d-bar
/// ticks) and whose target is more likely there than gone (probablyAlive: pd of eq. (3) shared out
/// over the report ages by the delays learnt from every delivered report, and over the field by
/// where its sensors see, when the sensor model says); the estimate for an earlier tick of the
/// window is available through tracksAt().
class McmcdaEngine final : public Engine {
 public:
  explicit McmcdaEngine(const EngineContext& context);
  /// From its own configuration: resolved parameters (with the motion model), the region, the
  /// run's seed, the key of its random stream (a supernode's index) and the id space its new
  /// track ids come from.
  McmcdaEngine(const McmcdaParams& params, const common::Rect& region, std::uint64_t seed, std::uint32_t stream_key,
               common::track_id::Space ids);

  void adopt(const common::TrackHandoff& handoff) override;
  void step(const ObservationWindow& window) override;
  std::vector<common::TrackEstimate> confirmedTracks() const override;
  std::vector<TrackPrediction> predictions() const override;
  common::TrackHandoff release(common::TrackId track, std::uint32_t to_supernode) override;

  /// Confirmed tracks of ω̂ that span `tick` (first element <= tick <= last observation), with the
  /// filtered state at their last element at or before `tick`, predicted to `tick`. tick = newest
  /// - L is the fixed-lag estimate with lag L (its association has had L more ticks of evidence).
  std::vector<common::TrackEstimate> tracksAt(std::int32_t tick) const;
  /// tracksAt(tick) smoothed: each track's state at `tick` given all of its observations in the
  /// window, before and after (Rauch-Tung-Striebel over eq. (8)); the settled stream.
  std::optional<std::vector<common::TrackEstimate>> revisedTracks(std::int32_t tick) const override;

  /// An observation's identity across windows (live_track.hpp).
  using ObservationKey = mcmcda::ObservationKey;

  /// A live track of ω̂ (or one kept for a late continuation) with what the reporting rule of
  /// confirmedTracks() looks at, for callers that add evidence of their own (the aggregator).
  struct LiveTrackView {
    common::TrackEstimate now;  ///< filtered state at the last observation, predicted to the newest tick
    std::vector<ObservationKey> observations;  ///< in the window, tick order
    bool confirmed = false;       ///< holds confirm_observations observations in all
    bool probably_alive = false;  ///< see probablyAlive()
    bool in_region = false;       ///< `now` lies in the surveillance region
  };
  /// Every track that may still be continued, sorted by id. confirmedTracks() is the `now` of
  /// those that are confirmed, probably alive and in the region.
  std::vector<LiveTrackView> liveTracks() const;

  /// Chooses the id of a track that continues no previous track, from its observations in the
  /// window; 0 (or an id in use) means "mint one". The default mints every id.
  using IdProposer = mcmcda::IdProposer;
  void setIdProposer(IdProposer proposer) { propose_id_ = std::move(proposer); }

  /// Names a group of observations known to belong together (the aggregator: elements of one
  /// supernode track); 0 means none. The start state appends a new observation to the track that
  /// holds the latest earlier member of its group, when it can follow that track's last element
  /// (ω_init "from the tracks themselves", Oh §VI). The default knows no groups.
  using GroupOf = mcmcda::GroupOf;
  void setGroupOf(GroupOf group_of) { group_of_ = std::move(group_of); }

  /// A fresh id of the engine's id space, never given to one of its tracks (the aggregator reports
  /// a supernode track under one when its own id is taken).
  common::TrackId mintId();

  /// Statistics of the last step, for benchmarks and logs.
  struct StepStats {
    std::int32_t observations = 0;  ///< problem size, anchors included
    std::int32_t tracks = 0;        ///< tracks in ω̂
    double log_posterior = 0.0;     ///< of ω̂
    MoveStats moves;                ///< of the last chain
  };
  const StepStats& lastStep() const { return last_step_; }
  /// Handoffs ignored because their state or covariance was not finite.
  std::uint64_t rejectedHandoffs() const { return rejected_handoffs_; }

 private:
  /// Step 1: observations older than the window become anchors; tracks that cannot go on end.
  void commitLeavingObservations(std::int32_t oldest);
  /// Algorithm 1 on the window (merged when merge_radius > 0), at its newest tick: steps 2 to 5,
  /// with the start state (step 3) and the new track set (step 5) of start_state.hpp.
  void associate(const ObservationWindow& window, std::int32_t newest);
  /// Step 2: anchors and the window's reports as a Problem.
  WindowProblem buildProblem(const ObservationWindow& window) const;

  /// A report in a window starting at `oldest` could still continue the track.
  bool canContinue(const LiveTrack& track, std::int32_t oldest) const {
    return track.canContinue(oldest, params_.model.max_gap);
  }
  /// The track may still be continued in the current window.
  bool isLive(const LiveTrack& track) const { return canContinue(track, oldest_tick_); }
  /// The track's target is more likely there at `tick` (at most the newest) than gone, given the
  /// ticks since its last observation, the detection probability and the delays learnt so far.
  bool probablyAlive(const LiveTrack& track, std::int32_t tick) const;
  /// The chance that the track's target, last seen at its last observation, gives no report in the
  /// window after it, ending at some tick or not; `there_at_tick` the part of it in which it is
  /// there at `tick`.
  double unseenLikelihood(const LiveTrack& track, std::int32_t tick, double& there_at_tick) const;
  /// Eq. (3) prefers a target to a false alarm for the report of a one-report track, given its silence since.
  bool loneTargetLikely(const LiveTrack& track) const;
  /// P(a live target's report of the tick `age` ticks back is in the window): pd shared out by
  /// the delays learnt so far (arrived_by_age_).
  double arrivedBy(std::int32_t age) const {
    return arrived_by_age_[std::min(static_cast<std::size_t>(std::max(age, 0)), arrived_by_age_.size() - 1)];
  }
  /// The same for a target at `where`: shared out over the field too, where the sensors' coverage
  /// is known (detection_share_), at most 1; without coverage, arrivedBy(age) exactly.
  double arrivedBy(std::int32_t age, common::Vec2 where) const {
    return std::min(1.0, arrivedBy(age) * detection_share_.at(where));
  }
  /// Updates the delay histogram from the slot that just became final, and arrived_by_age_ with it.
  void learnDelays(const ObservationWindow& window);

  std::uint32_t stream_key_;
  common::track_id::Space ids_;
  std::uint64_t seed_;
  common::Rect region_;  ///< the surveillance region
  /// Where the field's sensors see well and where not (field sensors); uniform for a grid of
  /// identical sensors, and for the aggregator's engine.
  common::DetectionShare detection_share_;
  McmcdaParams params_;
  MotionModel motion_;
  std::int32_t newest_tick_ = 0;
  std::int32_t oldest_tick_ = 0;  ///< of the window last stepped
  std::vector<LiveTrack> tracks_;  ///< sorted by id
  std::vector<ObservationKey> released_;  ///< observations of tracks handed to a neighbour
  std::uint64_t next_serial_ = 1;
  IdProposer propose_id_;
  GroupOf group_of_;
  // What the engine learns about delivery: the delays of the reports in settled slots, and from
  // them pd_a by age (the last entry holds for every later age).
  std::int32_t settled_tick_ = 0;
  std::vector<double> delay_counts_;
  double delay_total_ = 0.0;
  std::vector<double> arrived_by_age_;
  std::uint64_t rejected_handoffs_ = 0;
  StepStats last_step_;
};

}  // namespace wsn::supernode::mcmcda

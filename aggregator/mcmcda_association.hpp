// Track-level MCMCDA at the aggregator (Oh et al. §VI): the supernodes' established tracks become
// the observation set Yc of a sliding-window MCMCDA run by the same library the supernodes use.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "aggregator/association.hpp"
#include "supernode/mcmcda/mcmcda_engine.hpp"
#include "supernode/observation_window.hpp"

namespace wsn::aggregator {

/// The registration: name "mcmcda", parameters window_size plus the MCMCDA model's, with
/// defaults for track-level data.
AssociationSpec mcmcdaAssociationSpec();

/// The ids under which the aggregator reports its global tracks, tick by tick. A track the output
/// already had keeps its id. A chain that re-forms a target's track under a new engine id for a
/// tick (it splits off the newest elements and merges them back when more evidence arrives) would
/// make the target change id twice, so a track new to the output is reported under the id its
/// supernode tracks were reported under at the previous tick, when that id is free now, and keeps
/// that alias while its engine track lives.
class ReportedIds {
 public:
  /// A global track to report: the engine's id and the supernode tracks of its elements.
  struct Global {
    common::TrackId engine_id = 0;
    std::vector<common::TrackId> sources;
  };
  struct Assignment {
    std::vector<common::TrackId> global;  ///< per Global, in input order
    std::vector<common::TrackId> passed;  ///< per passed-through supernode track: its id, or 0 when taken
  };
  /// One tick: `globals` sorted by engine id, `passed` the supernode tracks reported as they are,
  /// `live_engine_ids` every track the engine still keeps (aliases of the others are forgotten).
  Assignment assign(const std::vector<Global>& globals, const std::vector<common::TrackId>& passed,
                    const std::set<common::TrackId>& live_engine_ids);

 private:
  std::map<common::TrackId, common::TrackId> alias_;  // engine id -> the id it is reported under
  std::map<common::TrackId, common::TrackId> owner_;  // supernode track -> global id it was reported in
  std::set<common::TrackId> previous_;                // ids reported at the previous tick
};

/// The MCMCDA engine's defaults for track-level association (why each differs: the .cpp).
supernode::mcmcda::McmcdaParams trackLevelEngineDefaults();

/// The "mcmcda" association's parameters: its own window and every MCMCDA engine parameter.
struct McmcdaAssociationParams {
  std::int32_t window_size = 10;  ///< ws of the aggregator's window (ticks)
  supernode::mcmcda::McmcdaParams engine = trackLevelEngineDefaults();
};

/// aggregator.params of "mcmcda", described once.
const common::config::FieldTable<McmcdaAssociationParams>& mcmcdaAssociationParamTable();

/// Yc and ω_init as Oh §VI forms them, online:
///  - An element of Yc is one supernode track at a tick where it was *observed*: a supernode's
///    estimate carries the tick of its latest observation (last_seen_tick), and since its state is
///    the filtered state there predicted forward, x − vx·(t − last_seen_tick) recovers the filtered
///    position at that tick exactly. Coasted ticks are not elements: a prediction is not evidence,
///    and a coasting duplicate would look like a perfect straight-line track.
///  - Each (track, tick) enters once, at the aggregator tick it is first reported. An
///    element for an earlier tick arrives late and goes into its own slot, exactly like a delayed
///    report at a supernode; one older than the window is dropped (counted).
///  - ω_init from the tracks themselves: the chain starts from the previous ω̂ with each new element
///    appended to the global track that holds the latest element of its supernode track (the
///    engine's groups), then the engine's greedy join; the chain re-decides what crosses
///    supernodes: the fragments of one target that a boundary split.
///  - One target produces at most one fused report per tick and each report reaches one supernode,
///    so two elements of one target at one tick are rare — §III-B's constraint (one observation per
///    track per tick) holds for Yc as it does for the supernodes' input.
///  - The window, the anchors, the chain and the identities are the supernode engine's
///    (supernode/mcmcda), run on the whole region, its random stream keyed one past the last real
///    supernode and its new ids the aggregator's "gN" (as the gated merge's). A global track that continues no
///    previous one takes the id of the supernode track of its first element, so a target keeps
///    the id its first supernode gave it.
///  - Reporting. A confirmed global track in the region is reported while its target is probably
///    alive by the engine's rule, or while a supernode still reports one of its member tracks: a
///    supernode sees the raw reports and their delays, the aggregator only the outcome, so the
///    supernode's judgement that a target is still there outranks the aggregator's. A supernode
///    track that no reported global track holds (its first tick: one element cannot form an MCMCDA
///    track) is passed through under its own id, which the global track it grows into then takes.
///    The reported state is the aggregator's filter over the elements, predicted to the tick; a
///    passed-through track's is the supernode's.
class McmcdaAssociator final : public TrackAssociator {
 public:
  /// `context.params` must be resolved against mcmcdaAssociationSpec(); the motion model is the
  /// scenario's dynamics.
  explicit McmcdaAssociator(const AssociationContext& context);
  /// From its own parameters: the run's seed and the key of its random stream (the scenario's
  /// supernode count, one past the last supernode's). New global ids are the aggregator's "gN",
  /// like the gated merge's.
  McmcdaAssociator(const McmcdaAssociationParams& params, const common::Rect& region, std::uint64_t seed,
                   std::uint32_t stream_key);

  std::vector<common::TrackEstimate> associate(std::int32_t tick, const std::vector<SupernodeTracks>& inputs) override;
  std::uint64_t droppedNonFinite() const override { return dropped_non_finite_; }

  /// Elements that arrived after their tick had left the window.
  std::uint64_t droppedStale() const { return window_.droppedStale(); }
  const supernode::mcmcda::McmcdaEngine& engine() const { return *engine_; }

 private:
  // Track ids are unique across supernodes and a handed-over track keeps its id, so (track, tick)
  // names one observation even when the sender and the receiver both report the track.
  using ElementKey = std::pair<common::TrackId, std::int32_t>;

  std::unique_ptr<supernode::mcmcda::McmcdaEngine> engine_;
  supernode::ObservationWindow window_;
  std::map<ElementKey, common::SensorId> seen_;  // element -> its pseudo-sensor id
  std::map<common::SensorId, common::TrackId> source_;  // pseudo-sensor id -> supernode track
  ReportedIds reported_ids_;
  common::SensorId next_element_ = 0;
  std::uint64_t dropped_non_finite_ = 0;
};

}  // namespace wsn::aggregator

// Track-level MCMCDA at the aggregator (Oh et al. §VI): the supernodes' established tracks become
// the observation set Yc of a sliding-window MCMCDA run by the same library the supernodes use.
#pragma once

#include <cstdint>
#include <functional>
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

/// The ids under which the aggregator reports its global tracks, tick by tick. Identity follows
/// the supernodes' tracks, whose identities are decided on the raw reports: a global track is
/// reported under the id its supernode tracks were reported under at the previous tick, when that
/// is free; else, when the engine continues a track reported at the previous tick (a target's new
/// supernode track joins its global track), under that track's id; else under its engine id, or a
/// fresh one. A chain that re-forms a target's track under a new engine id (it splits off the
/// newest elements and merges them back when more evidence arrives) therefore changes no id.
class ReportedIds {
 public:
  /// A global track to report: the engine's id and the supernode tracks it holds now.
  struct Global {
    common::TrackId engine_id = 0;
    std::vector<common::TrackId> sources;
  };
  struct Assignment {
    std::vector<common::TrackId> global;  ///< per Global, in input order
    std::vector<common::TrackId> passed;  ///< per passed-through supernode track
  };
  /// One tick: `globals` sorted by engine id, `passed` the supernode tracks reported as they are,
  /// `live_engine_ids` every track the engine still keeps (aliases of the others are forgotten),
  /// `mint` a fresh id of the aggregator's space.
  Assignment assign(const std::vector<Global>& globals, const std::vector<common::TrackId>& passed,
                    const std::set<common::TrackId>& live_engine_ids, const std::function<common::TrackId()>& mint);

 private:
  std::map<common::TrackId, common::TrackId> alias_;  // engine id -> the id it is reported under
  std::map<common::TrackId, common::TrackId> owner_;  // supernode track -> global id it was reported in
  std::set<common::TrackId> previous_;                // ids reported at the previous tick
};

/// The MCMCDA engine's defaults for track-level association (why each differs: the .cpp).
supernode::mcmcda::McmcdaParams trackLevelEngineDefaults();

/// How the track-level model follows the scenario: the supernode engine's derivations (Yc's
/// elements are observed, err, appear and end as the supernodes' reports do), less those that
/// describe raw reports only (confirm_observations, merge_radius).
std::map<std::string, common::ParamDerivation> trackLevelDerivations();

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
///    supernode and its new ids the aggregator's "gN" (as the gated merge's). The model's parameters
///    are the supernodes' (trackLevelDerivations). Ids follow the supernode tracks (ReportedIds).
///  - Which supernode tracks a global track holds now: each supernode track reported at this tick
///    belongs to the global track that holds its newest element, with the newest such element's
///    track and those whose estimates pass the track-to-track test against it (sameTarget); one
///    that fails is another target the chain linked over a long gap and is passed through.
///  - Reporting. A confirmed global track is reported while a supernode reports a track it holds
///    now, and ends when they end: a supernode sees the raw reports and their delays, the
///    aggregator only the outcome. Its estimate is fused from those supernode tracks as they
///    published them (aggregator/track_fusion.hpp): one passes through, several are combined by
///    covariance intersection; the chain's own filter over the elements, which would treat
///    already filtered states as raw reports, is not what the user sees. Every reported
///    supernode track is in the output: one that no reported global track holds (its first tick:
///    one element cannot form an MCMCDA track) is passed through, and ReportedIds names it.
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
  /// Yc's new elements of the tick's inputs, each (track, tick) once, into the window.
  void addElements(std::int32_t tick, const std::vector<SupernodeTracks>& inputs);

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

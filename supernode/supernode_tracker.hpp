// One supernode's tracking (Oh §VI): the sliding observation window, the configured engine, and
// the handoff of tracks whose predicted position enters another supernode's tracking group.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "common/messages.hpp"
#include "supernode/engine.hpp"
#include "supernode/observation_window.hpp"
#include "supernode/rehome.hpp"

namespace wsn::supernode {

/// Oh §V, g(): index of the supernode nearest to `position` (ties go to the lower index);
/// 0 when there are no supernodes.
std::uint32_t nearestSupernode(const std::vector<common::Vec2>& supernodes, common::Vec2 position);


/// What one supernode's tracker runs with, split off the scenario at the role edge.
struct SupernodeConfig {
  EngineContext engine;                  ///< its engine, with resolved parameters; engine.supernode is its index
  std::vector<common::Vec2> supernodes;  ///< every supernode: the tracking groups a track may enter
};

/// The config of supernode `index` of `resolved` (whose tracker.params are resolved, as the
/// launcher resolves them and the run directory's scenario.yaml writes them out).
SupernodeConfig supernodeConfig(const common::Scenario& resolved, std::uint32_t index);

/// Window + engine + handoff decision of one supernode; pure and deterministic.
class SupernodeTracker {
 public:
  /// The settled estimate of ticks first .. first + by_tick.size() - 1: each tick's tracks as the
  /// engine revised them when the tick left the window (its live ones when it does not revise).
  struct Settled {
    std::int32_t first = 1;
    std::vector<std::vector<common::TrackEstimate>> by_tick;
    std::int32_t last() const { return first + static_cast<std::int32_t>(by_tick.size()) - 1; }
    friend bool operator==(const Settled&, const Settled&) = default;
  };

  /// What one tick produced.
  struct TickOutput {
    std::int32_t tick = 0;
    std::vector<common::TrackEstimate> tracks;      ///< confirmed tracks, sorted by id
    /// The tick that left the window with this one (tick - ws + 1), once there is one.
    Settled settled;
    std::vector<common::TrackHandoff> handoffs;     ///< released tracks, sorted by id
    std::uint32_t observations_in_window = 0;
    std::uint64_t observations_dropped_stale = 0;  ///< cumulative
    friend bool operator==(const TickOutput&, const TickOutput&) = default;
  };

  /// Throws std::invalid_argument when config.engine.supernode names no supernode of
  /// config.supernodes (index 0 is the single tracking group when there are none), and what
  /// makeEngine throws for an unknown engine or unresolved parameters.
  explicit SupernodeTracker(SupernodeConfig config);
  /// A tracker that starts afresh at `first_tick` (a supernode back after a pause, or restarted): it settles
  /// ticks from first_tick on, and its first step must be at first_tick.
  SupernodeTracker(SupernodeConfig config, std::int32_t first_tick);

  /// Which supernodes own a tracking group at the next tick (faults); a track predicted into
  /// the group of a dead one goes to the nearest live one. All of them until set.
  void setLiveSupernodes(std::vector<bool> live) { live_ = std::move(live); }
  /// The supernodes whose groups border this one's, ascending: the only receivers of its handoffs.
  const std::vector<std::uint32_t>& neighbours() const { return neighbours_; }

  /// Processes tick `tick`: slides the window, files the delivered observations into their slots,
  /// adopts the incoming handoffs, steps the engine and releases the tracks predicted to enter
  /// another supernode's Voronoi cell. Handoffs addressed to another supernode are ignored; an
  /// observation of a measurement kind the engine does not accept throws (requireAccepted).
  TickOutput step(std::int32_t tick, std::span<const common::Observation> delivered,
                  std::span<const common::TrackHandoff> incoming);

  /// Settles every tick not settled yet (the last ws - 1 of a run, after its last step).
  Settled settleRemaining();

  std::uint32_t supernodeIndex() const { return index_; }
  /// Whether the engine holds a live track of this id (tentative ones included).
  bool tracks(common::TrackId track) const;
  const ObservationWindow& window() const { return window_; }
  const Engine& engine() const { return *engine_; }
  /// Incoming handoffs that named another supernode (dropped, counted).
  std::uint64_t misaddressedHandoffs() const { return misaddressed_handoffs_; }

 private:
  std::vector<common::Vec2> supernodes_;
  /// The supernodes whose groups border this one's (common/voronoi.hpp): the only ones a handoff
  /// goes to, since handoffs travel between neighbouring groups only.
  std::vector<std::uint32_t> neighbours_;
  std::vector<bool> live_;  ///< empty: every supernode
  /// Oh §VI's receiver of a track predicted at `position`: the nearest live supernode among this
  /// one and its neighbours.
  std::uint32_t ownerOf(common::Vec2 position) const;
  std::uint32_t index_;
  ObservationWindow window_;
  std::unique_ptr<Engine> engine_;
  const EngineSpec* engine_spec_ = nullptr;  // in the static registry
  std::uint32_t accepted_kinds_ = 0;         // acceptedKindMask(*engine_spec_)
  std::uint64_t misaddressed_handoffs_ = 0;
  /// The live tracks of the ticks still in the window, oldest first: the settled estimate of an
  /// engine that does not revise the past.
  std::deque<std::pair<std::int32_t, std::vector<common::TrackEstimate>>> live_history_;
  std::int32_t settled_through_ = 0;  ///< every tick up to this one is settled

  /// Revised estimates of tracks handed to a neighbour, for the ticks not settled yet, by tick.
  std::map<std::int32_t, std::vector<common::TrackEstimate>> released_settled_;

  /// The settled tracks of `tick` (still in the window), those handed on before included.
  std::vector<common::TrackEstimate> settle(std::int32_t tick);
  /// Keeps the revised estimate of `track`, about to be handed on at `tick`, of every tick not
  /// settled yet.
  void keepSettledOf(common::TrackId track, std::int32_t tick);
};

}  // namespace wsn::supernode

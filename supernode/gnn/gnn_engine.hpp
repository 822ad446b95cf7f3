// Global-nearest-neighbour tracking engine ("gnn"): the baseline every other engine is measured
// against. Kalman filters on Oh eq. (8), optimal gated assignment per tick, M-of-N confirmation,
// and replay of the whole observation window so that delayed observations are used.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/kalman.hpp"
#include "supernode/engine.hpp"

namespace wsn::supernode::gnn {

/// The engine's registration: name "gnn", its parameters with defaults and ranges, factory.
EngineSpec engineSpec();

/// Resolved parameters (see engineSpec() for meaning, defaults and ranges).
struct GnnParams {
  double measurement_sigma = 0.5;
  double gate_chi2 = 9.21;
  std::int32_t confirm_hits = 3;
  std::int32_t confirm_window = 5;
  std::int32_t max_misses = 3;
  double initial_velocity_sigma = 2.0;
  double merge_radius = 0.0;  ///< same-tick reports this close are merged first (0: none)

  /// From the engine context's resolved params (paramTable() decodes them).
  static GnnParams fromContext(const EngineContext& context);
};

/// The parameters' one description: key, member, unit, range, default (GnnParams{}) and meaning.
const config::FieldTable<GnnParams>& paramTable();


/// GNN tracker with window replay. The engine keeps an *anchor* (its tracks after every tick that
/// already left the window) and, on each step, replays the window's ticks from the anchor, so an
/// observation that arrives late in its own slot changes the newest estimate just as if it had been
/// on time. Handoffs are events in that timeline: an adopted track enters every replay at the tick
/// after its last_tick, a released one leaves every replay after the tick it was released at.
class GnnEngine final : public Engine {
 public:
  explicit GnnEngine(const EngineContext& context);

  void adopt(const common::TrackHandoff& handoff) override;
  void step(const ObservationWindow& window) override;
  std::vector<common::TrackEstimate> confirmedTracks() const override;
  std::vector<TrackPrediction> predictions() const override;
  common::TrackHandoff release(common::TrackId track, std::uint32_t to_supernode) override;

  /// A live track (tentative or confirmed) as the engine holds it.
  struct Track {
    common::TrackId id = 0;
    common::GaussianState state;
    /// Observations associated so far (the birth observation included).
    std::int32_t hits = 0;
    /// Tentative: misses since birth (so hits + misses is the track's age in ticks);
    /// confirmed: consecutive misses since the last hit.
    std::int32_t misses = 0;
    bool confirmed = false;
  };

  /// Tracks at the newest tick, sorted by id (tentative ones included).
  const std::vector<Track>& liveTracks() const { return current_; }
  /// Handoffs ignored because their state or covariance was not finite.
  std::uint64_t rejectedHandoffs() const { return rejected_handoffs_; }

 private:
  struct Adoption {
    std::int32_t tick = 0;  // first tick at which the track takes part (handoff.last_tick + 1)
    std::int32_t state_tick = 0;
    Track track;
  };
  struct Release {
    std::int32_t tick = 0;  // the track is gone after this tick
    common::TrackId id = 0;
  };

  /// Optimal gated assignment of observations to (predicted) tracks: for each track, the index
  /// of its observation in `slot` or -1.
  std::vector<int> associate(const std::vector<Track>& tracks, std::span<const common::Observation> slot) const;
  /// One GNN scan at `tick` on tracks whose state is at tick - 1.
  void processTick(std::vector<Track>& tracks, std::int32_t tick, std::span<const common::Observation> slot) const;
  /// Adds (or replaces, by id) a track; keeps `tracks` sorted by id.
  static void inject(std::vector<Track>& tracks, const Track& track);
  /// Moves the anchor forward to `tick` with the final contents of the ticks it passes.
  void foldAnchorTo(std::int32_t tick);

  std::uint32_t supernode_;
  common::Rect region_;  ///< the surveillance region: no sensor sees a target outside it
  GnnParams params_;
  common::ConstantVelocityModel model_;
  bool started_ = false;
  std::int32_t anchor_tick_ = 0;  // anchor_ holds the tracks after this tick
  std::vector<Track> anchor_;
  std::int32_t current_tick_ = 0;  // current_ holds the tracks after this (the newest) tick
  std::vector<Track> current_;
  std::vector<Adoption> adoptions_;  // not yet folded into the anchor
  std::vector<Release> releases_;    // not yet folded into the anchor
  // The window's contents as of the last step: a tick that has since left the window is folded
  // into the anchor with these, its final contents.
  std::int32_t cached_oldest_tick_ = 0;
  std::vector<std::vector<common::Observation>> cached_slots_;
  std::uint64_t rejected_handoffs_ = 0;
};

}  // namespace wsn::supernode::gnn

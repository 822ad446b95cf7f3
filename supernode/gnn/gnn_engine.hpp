// Global-nearest-neighbour tracking engine ("gnn"): the baseline every other engine is measured
// against. Kalman filters on Oh eq. (8), optimal gated assignment per tick, M-of-N confirmation,
// and replay of the whole observation window so that delayed observations are used.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/kalman.hpp"
#include "supernode/engine.hpp"
#include "supernode/window_replay.hpp"

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


/// GNN tracker with window replay (supernode/window_replay.hpp, shared with sbmht): the engine keeps
/// an *anchor* (its tracks after every tick that already left the window) and, on each step, replays
/// the window's ticks from the anchor, so an observation that arrives late in its own slot changes the
/// newest estimate just as if it had been on time. Handoffs are events in that timeline: an adopted
/// track enters every replay at the tick after its last_tick, a released one leaves every replay after
/// the tick it was released at.
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
    /// Where the sensors' coverage is known (confirmed tracks): the chance that a live target at
    /// the track's predicted positions went unseen through its misses since the last hit.
    double silence = 1.0;
    bool confirmed = false;
  };

  /// Tracks at the newest tick, sorted by id (tentative ones included).
  const std::vector<Track>& liveTracks() const { return replay_.current(); }
  /// Handoffs ignored because their state or covariance was not finite.
  std::uint64_t rejectedHandoffs() const { return rejected_handoffs_; }

 private:
  /// Optimal gated assignment of observations to (predicted) tracks: for each track, the index
  /// of its observation in `slot` or -1.
  std::vector<int> associate(const std::vector<Track>& tracks, std::span<const common::Observation> slot) const;
  /// A confirmed track's miss at its predicted position: updates its silence and tells whether a
  /// live target's silence so long would be rarer than common::kRareMissRun (coverage known only).
  bool silenceIsRare(Track& track) const;
  /// One GNN scan at `tick` on tracks whose state is at tick - 1.
  void processTick(std::vector<Track>& tracks, std::int32_t tick, std::span<const common::Observation> slot) const;

  std::uint32_t supernode_;
  common::Rect region_;  ///< the surveillance region: no sensor sees a target outside it
  /// Where the field's sensors see well and where not (field sensors); uniform otherwise.
  common::DetectionShare detection_share_;
  GnnParams params_;
  /// rho = common::kRareMissRun^(1 / max_misses): one silent tick of a live target on the field's
  /// average (silenceIsRare).
  double unseen_tick_weight_;
  common::ConstantVelocityModel model_;
  WindowReplay<Track> replay_;
  std::uint64_t rejected_handoffs_ = 0;
};

}  // namespace wsn::supernode::gnn

// Re-homing a dead supernode's tracking group: the tracks it reported last become handoffs to
// the live supernodes whose groups they are about to enter, so that the adopters carry them on
// (ids included) instead of starting them again from nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "common/geometry.hpp"
#include "common/messages.hpp"

namespace wsn::supernode {

/// Oh §V's g() over the supernodes `live` marks (one flag per supernode; empty: all): the index
/// of the nearest live one (ties to the lower index); 0 when none is live. A group re-homed
/// after a fault belongs to the nearest live supernode.
std::uint32_t nearestLiveSupernode(const std::vector<common::Vec2>& supernodes, const std::vector<bool>& live,
                                   common::Vec2 position);

/// What the adopters need to continue a dead supernode's tracks.
struct OrphanContext {
  std::vector<common::Vec2> supernodes;  ///< every supernode of the scenario
  std::vector<bool> live;                ///< those live at the tick the adopters take over
  double delta = 1.0;                    ///< the tick length (dynamics.delta): a track's next position is x + Δ v
  std::int32_t window_size = 10;         ///< an orphan counts as seen in a full window (hits)
};

/// The dead supernode's confirmed tracks of `last_tick` (its last TrackBatch), each addressed to
/// the live supernode nearest its predicted position at last_tick + 1, in track order. A track
/// keeps its id, state and covariance; its misses are the ticks since it was last seen.
std::vector<common::TrackHandoff> orphanHandoffs(const std::vector<common::TrackEstimate>& last_tracks,
                                                 std::int32_t last_tick, const OrphanContext& context);

}  // namespace wsn::supernode

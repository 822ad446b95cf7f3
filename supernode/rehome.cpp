#include "supernode/rehome.hpp"

#include <algorithm>
#include <optional>

namespace wsn::supernode {

std::uint32_t nearestLiveSupernode(const std::vector<common::Vec2>& supernodes, const std::vector<bool>& live,
                                   common::Vec2 position) {
  const auto is_live = [&](std::uint32_t j) { return live.empty() || (j < live.size() && live[j]); };
  std::optional<std::uint32_t> best;
  for (std::uint32_t j = 0; j < supernodes.size(); ++j)
    if (is_live(j) && (!best || common::squaredDistance(supernodes[j], position) <
                                    common::squaredDistance(supernodes[*best], position)))
      best = j;
  return best.value_or(0);
}

std::vector<common::TrackHandoff> orphanHandoffs(const std::vector<common::TrackEstimate>& last_tracks,
                                                 std::int32_t last_tick, const OrphanContext& context) {
  std::vector<common::TrackHandoff> out;
  for (const auto& track : last_tracks) {
    if (!common::isFinite(track)) continue;
    const common::Vec2 next{track.x + context.delta * track.vx, track.y + context.delta * track.vy};
    common::TrackHandoff h;
    h.track = track.track;
    h.to_supernode = nearestLiveSupernode(context.supernodes, context.live, next);
    h.last_tick = last_tick;
    h.state = {track.x, track.y, track.vx, track.vy};
    h.covariance = track.covariance;
    h.hits = context.window_size;
    h.misses = track.last_seen_tick > 0 ? std::max(0, last_tick - track.last_seen_tick) : 0;
    h.confirmed = true;
    h.class_probabilities = track.class_probabilities;
    out.push_back(std::move(h));
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.track < b.track; });
  return out;
}

}  // namespace wsn::supernode

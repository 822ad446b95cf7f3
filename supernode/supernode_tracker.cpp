#include "supernode/supernode_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "common/voronoi.hpp"

namespace wsn::supernode {
namespace {

bool handoffLess(const common::TrackHandoff& a, const common::TrackHandoff& b) {
  return std::tie(a.track, a.last_tick, a.to_supernode, a.state, a.covariance, a.hits, a.misses, a.confirmed) <
         std::tie(b.track, b.last_tick, b.to_supernode, b.state, b.covariance, b.hits, b.misses, b.confirmed);
}

}  // namespace

std::uint32_t nearestSupernode(const std::vector<common::Vec2>& supernodes, common::Vec2 position) {
  return nearestLiveSupernode(supernodes, {}, position);
}


SupernodeConfig supernodeConfig(const common::Scenario& resolved, std::uint32_t index) {
  return {engineContext(resolved, index), resolved.supernodes};
}

SupernodeTracker::SupernodeTracker(SupernodeConfig config)
    : supernodes_(std::move(config.supernodes)), index_(config.engine.supernode), window_(config.engine.window_size) {
  // Without supernodes in the scenario there is a single tracking group, index 0.
  if (index_ >= std::max<std::size_t>(1, supernodes_.size()))
    throw std::invalid_argument("supernode index " + std::to_string(index_) + " out of range: the scenario has " +
                                std::to_string(supernodes_.size()) + " supernodes");
  if (!supernodes_.empty()) neighbours_ = common::voronoiNeighboursOf(supernodes_, config.engine.region, index_);
  engine_ = makeEngine(config.engine);
  engine_spec_ = engineRegistry().find(config.engine.engine);  // makeEngine found it
  accepted_kinds_ = acceptedKindMask(*engine_spec_);
}

SupernodeTracker::SupernodeTracker(SupernodeConfig config, std::int32_t first_tick) : SupernodeTracker(std::move(config)) {
  settled_through_ = first_tick - 1;
}

SupernodeTracker::TickOutput SupernodeTracker::step(std::int32_t tick, std::span<const common::Observation> delivered,
                                                    std::span<const common::TrackHandoff> incoming) {
  window_.advanceTo(tick);
  // No sort first: the window files each observation at its canonical place in its slot, and
  // canonical order is total, so the slots come out the same in any arrival order.
  for (const auto& observation : delivered) {
    const auto kind = static_cast<unsigned>(observation.measurement.kind());
    const std::uint32_t kind_bit = kind < 32 ? 1u << kind : 0;  // an unknown kind is never accepted
    if ((accepted_kinds_ & kind_bit) == 0) requireAccepted(*engine_spec_, observation);  // throws
    window_.insert(observation);
  }

  std::vector<common::TrackHandoff> handoffs_in(incoming.begin(), incoming.end());
  std::sort(handoffs_in.begin(), handoffs_in.end(), handoffLess);
  for (const auto& handoff : handoffs_in) {
    if (handoff.to_supernode != index_) {
      ++misaddressed_handoffs_;
      continue;
    }
    engine_->adopt(handoff);
  }

  engine_->step(window_);

  TickOutput out;
  out.tick = tick;
  out.tracks = engine_->confirmedTracks();
  // Oh §VI: a track whose predicted next state lies in another supernode's tracking group is
  // passed to that supernode, or towards it (ownerOf).
  for (const auto& prediction : engine_->predictions()) {  // sorted by id
    const std::uint32_t owner = ownerOf(prediction.next_position);
    if (owner != index_) {
      keepSettledOf(prediction.track, tick);
      out.handoffs.push_back(engine_->release(prediction.track, owner));
    }
  }
  out.observations_in_window = static_cast<std::uint32_t>(window_.size());
  out.observations_dropped_stale = window_.droppedStale();

  live_history_.emplace_back(tick, out.tracks);
  const std::int32_t leaving = tick - window_.windowSize() + 1;  // the window's oldest slot: final now
  out.settled.first = settled_through_ + 1;
  for (std::int32_t t = settled_through_ + 1; t <= leaving; ++t) out.settled.by_tick.push_back(settle(t));
  settled_through_ = std::max(settled_through_, leaving);
  while (!live_history_.empty() && live_history_.front().first <= settled_through_) live_history_.pop_front();
  return out;
}

std::uint32_t SupernodeTracker::ownerOf(common::Vec2 position) const {
  // A track that leaps past the neighbouring groups in one tick goes to the neighbour nearest to
  // it, which hands it on at its next step; each hop brings it nearer, so it never comes back.
  // A group's nearest other supernode always borders it, so a track that leaves a group for the
  // next one goes where the network model routes that group's reports.
  std::uint32_t best = index_;
  if (supernodes_.empty()) return best;
  const auto is_live = [&](std::uint32_t j) { return live_.empty() || (j < live_.size() && live_[j]); };
  double best_d2 = is_live(index_) ? common::squaredDistance(supernodes_[index_], position) : INFINITY;
  for (const std::uint32_t j : neighbours_) {
    if (!is_live(j)) continue;
    const double d2 = common::squaredDistance(supernodes_[j], position);
    if (d2 < best_d2 || (d2 == best_d2 && j < best)) {
      best = j;
      best_d2 = d2;
    }
  }
  return best;
}

bool SupernodeTracker::tracks(common::TrackId track) const {
  for (const auto& prediction : engine_->predictions())
    if (prediction.track == track) return true;
  return false;
}

void SupernodeTracker::keepSettledOf(common::TrackId track, std::int32_t tick) {
  // The neighbour continues the track from an anchor at `tick` (and settles that tick itself):
  // the ticks before it that are still in this window would be in neither window's revised
  // estimate. Keep this window's estimate of them as it stands now.
  for (std::int32_t t = settled_through_ + 1; t < tick; ++t) {
    const auto revised = engine_->revisedTracks(t);
    if (!revised) return;  // an engine that does not revise: its live history has the track
    for (const auto& estimate : *revised)
      if (estimate.track == track) released_settled_[t].push_back(estimate);
  }
}

std::vector<common::TrackEstimate> SupernodeTracker::settle(std::int32_t tick) {
  std::vector<common::TrackEstimate> tracks;
  if (auto revised = engine_->revisedTracks(tick)) {
    tracks = std::move(*revised);
  } else {
    for (const auto& [t, live] : live_history_)
      if (t == tick) tracks = live;
  }
  if (const auto it = released_settled_.find(tick); it != released_settled_.end()) {
    tracks.insert(tracks.end(), it->second.begin(), it->second.end());
    released_settled_.erase(it);
  }
  std::sort(tracks.begin(), tracks.end(),
            [](const common::TrackEstimate& a, const common::TrackEstimate& b) { return a.track < b.track; });
  return tracks;
}

SupernodeTracker::Settled SupernodeTracker::settleRemaining() {
  Settled out;
  out.first = settled_through_ + 1;
  for (std::int32_t t = settled_through_ + 1; t <= window_.newestTick(); ++t) out.by_tick.push_back(settle(t));
  settled_through_ = std::max(settled_through_, window_.newestTick());
  live_history_.clear();
  return out;
}

}  // namespace wsn::supernode

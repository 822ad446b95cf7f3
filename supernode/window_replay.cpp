#include "supernode/window_replay.hpp"

namespace wsn::supernode {

std::optional<ReplayClock::Ticks> ReplayClock::start(const ObservationWindow& window) {
  const std::int32_t newest = window.newestTick();
  if (newest < 1) return std::nullopt;
  const std::int32_t oldest = window.oldestTick();
  if (!started_) {
    started_ = true;
    anchor_tick_ = oldest - 1;
    cached_oldest_tick_ = oldest;
  }
  return Ticks{oldest, newest};
}

void ReplayClock::foldAnchorTo(std::int32_t tick, const TickVisit& visit) {
  for (std::int32_t t = anchor_tick_ + 1; t <= tick; ++t) {
    std::span<const common::Observation> slot;
    const std::int64_t index = std::int64_t{t} - cached_oldest_tick_;
    if (index >= 0 && index < static_cast<std::int64_t>(cached_slots_.size()))
      slot = cached_slots_[static_cast<std::size_t>(index)];
    visit(t, slot);
    anchor_tick_ = t;
  }
}

void ReplayClock::replay(const ObservationWindow& window, Ticks ticks, const TickVisit& visit) {
  for (std::int32_t t = ticks.oldest; t <= ticks.newest; ++t) visit(t, window.slot(t));
  current_tick_ = ticks.newest;
  cached_oldest_tick_ = ticks.oldest;
  cached_slots_.clear();
  for (std::int32_t t = ticks.oldest; t <= ticks.newest; ++t) {
    const auto slot = window.slot(t);
    cached_slots_.emplace_back(slot.begin(), slot.end());
  }
}

}  // namespace wsn::supernode

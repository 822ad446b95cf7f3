#include "supernode/observation_window.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "common/report_merging.hpp"

namespace wsn::supernode {
namespace {

/// Canonical order within a slot: sensor, then position; delivery tick, target, power level and
/// measurement only break ties. The order is total over every field an engine reads, so a slot's
/// contents never show the order in which observations arrived.
bool canonicalLess(const common::Observation& a, const common::Observation& b) {
  return std::tie(a.sensor, a.x, a.y, a.tick_delivered, a.target, a.power_level, a.measurement) <
         std::tie(b.sensor, b.x, b.y, b.tick_delivered, b.target, b.power_level, b.measurement);
}

}  // namespace

ObservationWindow::ObservationWindow(std::int32_t window_size) : window_size_(window_size) {
  if (window_size < 1)
    throw std::invalid_argument("observation window size must be >= 1, got " + std::to_string(window_size));
}

std::int32_t ObservationWindow::oldestTick() const { return std::max(1, newest_tick_ - window_size_ + 1); }

void ObservationWindow::advanceTo(std::int32_t tick) {
  if (tick <= newest_tick_) return;
  // Oh §VI: slots older than t - ws + 1 leave the window; new ticks get empty slots.
  const std::int32_t old_oldest = oldestTick();
  newest_tick_ = tick;
  const std::int32_t new_oldest = oldestTick();
  const auto drop = std::min(static_cast<std::size_t>(new_oldest - old_oldest), slots_.size());
  slots_.erase(slots_.begin(), slots_.begin() + static_cast<std::ptrdiff_t>(drop));
  const auto wanted = static_cast<std::size_t>(newest_tick_ - new_oldest + 1);
  while (slots_.size() < wanted) slots_.emplace_back();
}

bool ObservationWindow::insert(common::Observation observation) {
  const std::int32_t t = observation.tick_generated;
  if (slots_.empty() || t < oldestTick() || t > newest_tick_) {
    ++dropped_stale_;
    return false;
  }
  auto& slot = slots_[static_cast<std::size_t>(t - oldestTick())];
  const auto at = std::upper_bound(slot.begin(), slot.end(), observation, canonicalLess);
  slot.insert(at, std::move(observation));
  return true;
}

ObservationWindow ObservationWindow::merged(double radius) const {
  ObservationWindow out(*this);
  if (radius > 0.0)
    for (auto& slot : out.slots_) {
      slot = common::mergeNearby(std::span<const common::Observation>(slot), radius);
      std::stable_sort(slot.begin(), slot.end(), canonicalLess);
    }
  return out;
}

std::span<const common::Observation> ObservationWindow::slot(std::int32_t tick) const {
  if (slots_.empty() || tick < oldestTick() || tick > newest_tick_) return {};
  return slots_[static_cast<std::size_t>(tick - oldestTick())];
}

std::size_t ObservationWindow::size() const {
  std::size_t n = 0;
  for (const auto& slot : slots_) n += slot.size();
  return n;
}

}  // namespace wsn::supernode

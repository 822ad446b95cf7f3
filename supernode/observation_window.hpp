// The sliding window of ws ticks of delivered observations (Oh §VI): a delayed observation
// goes into the slot of the tick it was generated; one older than the window is dropped.
#pragma once

#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include "common/messages.hpp"

namespace wsn::supernode {

class ObservationWindow {
 public:
  explicit ObservationWindow(std::int32_t window_size);

  /// Slides the window so that its newest slot is `tick` (ticks only move forward).
  void advanceTo(std::int32_t tick);
  /// Puts an observation into the slot of its tick_generated; returns false (and counts it)
  /// when that tick already left the window or lies in the future.
  bool insert(common::Observation observation);

  std::int32_t windowSize() const { return window_size_; }
  std::int32_t newestTick() const { return newest_tick_; }
  /// max(1, newest - ws + 1).
  std::int32_t oldestTick() const;
  /// Observations generated at `tick`, in canonical order (sorted by sensor, then position).
  std::span<const common::Observation> slot(std::int32_t tick) const;
  std::size_t size() const;
  std::uint64_t droppedStale() const { return dropped_stale_; }
  /// This window with each slot's observations within `radius` of one another merged into one
  /// (common::mergeNearby): what an engine assuming at most one report per target and tick sees of
  /// a sensor model that reports every detecting sensor. radius <= 0: an unchanged copy.
  ObservationWindow merged(double radius) const;

 private:
  std::int32_t window_size_;
  std::int32_t newest_tick_ = 0;
  std::deque<std::vector<common::Observation>> slots_;  // front = oldest
  std::uint64_t dropped_stale_ = 0;
};

}  // namespace wsn::supernode

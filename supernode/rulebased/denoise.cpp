#include "supernode/rulebased/denoise.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace wsn::supernode::rulebased {

PersistenceFilter::PersistenceFilter(std::int32_t ticks) : ticks_(ticks) {
  if (ticks < 1) throw std::invalid_argument("persistence filter: ticks must be >= 1, got " + std::to_string(ticks));
}

std::vector<Detection> PersistenceFilter::apply(std::int32_t tick, std::span<const Detection> detections) {
  std::vector<Detection> kept;
  // Each of the previous ticks_ - 1 ticks must have been fed and hold the sensor.
  const auto needed = static_cast<std::size_t>(ticks_ - 1);
  bool consecutive = history_.size() == needed;
  for (std::size_t i = 0; consecutive && i < history_.size(); ++i)
    consecutive = history_[i].tick == tick - static_cast<std::int32_t>(needed - i);
  if (consecutive) {
    for (const auto& d : detections) {
      const bool persisted = std::all_of(history_.begin(), history_.end(), [&](const Past& past) {
        return std::binary_search(past.sensors.begin(), past.sensors.end(), d.sensor);
      });
      if (persisted) kept.push_back(d);
    }
  }
  if (needed > 0) {
    Past now{tick, {}};
    for (const auto& d : detections) now.sensors.push_back(d.sensor);
    std::sort(now.sensors.begin(), now.sensors.end());
    history_.push_back(std::move(now));
    while (history_.size() > needed) history_.pop_front();
  }
  return kept;
}

std::vector<Detection> spatialFilter(std::span<const Detection> survivors, double radius, std::int32_t min_cluster) {
  const std::size_t m = survivors.size();
  // n_j >= min(m / 2, min_cluster), compared as 2 n_j >= m to stay in integers for the paper's part.
  const double radius_squared = radius * radius;
  std::vector<Detection> kept;
  for (std::size_t j = 0; j < m; ++j) {
    std::size_t near = 0;
    for (std::size_t l = 0; l < m; ++l)
      if (common::squaredDistance(survivors[j].position, survivors[l].position) <= radius_squared) ++near;
    if (2 * near >= m || near >= static_cast<std::size_t>(std::max(min_cluster, 1))) kept.push_back(survivors[j]);
  }
  return kept;
}

}  // namespace wsn::supernode::rulebased

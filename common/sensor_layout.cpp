#include "common/sensor_layout.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/rng.hpp"

namespace wsn::common {

GridShape gridShape(const Rect& region, double spacing) {
  return {static_cast<std::uint32_t>(std::floor(region.width() / spacing + 1e-9)),
          static_cast<std::uint32_t>(std::floor(region.height() / spacing + 1e-9))};
}

std::uint64_t sensorCount(const SensorLayoutConfig& config, const Rect& region) {
  switch (config.kind) {
    case SensorLayoutConfig::Kind::kList: return config.list.size();
    case SensorLayoutConfig::Kind::kGrid: return gridShape(region, config.spacing).sensors();
    default: return config.count;
  }
}

SensorFieldConfig sensorFieldConfig(const Scenario& scenario) {
  return {scenario.region, scenario.sensors, scenario.localisation.sigma, scenario.sensor_model.sensing_range,
          scenario.run.seed};
}

PlacedSensor placedSensorOf(const PlacedSensorConfig& config) {
  constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;
  return {config.name,
          config.type,
          config.heading_deg * kRadiansPerDegree,
          config.fov_deg * kRadiansPerDegree,
          config.range,
          config.height};
}

SensorLayout::SensorLayout(const SensorFieldConfig& field) : region_(field.region) {
  const auto& config = field.sensors;
  if (config.kind == SensorLayoutConfig::Kind::kList) {
    true_positions_.reserve(config.list.size());
    placed_.reserve(config.list.size());
    for (const auto& sensor : config.list) {
      true_positions_.push_back(sensor.position);
      placed_.push_back(placedSensorOf(sensor));
    }
  } else if (config.kind == SensorLayoutConfig::Kind::kGrid) {
    const GridShape grid = gridShape(region_, config.spacing);
    true_positions_.reserve(grid.sensors());
    for (std::uint32_t r = 0; r < grid.rows; ++r)
      for (std::uint32_t c = 0; c < grid.columns; ++c)
        true_positions_.push_back({region_.x_min + (c + 0.5) * config.spacing, region_.y_min + (r + 0.5) * config.spacing});
  } else {
    true_positions_.reserve(config.count);
    for (std::uint32_t id = 0; id < config.count; ++id) {
      Stream place(field.seed, Purpose::kSensorPlacement, id, 0);
      const double x = place.uniform(region_.x_min, region_.x_max);
      const double y = place.uniform(region_.y_min, region_.y_max);
      true_positions_.push_back({x, y});
    }
  }

  believed_positions_ = true_positions_;
  if (field.localisation_sigma > 0.0) {
    for (SensorId id = 0; id < believed_positions_.size(); ++id) {
      Stream error(field.seed, Purpose::kSensorLocalisation, id, 0);
      const double ex = field.localisation_sigma * error.normal();
      const double ey = field.localisation_sigma * error.normal();
      believed_positions_[id] = true_positions_[id] + Vec2{ex, ey};
    }
  }

  // Cells of side 2 Rs: a 2 Rs neighbourhood touches at most 3 x 3 cells.
  cell_size_ = std::max(2.0 * field.sensing_range, 1e-6);
  columns_ = std::max(1, static_cast<std::int32_t>(std::ceil(region_.width() / cell_size_ - 1e-9)));
  rows_ = std::max(1, static_cast<std::int32_t>(std::ceil(region_.height() / cell_size_ - 1e-9)));
  cells_.assign(static_cast<std::size_t>(columns_) * rows_, {});
  for (SensorId id = 0; id < true_positions_.size(); ++id) cells_[cellOf(true_positions_[id])].push_back(id);
}

std::int32_t SensorLayout::cellOf(Vec2 p) const {
  auto c = static_cast<std::int32_t>(std::floor((p.x - region_.x_min) / cell_size_));
  auto r = static_cast<std::int32_t>(std::floor((p.y - region_.y_min) / cell_size_));
  c = std::clamp(c, 0, columns_ - 1);
  r = std::clamp(r, 0, rows_ - 1);
  return r * columns_ + c;
}

Rect SensorLayout::cellRect(std::int32_t cell) const {
  const std::int32_t c = cell % columns_;
  const std::int32_t r = cell / columns_;
  const double x0 = region_.x_min + c * cell_size_;
  const double y0 = region_.y_min + r * cell_size_;
  return {x0, y0, x0 + cell_size_, y0 + cell_size_};
}

void SensorLayout::collectWithin(Vec2 p, double radius, std::vector<SensorId>& out) const {
  out.clear();
  const double r2 = radius * radius;
  const auto c0 = std::clamp(static_cast<std::int32_t>(std::floor((p.x - radius - region_.x_min) / cell_size_)), 0, columns_ - 1);
  const auto c1 = std::clamp(static_cast<std::int32_t>(std::floor((p.x + radius - region_.x_min) / cell_size_)), 0, columns_ - 1);
  const auto r0 = std::clamp(static_cast<std::int32_t>(std::floor((p.y - radius - region_.y_min) / cell_size_)), 0, rows_ - 1);
  const auto r1 = std::clamp(static_cast<std::int32_t>(std::floor((p.y + radius - region_.y_min) / cell_size_)), 0, rows_ - 1);
  for (std::int32_t r = r0; r <= r1; ++r)
    for (std::int32_t c = c0; c <= c1; ++c)
      for (SensorId id : cells_[static_cast<std::size_t>(r * columns_ + c)])
        if (squaredDistance(true_positions_[id], p) <= r2) out.push_back(id);
  std::sort(out.begin(), out.end());
}

}  // namespace wsn::common

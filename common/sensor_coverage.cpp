#include "common/sensor_coverage.hpp"

#include <cmath>
#include <algorithm>
#include <numbers>
#include <utility>

namespace wsn::common {

bool inSector(Vec2 sensor, double heading, double fov, double range, Vec2 p) {
  const double dx = p.x - sensor.x;
  const double dy = p.y - sensor.y;
  if (std::hypot(dx, dy) > range) return false;
  // A full circle covers every bearing, including the one at exactly -pi from the heading.
  return fov >= 2.0 * std::numbers::pi || std::abs(wrapAngle(std::atan2(dy, dx) - heading)) <= 0.5 * fov;
}

bool hiddenBy(const Terrain* terrain, SightBlockers blockers, Vec2 from, Vec2 p) {
  if (terrain == nullptr) return false;
  switch (blockers) {
    case SightBlockers::none:
      return false;
    case SightBlockers::buildings:
      return terrain->blockedBy(from, p, MaskKind::kBuilding);
    case SightBlockers::buildings_and_vegetation:
      return !terrain->lineOfSight(from, p);
  }
  return false;
}

double detectionProbabilityAt(const SensorCoverage& sensor, Vec2 p, const Terrain* terrain) {
  if (!inSector(sensor.position, sensor.heading, sensor.fov, sensor.range, p)) return 0.0;
  if (hiddenBy(terrain, sensor.blockers, sensor.position, p)) return 0.0;
  return sensor.detection_probability;
}

double sensedProbabilityAt(const std::vector<SensorCoverage>& sensors, Vec2 p, const Terrain* terrain) {
  double missed = 1.0;
  for (const SensorCoverage& sensor : sensors) missed *= 1.0 - detectionProbabilityAt(sensor, p, terrain);
  return 1.0 - missed;
}

double meanSensedProbability(const std::vector<SensorCoverage>& sensors, const Rect& region, const Terrain* terrain,
                             int cells_per_side) {
  if (sensors.empty() || cells_per_side < 1 || region.area() <= 0.0) return 0.0;
  const double dx = region.width() / cells_per_side;
  const double dy = region.height() / cells_per_side;
  // Each sensor touches only the cells within its range: the product of misses is built sensor by
  // sensor over those, so a large field costs its sensors' footprints, not sensors x cells.
  std::vector<double> missed(static_cast<std::size_t>(cells_per_side) * static_cast<std::size_t>(cells_per_side), 1.0);
  const auto cell = [&](double v, double lo, double step) {
    return std::clamp(static_cast<int>(std::floor((v - lo) / step)), 0, cells_per_side - 1);
  };
  for (const SensorCoverage& sensor : sensors) {
    const int i0 = cell(sensor.position.x - sensor.range, region.x_min, dx);
    const int i1 = cell(sensor.position.x + sensor.range, region.x_min, dx);
    const int j0 = cell(sensor.position.y - sensor.range, region.y_min, dy);
    const int j1 = cell(sensor.position.y + sensor.range, region.y_min, dy);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Vec2 p{region.x_min + (i + 0.5) * dx, region.y_min + (j + 0.5) * dy};
        missed[static_cast<std::size_t>(j) * static_cast<std::size_t>(cells_per_side) + static_cast<std::size_t>(i)] *=
            1.0 - detectionProbabilityAt(sensor, p, terrain);
      }
  }
  double sensed = 0.0;
  for (const double m : missed) sensed += 1.0 - m;
  return sensed / static_cast<double>(missed.size());
}

DetectionShare::DetectionShare(std::vector<SensorCoverage> sensors, std::shared_ptr<const Terrain> terrain,
                               double region_mean)
    : sensors_(std::move(sensors)), terrain_(std::move(terrain)), region_mean_(region_mean) {}

}  // namespace wsn::common

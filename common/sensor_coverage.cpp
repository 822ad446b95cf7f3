#include "common/sensor_coverage.hpp"

#include <cmath>
#include <numbers>

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

}  // namespace wsn::common

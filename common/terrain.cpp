#include "common/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

namespace wsn::common {
namespace {

double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
double length(Vec2 a) { return std::hypot(a.x, a.y); }

/// Twice the signed area of the triangle (o, a, b): > 0 when o -> a -> b turns counter-clockwise.
double orientation(Vec2 o, Vec2 a, Vec2 b) { return cross(a - o, b - o); }

/// p on the closed segment a-b.
bool onSegment(Vec2 p, Vec2 a, Vec2 b) {
  return orientation(a, b, p) == 0.0 && p.x >= std::min(a.x, b.x) && p.x <= std::max(a.x, b.x) &&
         p.y >= std::min(a.y, b.y) && p.y <= std::max(a.y, b.y);
}

/// Whether the closed segments p1-p2 and q1-q2 share a point.
bool segmentsMeet(Vec2 p1, Vec2 p2, Vec2 q1, Vec2 q2) {
  const double d1 = orientation(q1, q2, p1);
  const double d2 = orientation(q1, q2, p2);
  const double d3 = orientation(p1, p2, q1);
  const double d4 = orientation(p1, p2, q2);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return onSegment(p1, q1, q2) || onSegment(p2, q1, q2) || onSegment(q1, p1, p2) || onSegment(q2, p1, p2);
}

bool onBoundary(std::span<const Vec2> polygon, Vec2 point) {
  for (std::size_t i = 0; i < polygon.size(); ++i)
    if (onSegment(point, polygon[i], polygon[(i + 1) % polygon.size()])) return true;
  return false;
}

/// Crossing number of a ray from `point` towards +x: odd inside (boundary points are ambiguous).
bool oddCrossings(std::span<const Vec2> polygon, Vec2 point) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2 a = polygon[i];
    const Vec2 b = polygon[j];
    if ((a.y > point.y) != (b.y > point.y) && point.x < (b.x - a.x) * (point.y - a.y) / (b.y - a.y) + a.x)
      inside = !inside;
  }
  return inside;
}

}  // namespace

double PolylineFoot::heading() const { return std::atan2(direction.y, direction.x); }

std::optional<PolylineFoot> footPoint(std::span<const Vec2> polyline, Vec2 position) {
  std::optional<PolylineFoot> best;
  double start_along = 0.0;
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
    const Vec2 start = polyline[i];
    const Vec2 segment = polyline[i + 1] - start;
    const double segment_length = length(segment);
    if (!(segment_length > 0.0)) continue;
    const Vec2 direction = (1.0 / segment_length) * segment;
    const double t = std::clamp(dot(position - start, direction), 0.0, segment_length);
    const Vec2 point = start + t * direction;
    const double away = distance(position, point);
    if (!best || away < best->distance) best = PolylineFoot{i, point, direction, away, start_along + t};
    start_along += segment_length;
  }
  return best;
}

bool insidePolygon(std::span<const Vec2> polygon, Vec2 point) {
  if (polygon.size() < 3) return false;
  return onBoundary(polygon, point) || oddCrossings(polygon, point);
}

bool strictlyInsidePolygon(std::span<const Vec2> polygon, Vec2 point) {
  if (polygon.size() < 3) return false;
  return !onBoundary(polygon, point) && oddCrossings(polygon, point);
}

bool segmentEntersPolygon(Vec2 a, Vec2 b, std::span<const Vec2> polygon) {
  if (polygon.size() < 3) return false;
  if (strictlyInsidePolygon(polygon, a) || strictlyInsidePolygon(polygon, b)) return true;
  const Vec2 d = b - a;
  const double dd = dot(d, d);
  if (!(dd > 0.0)) return false;
  // Between two consecutive points where a-b meets the boundary the segment is wholly inside or
  // wholly outside, so one midpoint per piece decides it; this handles passing exactly through
  // vertices and along edges, where counting proper crossings alone goes wrong.
  std::vector<double> cuts{0.0, 1.0};
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 p = polygon[i];
    const Vec2 e = polygon[(i + 1) % polygon.size()] - p;
    const double denominator = cross(d, e);
    if (denominator != 0.0) {
      const double t = cross(p - a, e) / denominator;
      const double u = cross(p - a, d) / denominator;
      if (t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0) cuts.push_back(t);
    } else if (cross(p - a, d) == 0.0) {  // collinear: the edge's ends cut the segment
      for (const Vec2 v : {p, p + e}) {
        const double t = dot(v - a, d) / dd;
        if (t > 0.0 && t < 1.0) cuts.push_back(t);
      }
    }
  }
  std::sort(cuts.begin(), cuts.end());
  // Cuts a rounding error apart are one point: a midpoint between them would sit on the boundary.
  constexpr double kSamePoint = 1e-12;
  double previous = cuts.front();
  for (const double t : cuts) {
    if (t - previous <= kSamePoint) continue;
    if (strictlyInsidePolygon(polygon, a + 0.5 * (previous + t) * d)) return true;
    previous = t;
  }
  return false;
}

bool isSimplePolygon(std::span<const Vec2> polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) return false;
  double twice_area = 0.0;
  for (std::size_t i = 0; i < n; ++i) twice_area += cross(polygon[i], polygon[(i + 1) % n]);
  if (twice_area == 0.0) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a1 = polygon[i];
    const Vec2 a2 = polygon[(i + 1) % n];
    if (a1 == a2) return false;
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec2 b1 = polygon[j];
      const Vec2 b2 = polygon[(j + 1) % n];
      if (j == i + 1 || (i == 0 && j == n - 1)) {
        // Adjacent edges share one vertex; they must not also run back over each other.
        const Vec2 shared = j == i + 1 ? a2 : a1;
        const Vec2 p = j == i + 1 ? a1 : a2;
        const Vec2 q = j == i + 1 ? b2 : b1;
        if (orientation(shared, p, q) == 0.0 && dot(p - shared, q - shared) > 0.0) return false;
        continue;
      }
      if (segmentsMeet(a1, a2, b1, b2)) return false;
    }
  }
  return true;
}

Terrain::Terrain(TerrainConfig config) : config_(std::move(config)) {
  // Exact coordinates as keys: a junction is where roads share a vertex, not where they come close.
  std::map<std::pair<double, double>, std::set<std::size_t>> roads_at;
  for (std::size_t r = 0; r < config_.roads.size(); ++r)
    for (const Vec2 p : config_.roads[r].points) roads_at[{p.x, p.y}].insert(r);
  std::set<std::pair<double, double>> junction_points;
  for (const auto& [point, roads] : roads_at) {
    if (roads.size() < 2) continue;
    junctions_.push_back({{point.first, point.second}, {roads.begin(), roads.end()}});
    junction_points.insert(point);
  }

  for (std::size_t r = 0; r < config_.roads.size(); ++r) {
    const auto& points = config_.roads[r].points;
    if (points.size() < 2) continue;
    std::size_t first = 0;
    for (std::size_t i = 1; i < points.size(); ++i) {
      const bool last = i + 1 == points.size();
      if (!last && !junction_points.contains({points[i].x, points[i].y})) continue;
      RoadSection section{r, first, i, {points.begin() + static_cast<std::ptrdiff_t>(first),
                                        points.begin() + static_cast<std::ptrdiff_t>(i) + 1}, 0.0};
      section.dead_end_first = first == 0 && !junction_points.contains({points[0].x, points[0].y});
      section.dead_end_last = last && !junction_points.contains({points[i].x, points[i].y});
      for (std::size_t k = first; k < i; ++k) section.length += distance(points[k], points[k + 1]);
      sections_.push_back(std::move(section));
      first = i;
    }
  }
}

std::optional<RoadProjection> Terrain::project(Vec2 position) const {
  std::optional<RoadProjection> best;
  for (std::size_t s = 0; s < sections_.size(); ++s) {
    const auto foot = footPoint(sections_[s].points, position);
    if (!foot || (best && !(foot->distance < best->distance))) continue;
    best = RoadProjection{s, foot->segment, foot->point, foot->distance, foot->along, foot->direction};
  }
  if (!best) return best;
  // Beside the road the offset is perpendicular to it; past an end the foot is clamped there and
  // the offset has a component along the road. The tolerance is rounding at field coordinates.
  constexpr double kAlongTolerance = 1e-6;
  const RoadSection& section = sections_[best->section];
  const double ahead = dot(position - best->foot, best->direction);
  best->past_dead_end = (section.dead_end_first && best->segment == 0 && ahead < -kAlongTolerance) ||
                        (section.dead_end_last && best->segment + 2 == section.points.size() && ahead > kAlongTolerance);
  return best;
}

std::vector<std::size_t> Terrain::masksContaining(Vec2 point) const {
  std::vector<std::size_t> out;
  for (std::size_t m = 0; m < config_.masks.size(); ++m)
    if (insidePolygon(config_.masks[m].polygon, point)) out.push_back(m);
  return out;
}

bool Terrain::blockedBy(Vec2 a, Vec2 b, MaskKind kind) const {
  return std::any_of(config_.masks.begin(), config_.masks.end(), [&](const Mask& mask) {
    return mask.kind == kind && segmentEntersPolygon(a, b, mask.polygon);
  });
}

bool Terrain::lineOfSight(Vec2 a, Vec2 b) const {
  return !blockedBy(a, b, MaskKind::kBuilding) && !blockedBy(a, b, MaskKind::kVegetation);
}

}  // namespace wsn::common

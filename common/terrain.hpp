// The ground the targets move over (ONERA §II, §V): roads as named polylines split into sections
// at their junctions, and masks (buildings, vegetation) as polygons that hide what lies behind
// them. Pure geometry, shared by the scenario loader, the truth and the trackers; no DDS.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/geometry.hpp"

namespace wsn::common {

/// A road as its centre line, named in the scenario: a polyline through at least two points.
struct RoadLine {
  std::string name;
  std::vector<Vec2> points;
  friend bool operator==(const RoadLine&, const RoadLine&) = default;
};

/// What a mask is made of. The order is the scenario's choice list (common/scenario_schema.cpp).
enum class MaskKind { kBuilding, kVegetation };

/// An area that hides targets from sight: a simple polygon (vertices in either order, closed
/// implicitly from the last vertex back to the first).
struct Mask {
  std::string name;
  MaskKind kind = MaskKind::kBuilding;
  std::vector<Vec2> polygon;
  friend bool operator==(const Mask&, const Mask&) = default;
};

/// The scenario's `terrain:` section; empty when the scenario has none.
struct TerrainConfig {
  std::vector<RoadLine> roads;
  std::vector<Mask> masks;
  bool empty() const { return roads.empty() && masks.empty(); }
  friend bool operator==(const TerrainConfig&, const TerrainConfig&) = default;
};

/// Where a position meets a polyline: the foot of the perpendicular on its nearest segment.
struct PolylineFoot {
  /// Segment from points[segment] to points[segment + 1].
  std::size_t segment = 0;
  Vec2 point;
  /// Unit vector along the segment, in the polyline's order.
  Vec2 direction;
  /// From the position to the foot point.
  double distance = 0.0;
  /// Along the polyline from its first point to the foot point.
  double along = 0.0;

  /// The segment's direction in radians counter-clockwise from +x.
  double heading() const;
};

/// The foot point of `position` on the polyline's nearest segment; on a tie (outside a bend both
/// segments are nearest at their shared vertex) the first segment in the polyline's order.
/// Zero-length segments are skipped; nullopt when no segment is left. The one implementation of
/// this projection: the sbmht engine's roads (supernode/sbmht/road.hpp) use it too.
std::optional<PolylineFoot> footPoint(std::span<const Vec2> polyline, Vec2 position);

/// Whether `point` lies in the closed polygon (its boundary counts as inside).
bool insidePolygon(std::span<const Vec2> polygon, Vec2 point);

/// Whether `point` lies strictly inside the polygon (not on its boundary).
bool strictlyInsidePolygon(std::span<const Vec2> polygon, Vec2 point);

/// Whether some part of the closed segment a-b of positive length lies strictly inside the
/// polygon: crossing it, or starting or ending inside it. Grazing a vertex or running along an
/// edge from outside does not count.
bool segmentEntersPolygon(Vec2 a, Vec2 b, std::span<const Vec2> polygon);

/// Whether the polygon is simple: no two non-adjacent edges meet, no adjacent edges fold back
/// onto each other, and its area is not zero. The loader rejects the others.
bool isSimplePolygon(std::span<const Vec2> polygon);

/// Part of a road between two junctions or ends: the polyline from points[first_point] to
/// points[last_point] of roads[road].
struct RoadSection {
  std::size_t road = 0;
  std::size_t first_point = 0;
  std::size_t last_point = 0;
  std::vector<Vec2> points;
  double length = 0.0;
  /// Whether its first (last) point is a dead end: the end of a road that meets no other road there.
  bool dead_end_first = false;
  bool dead_end_last = false;
};

/// A point where two or more roads meet: a vertex of each of them, at exactly the same coordinates.
struct Junction {
  Vec2 point;
  std::vector<std::size_t> roads;  ///< ascending, each once
};

/// A position projected onto the nearest road section.
struct RoadProjection {
  std::size_t section = 0;  ///< index into Terrain::sections()
  std::size_t segment = 0;  ///< the foot's segment, from the section's points[segment] to points[segment + 1]
  Vec2 foot;
  double distance = 0.0;  ///< from the position to the foot point
  double along = 0.0;     ///< from the section's first point to the foot point
  Vec2 direction;         ///< unit, along the section's segment that holds the foot, in the road's order
  /// The position lies past a dead end of the section: the foot is that end, and the position is
  /// ahead of it along the road, not beside it. A target there has left the road.
  bool past_dead_end = false;
};

/// The scenario's terrain with its road sections and junctions worked out once.
class Terrain {
 public:
  Terrain() = default;
  explicit Terrain(TerrainConfig config);

  const TerrainConfig& config() const { return config_; }
  /// Sections in road order, and along each road in its points' order.
  const std::vector<RoadSection>& sections() const { return sections_; }
  /// Junctions ordered by (x, y).
  const std::vector<Junction>& junctions() const { return junctions_; }

  /// The foot point on the nearest section; on a tie the first section. Nullopt without roads.
  std::optional<RoadProjection> project(Vec2 position) const;

  /// The masks whose closed polygon holds `point`.
  std::vector<std::size_t> masksContaining(Vec2 point) const;

  /// Whether a mask of `kind` hides b from a (see segmentEntersPolygon).
  bool blockedBy(Vec2 a, Vec2 b, MaskKind kind) const;

  /// Optical line of sight: false when the segment a-b crosses or enters any mask. Buildings and
  /// vegetation both block it, since the paper's masks hide targets from cameras and PIR
  /// sensors; a sensor that sees through foliage (radar, acoustic) asks blockedBy(…, kBuilding).
  /// A segment of zero length is blocked only when its point is strictly inside a mask.
  bool lineOfSight(Vec2 a, Vec2 b) const;

 private:
  TerrainConfig config_;
  std::vector<RoadSection> sections_;
  std::vector<Junction> junctions_;
};

}  // namespace wsn::common

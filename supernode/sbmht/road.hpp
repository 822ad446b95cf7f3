// Roads as polylines for the road-constrained tracker (ONERA §III-B): the nearest point of a road
// to a position, the direction there, and the projection of a track's state onto the road.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "common/geometry.hpp"
#include "common/kalman.hpp"
#include "common/terrain.hpp"

namespace wsn::supernode::sbmht {

/// A road as its centre line: a polyline through at least two distinct points.
struct Road {
  std::vector<common::Vec2> points;
};

/// Where a position meets a road: the foot of the perpendicular on the nearest segment
/// (common/terrain.hpp computes it for every road of the scenario too).
using RoadFoot = common::PolylineFoot;

/// The foot point of `position` on the road's nearest segment; on a tie (outside a bend both
/// segments are nearest at their shared vertex) the first segment in the polyline's order.
/// Zero-length segments are skipped; nullopt when no segment is left.
inline std::optional<RoadFoot> footPoint(const Road& road, common::Vec2 position) {
  return common::footPoint(road.points, position);
}

/// The state moved onto the road at `foot` (docs/ONERA.md, check C8): the position to the foot point and the
/// velocity to its component along the segment, |v| cos(angle off the road), which reverses
/// the segment's direction for a target driving the other way.
///
/// Covariance: both moves are the linear map T = diag(u u', u u') (u the segment's direction)
/// about the foot point, so P becomes T P T', what Simon and Chia's estimate projection with
/// W = I gives, and nothing across the road is left. Then the road's own location error
/// (road_location_sigma, e.g. the GIS's metric precision) is added across the road on the position,
/// since the road is only known that well; the velocity stays exactly along the road.
common::GaussianState projectOntoRoad(const common::GaussianState& state, const RoadFoot& foot,
                                      double road_location_sigma);

/// The mean of projectOntoRoad (position to the foot point, velocity along the segment) with the
/// covariance left as it is: what a prediction needs to follow a bend without losing eq. 6's
/// across-road process noise, which the full projection would remove.
common::GaussianState moveOntoRoad(const common::GaussianState& state, const RoadFoot& foot);

/// The same at the state's own foot point on `road`; nullopt when the road has no segment.
std::optional<common::GaussianState> projectOntoRoad(const common::GaussianState& state, const Road& road,
                                                     double road_location_sigma);

}  // namespace wsn::supernode::sbmht

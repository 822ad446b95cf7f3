#include "supernode/sbmht/road.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wsn::supernode::sbmht {
namespace {

using common::kVx;
using common::kVy;
using common::kX;
using common::kY;
using common::StateMatrix;
using common::Vec2;

double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }

}  // namespace

double RoadFoot::heading() const { return std::atan2(direction.y, direction.x); }

std::optional<RoadFoot> footPoint(const Road& road, Vec2 position) {
  std::optional<RoadFoot> best;
  for (std::size_t i = 0; i + 1 < road.points.size(); ++i) {
    const Vec2 start = road.points[i];
    const Vec2 along = road.points[i + 1] - start;
    const double length = std::hypot(along.x, along.y);
    if (!(length > 0.0)) continue;
    const Vec2 direction = (1.0 / length) * along;
    const double t = std::clamp(dot(position - start, direction), 0.0, length);
    const Vec2 point = start + t * direction;
    const double distance = common::distance(position, point);
    if (!best || distance < best->distance) best = RoadFoot{i, point, direction, distance};
  }
  return best;
}

common::GaussianState projectOntoRoad(const common::GaussianState& state, const RoadFoot& foot,
                                      double road_location_sigma) {
  const Eigen::Vector2d u(foot.direction.x, foot.direction.y);
  const Eigen::Vector2d normal(-u.y(), u.x());
  const Eigen::Matrix2d onto_road = u * u.transpose();

  common::GaussianState out;
  out.x(kX) = foot.point.x;
  out.x(kY) = foot.point.y;
  const Eigen::Vector2d velocity = onto_road * Eigen::Vector2d(state.x(kVx), state.x(kVy));
  out.x(kVx) = velocity.x();
  out.x(kVy) = velocity.y();

  StateMatrix T = StateMatrix::Zero();
  T.block<2, 2>(kX, kX) = onto_road;
  T.block<2, 2>(kVx, kVx) = onto_road;
  StateMatrix P = T * state.P * T.transpose();
  P.block<2, 2>(kX, kX) += road_location_sigma * road_location_sigma * normal * normal.transpose();
  out.P = 0.5 * (P + P.transpose());
  return out;
}

std::optional<common::GaussianState> projectOntoRoad(const common::GaussianState& state, const Road& road,
                                                     double road_location_sigma) {
  const auto foot = footPoint(road, {state.x(kX), state.x(kY)});
  if (!foot) return std::nullopt;
  return projectOntoRoad(state, *foot, road_location_sigma);
}

}  // namespace wsn::supernode::sbmht

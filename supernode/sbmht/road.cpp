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

}  // namespace

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

common::GaussianState moveOntoRoad(const common::GaussianState& state, const RoadFoot& foot) {
  const Eigen::Vector2d u(foot.direction.x, foot.direction.y);
  const double along = u.dot(Eigen::Vector2d(state.x(kVx), state.x(kVy)));
  common::GaussianState out = state;
  out.x(kX) = foot.point.x;
  out.x(kY) = foot.point.y;
  out.x(kVx) = along * u.x();
  out.x(kVy) = along * u.y();
  return out;
}

std::optional<common::GaussianState> projectOntoRoad(const common::GaussianState& state, const Road& road,
                                                     double road_location_sigma) {
  const auto foot = footPoint(road, {state.x(kX), state.x(kY)});
  if (!foot) return std::nullopt;
  return projectOntoRoad(state, *foot, road_location_sigma);
}

}  // namespace wsn::supernode::sbmht

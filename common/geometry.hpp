// Plane geometry shared by every role: points, the rectangular surveillance region, and a
// uniform-cell spatial index for range queries over sensors.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace wsn::common {

/// A point or vector in the plane (units: sensor separations).
struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  friend Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
  friend Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
  friend Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
  friend bool operator==(Vec2, Vec2) = default;
};

inline double squaredDistance(Vec2 a, Vec2 b) {
  const double dx = a.x - b.x;
  const double dy = a.y - b.y;
  return dx * dx + dy * dy;
}
inline double distance(Vec2 a, Vec2 b) { return std::sqrt(squaredDistance(a, b)); }

/// An angle brought into (-pi, pi]: the one convention of every bearing a sensor reports and a
/// tracker predicts. remainder() lands in [-pi, pi]; -pi is the same direction as pi, and (-pi, pi]
/// keeps pi.
inline double wrapAngle(double angle) {
  const double wrapped = std::remainder(angle, 2.0 * std::numbers::pi);
  return wrapped <= -std::numbers::pi ? wrapped + 2.0 * std::numbers::pi : wrapped;
}

/// Axis-aligned rectangle [x_min, x_max] x [y_min, y_max].
struct Rect {
  double x_min = 0.0;
  double y_min = 0.0;
  double x_max = 0.0;
  double y_max = 0.0;
  double width() const { return x_max - x_min; }
  double height() const { return y_max - y_min; }
  double area() const { return width() * height(); }
  bool contains(Vec2 p) const { return p.x >= x_min && p.x <= x_max && p.y >= y_min && p.y <= y_max; }
  /// Half-open containment, so that tiles partition the region without double counting.
  bool containsHalfOpen(Vec2 p) const { return p.x >= x_min && p.x < x_max && p.y >= y_min && p.y < y_max; }
  friend bool operator==(const Rect&, const Rect&) = default;
  /// Distance from p to the rectangle (0 inside).
  double distanceTo(Vec2 p) const {
    const double dx = std::max({x_min - p.x, 0.0, p.x - x_max});
    const double dy = std::max({y_min - p.y, 0.0, p.y - y_max});
    return std::sqrt(dx * dx + dy * dy);
  }
};

}  // namespace wsn::common

#include "common/voronoi.hpp"

#include <algorithm>
#include <cmath>

namespace wsn::common {
namespace {

/// The part of a convex polygon where a.x * p.x + a.y * p.y <= b (Sutherland-Hodgman, one plane).
std::vector<Vec2> clip(const std::vector<Vec2>& polygon, Vec2 a, double b) {
  std::vector<Vec2> out;
  const auto side = [&](Vec2 p) { return a.x * p.x + a.y * p.y - b; };
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Vec2 p = polygon[k];
    const Vec2 q = polygon[(k + 1) % polygon.size()];
    const double sp = side(p);
    const double sq = side(q);
    if (sp <= 0.0) out.push_back(p);
    if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) out.push_back(p + (sp / (sp - sq)) * (q - p));
  }
  return out;
}

double segmentDistance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double length2 = ab.x * ab.x + ab.y * ab.y;
  const double s = length2 > 0.0 ? std::clamp(((p.x - a.x) * ab.x + (p.y - a.y) * ab.y) / length2, 0.0, 1.0) : 0.0;
  return distance(p, a + s * ab);
}

/// Distance between two convex polygons with disjoint interiors: a vertex of one to an edge of the other.
double polygonDistance(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  double best = INFINITY;
  for (int pass = 0; pass < 2; ++pass) {
    const auto& from = pass == 0 ? a : b;
    const auto& to = pass == 0 ? b : a;
    for (const Vec2 p : from)
      for (std::size_t k = 0; k < to.size(); ++k) best = std::min(best, segmentDistance(p, to[k], to[(k + 1) % to.size()]));
  }
  return best;
}

}  // namespace

std::vector<Vec2> voronoiCell(const std::vector<Vec2>& sites, const Rect& region, std::uint32_t i) {
  std::vector<Vec2> cell{{region.x_min, region.y_min}, {region.x_max, region.y_min},
                         {region.x_max, region.y_max}, {region.x_min, region.y_max}};
  for (std::uint32_t j = 0; j < sites.size() && !cell.empty(); ++j) {
    if (j == i || sites[j] == sites[i]) continue;
    // |p - s_i|^2 <= |p - s_j|^2  <=>  2 p . (s_j - s_i) <= |s_j|^2 - |s_i|^2
    const Vec2 a = 2.0 * (sites[j] - sites[i]);
    const double b = (sites[j].x * sites[j].x + sites[j].y * sites[j].y) - (sites[i].x * sites[i].x + sites[i].y * sites[i].y);
    cell = clip(cell, a, b);
  }
  return cell;
}

std::vector<std::vector<std::uint32_t>> voronoiNeighbours(const std::vector<Vec2>& sites, const Rect& region) {
  const auto n = static_cast<std::uint32_t>(sites.size());
  std::vector<std::vector<Vec2>> cells(n);
  for (std::uint32_t i = 0; i < n; ++i) cells[i] = voronoiCell(sites, region, i);
  const double tolerance = 1e-9 * (std::hypot(region.width(), region.height()) + 1.0);
  std::vector<std::vector<std::uint32_t>> neighbours(n);
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = i + 1; j < n; ++j) {
      if (cells[i].empty() || cells[j].empty()) continue;
      if (sites[i] == sites[j] || polygonDistance(cells[i], cells[j]) <= tolerance) {
        neighbours[i].push_back(j);
        neighbours[j].push_back(i);
      }
    }
  for (auto& list : neighbours) std::sort(list.begin(), list.end());
  return neighbours;
}

}  // namespace wsn::common

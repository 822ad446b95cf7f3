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

std::vector<std::uint32_t> voronoiNeighboursOf(const std::vector<Vec2>& sites, const Rect& region, std::uint32_t i) {
  // On cell i, |p - s_j|^2 - |p - s_i|^2 is linear in p and never negative, and it is zero where
  // the cells meet: cell j touches cell i iff it is zero (within the tolerance, as a distance to
  // the bisector) at a vertex of cell i. One clip per site, not a cell per site.
  const auto cell = voronoiCell(sites, region, i);
  std::vector<std::uint32_t> out;
  if (cell.empty()) return out;
  const double tolerance = 1e-9 * (std::hypot(region.width(), region.height()) + 1.0);
  for (std::uint32_t j = 0; j < sites.size(); ++j) {
    if (j == i) continue;
    const double separation = distance(sites[i], sites[j]);
    if (separation == 0.0) {  // twins share one cell
      out.push_back(j);
      continue;
    }
    for (const Vec2 v : cell)
      if ((squaredDistance(v, sites[j]) - squaredDistance(v, sites[i])) / (2.0 * separation) <= tolerance) {
        out.push_back(j);
        break;
      }
  }
  return out;
}

std::vector<std::vector<std::uint32_t>> voronoiNeighbours(const std::vector<Vec2>& sites, const Rect& region) {
  std::vector<std::vector<std::uint32_t>> neighbours(sites.size());
  for (std::uint32_t i = 0; i < sites.size(); ++i) neighbours[i] = voronoiNeighboursOf(sites, region, i);
  return neighbours;
}

}  // namespace wsn::common

// Pairs of points of two sets within a distance of each other, without looking at all pairs:
// the metrics of a city-scale run match thousands of truths against thousands of tracks, of
// which only the pairs within a cut-off can matter.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "common/geometry.hpp"

namespace wsn::common {

/// Calls visit(i, j) for every a[i], b[j] within `radius` of each other (each pair once, i
/// ascending and, within i, j ascending), in O((|a| + |b|) log |b| + pairs in the x strips):
/// b is sorted by x once and each a[i] scans the strip |x - a[i].x| <= radius. The test has a
/// margin of 1e-9 relative, so that a caller whose own distance rounds differently (hypot)
/// applies its exact criterion to a superset. Points with a non-finite coordinate are never
/// visited; an infinite radius visits every finite pair.
template <typename Visit>
void forEachPairWithin(std::span<const Vec2> a, std::span<const Vec2> b, double radius, Visit&& visit) {
  if (!(radius >= 0.0)) return;
  std::vector<std::pair<double, std::uint32_t>> by_x;
  by_x.reserve(b.size());
  for (std::uint32_t j = 0; j < b.size(); ++j)
    if (std::isfinite(b[j].x) && std::isfinite(b[j].y)) by_x.push_back({b[j].x, j});
  std::sort(by_x.begin(), by_x.end());
  const double reach = radius * (1.0 + 1e-9) + 1e-300;
  const double reach2 = reach * reach;
  std::vector<std::uint32_t> found;
  for (std::uint32_t i = 0; i < a.size(); ++i) {
    const Vec2 p = a[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    found.clear();
    auto it = std::lower_bound(by_x.begin(), by_x.end(), std::pair<double, std::uint32_t>{p.x - reach, 0});
    for (; it != by_x.end() && it->first <= p.x + reach; ++it)
      if (squaredDistance(p, b[it->second]) <= reach2) found.push_back(it->second);
    std::sort(found.begin(), found.end());
    for (const std::uint32_t j : found) visit(i, j);
  }
}

}  // namespace wsn::common

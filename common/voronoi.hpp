// Which tracking groups border each other: the Voronoi cells of the supernodes within the
// region, and the pairs of cells that touch. Handoffs travel between such neighbours only.
#pragma once

#include <cstdint>
#include <vector>

#include "common/geometry.hpp"

namespace wsn::common {

/// The cell of site i within `region`: the points of the region no farther from sites[i] than
/// from any other site, as a convex polygon (counter-clockwise; empty when the region has no such
/// point). Sites at the same position share one cell.
std::vector<Vec2> voronoiCell(const std::vector<Vec2>& sites, const Rect& region, std::uint32_t i);

/// The other sites whose cells touch site i's (a shared edge or a single corner, within 1e-9 of the
/// region's diagonal), ascending: i's edges of the Delaunay graph of the sites, clipped to the
/// region. Empty when i's cell misses the region. O(n) clips and O(n) vertex tests.
std::vector<std::uint32_t> voronoiNeighboursOf(const std::vector<Vec2>& sites, const Rect& region, std::uint32_t i);

/// voronoiNeighboursOf() of every site (symmetric).
std::vector<std::vector<std::uint32_t>> voronoiNeighbours(const std::vector<Vec2>& sites, const Rect& region);

}  // namespace wsn::common

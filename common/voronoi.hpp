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

/// For each site, the other sites whose cells touch its own (a shared edge or a single corner,
/// within 1e-9 of the region's diagonal), ascending: the Delaunay graph of the sites, clipped to
/// the region. Symmetric. O(n^2) clips and O(n^2) polygon distances: milliseconds at 1,000 sites.
std::vector<std::vector<std::uint32_t>> voronoiNeighbours(const std::vector<Vec2>& sites, const Rect& region);

}  // namespace wsn::common

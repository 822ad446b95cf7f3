#include "supernode/rulebased/clustering.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace wsn::supernode::rulebased {
namespace {

/// Union-find over detection indices; the root of a set is its smallest index, which keeps
/// the cluster order independent of the order in which links are found.
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::size_t{0}); }
  std::size_t find(std::size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

std::int64_t cellKey(std::int64_t cx, std::int64_t cy) { return (cx << 32) ^ (cy & 0xffffffff); }

}  // namespace

double clusterRadius(std::int32_t sensors, double sensor_spacing) {
  return std::sqrt(static_cast<double>(sensors)) * sensor_spacing / 2.0;
}

std::vector<Cluster> clusterDetections(std::span<const Detection> detections, double link_distance,
                                       double sensor_spacing) {
  std::vector<Detection> unique(detections.begin(), detections.end());
  std::stable_sort(unique.begin(), unique.end(),
                   [](const Detection& a, const Detection& b) { return a.sensor < b.sensor; });
  unique.erase(std::unique(unique.begin(), unique.end(),
                           [](const Detection& a, const Detection& b) { return a.sensor == b.sensor; }),
               unique.end());

  // Cells of side link_distance: linked sensors lie in the same or an adjacent cell, so each
  // detection is compared with O(1) others instead of all of them.
  const double cell = std::max(link_distance, 1e-9);
  const auto cellOf = [&](common::Vec2 p) {
    return std::pair{static_cast<std::int64_t>(std::floor(p.x / cell)), static_cast<std::int64_t>(std::floor(p.y / cell))};
  };
  std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;
  for (std::size_t i = 0; i < unique.size(); ++i) {
    const auto [cx, cy] = cellOf(unique[i].position);
    grid[cellKey(cx, cy)].push_back(i);
  }
  DisjointSets sets(unique.size());
  const double link_squared = link_distance * link_distance;
  for (std::size_t i = 0; i < unique.size(); ++i) {
    const auto [cx, cy] = cellOf(unique[i].position);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = grid.find(cellKey(cx + dx, cy + dy));
        if (it == grid.end()) continue;
        for (const std::size_t j : it->second)
          if (j > i && common::squaredDistance(unique[i].position, unique[j].position) <= link_squared)
            sets.unite(i, j);
      }
  }

  // Roots are smallest indices, i.e. smallest sensor ids: visiting in index order numbers the
  // clusters by their first sensor.
  std::vector<Cluster> clusters;
  std::vector<std::size_t> cluster_of_root(unique.size(), SIZE_MAX);
  for (std::size_t i = 0; i < unique.size(); ++i) {
    const std::size_t root = sets.find(i);
    if (cluster_of_root[root] == SIZE_MAX) {
      cluster_of_root[root] = clusters.size();
      clusters.emplace_back();
    }
    clusters[cluster_of_root[root]].members.push_back(unique[i]);
  }
  for (auto& c : clusters) {
    double weight = 0.0;
    common::Vec2 sum;
    const Detection* strongest = &c.members.front();
    for (const auto& d : c.members) {
      const double w = centroidWeight(d);
      weight += w;
      sum = sum + w * d.position;
      if (d.level > strongest->level) strongest = &d;  // ties: the smaller id, met first
    }
    c.centroid = (1.0 / weight) * sum;
    c.strongest = strongest->position;
    c.radius = clusterRadius(c.size(), sensor_spacing);
  }
  return clusters;
}

}  // namespace wsn::supernode::rulebased

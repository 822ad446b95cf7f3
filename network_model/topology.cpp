#include "network_model/topology.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace wsn::network_model {
namespace {

using common::Vec2;

/// A node of G inside the cell index, with its position inline so that scans stay sequential.
struct CellEntry {
  double x = 0.0;
  double y = 0.0;
  std::uint32_t node = 0;
};

/// Uniform cells of side >= range, so that every neighbour of a node lies in the 3 x 3 cells
/// around it. Nodes are stored cell by cell (CSR layout).
class CellIndex {
 public:
  CellIndex(std::span<const Vec2> nodes, double range) {
    double x_min = std::numeric_limits<double>::infinity();
    double y_min = x_min;
    double x_max = -x_min;
    double y_max = -x_min;
    for (const Vec2& p : nodes) {
      x_min = std::min(x_min, p.x);
      y_min = std::min(y_min, p.y);
      x_max = std::max(x_max, p.x);
      y_max = std::max(y_max, p.y);
    }
    origin_ = {x_min, y_min};
    // Cap the number of cells near 4 per node so that a tiny range on a large field cannot
    // exhaust memory; larger cells only cost more distance checks.
    const double extent = std::max({x_max - x_min, y_max - y_min, 1e-9});
    const double max_cells_per_side = std::ceil(2.0 * std::sqrt(static_cast<double>(nodes.size()))) + 1.0;
    cell_size_ = std::max({range, extent / max_cells_per_side, 1e-9});
    columns_ = static_cast<std::int32_t>(std::floor((x_max - x_min) / cell_size_)) + 1;
    rows_ = static_cast<std::int32_t>(std::floor((y_max - y_min) / cell_size_)) + 1;

    const auto cells = static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_);
    start_.assign(cells + 1, 0);
    std::vector<std::uint32_t> cell_of(nodes.size());
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
      cell_of[n] = cellOf(nodes[n]);
      ++start_[cell_of[n] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
    entries_.resize(nodes.size());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    // Ascending node order within each cell keeps the layout a pure function of the input.
    for (std::uint32_t n = 0; n < nodes.size(); ++n) entries_[fill[cell_of[n]]++] = {nodes[n].x, nodes[n].y, n};
  }

  std::uint32_t cellOf(Vec2 p) const {
    const auto c = std::clamp(static_cast<std::int32_t>(std::floor((p.x - origin_.x) / cell_size_)), 0, columns_ - 1);
    const auto r = std::clamp(static_cast<std::int32_t>(std::floor((p.y - origin_.y) / cell_size_)), 0, rows_ - 1);
    return static_cast<std::uint32_t>(r * columns_ + c);
  }
  std::int32_t columns() const { return columns_; }
  std::int32_t rows() const { return rows_; }
  std::size_t cellCount() const { return start_.size() - 1; }
  std::uint32_t begin(std::uint32_t cell) const { return start_[cell]; }
  std::uint32_t size(std::uint32_t cell) const { return start_[cell + 1] - start_[cell]; }
  const std::vector<CellEntry>& entries() const { return entries_; }
  /// Distance from p to the closed rectangle of cell (column c, row r).
  double distanceToCell(Vec2 p, std::int32_t c, std::int32_t r) const {
    const common::Rect rect{origin_.x + c * cell_size_, origin_.y + r * cell_size_,
                            origin_.x + (c + 1) * cell_size_, origin_.y + (r + 1) * cell_size_};
    return rect.distanceTo(p);
  }

 private:
  Vec2 origin_;
  double cell_size_ = 1.0;
  std::int32_t columns_ = 1;
  std::int32_t rows_ = 1;
  std::vector<std::uint32_t> start_;
  std::vector<CellEntry> entries_;
};

/// Breadth-first search in G over the cell index. A visited node is swap-removed from its
/// cell's working copy, so it is never examined again: a search is close to linear in the
/// nodes it reaches rather than in the edges of G (up to ~400 per node at Oh's density and
/// range). Working copies are made lazily, the first time a round touches a cell, and
/// removals persist across the searches of one round.
class BreadthFirst {
 public:
  BreadthFirst(const CellIndex& index, const std::vector<Vec2>& nodes, double range)
      : index_(index),
        nodes_(nodes),
        range_(range),
        range2_(range * range),
        work_(index.entries().size()),
        live_(index.cellCount(), 0),
        stamp_(index.cellCount(), 0) {
    queue_.reserve(nodes.size());
  }

  /// Starts a round: every node is unvisited again.
  void startRound() { ++round_; }

  /// Visits the nodes reachable from `source` that no earlier search of this round visited,
  /// calling visit(node, level) in BFS order (level = hops from source); stops early when
  /// visit returns false.
  template <typename Visit>
  void run(std::uint32_t source, Visit&& visit) {
    remove(source);
    queue_.clear();
    queue_.push_back({source, 0});
    for (std::size_t head = 0; head < queue_.size(); ++head) {
      const auto [u, level] = queue_[head];
      const Vec2 pu = nodes_[u];
      const std::uint32_t cu = index_.cellOf(pu);
      const auto columns = static_cast<std::uint32_t>(index_.columns());
      const auto cx = static_cast<std::int32_t>(cu % columns);
      const auto cy = static_cast<std::int32_t>(cu / columns);
      for (std::int32_t r = std::max(cy - 1, 0); r <= std::min(cy + 1, index_.rows() - 1); ++r) {
        for (std::int32_t c = std::max(cx - 1, 0); c <= std::min(cx + 1, index_.columns() - 1); ++c) {
          if (index_.distanceToCell(pu, c, r) > range_) continue;
          const auto cell = static_cast<std::uint32_t>(r * index_.columns() + c);
          touch(cell);
          const std::uint32_t b = index_.begin(cell);
          std::uint32_t n = live_[cell];
          for (std::uint32_t k = 0; k < n;) {
            const CellEntry e = work_[b + k];
            const double dx = e.x - pu.x;
            const double dy = e.y - pu.y;
            if (dx * dx + dy * dy > range2_) {
              ++k;
              continue;
            }
            work_[b + k] = work_[b + n - 1];
            --n;
            queue_.push_back({e.node, level + 1});
            if (!visit(e.node, level + 1)) {
              live_[cell] = n;
              return;
            }
          }
          live_[cell] = n;
        }
      }
    }
  }

 private:
  struct QueueItem {
    std::uint32_t node;
    std::int32_t level;
  };

  void touch(std::uint32_t cell) {
    if (stamp_[cell] == round_) return;
    stamp_[cell] = round_;
    const std::uint32_t b = index_.begin(cell);
    std::copy_n(index_.entries().begin() + b, index_.size(cell), work_.begin() + b);
    live_[cell] = index_.size(cell);
  }

  void remove(std::uint32_t node) {
    const std::uint32_t cell = index_.cellOf(nodes_[node]);
    touch(cell);
    const std::uint32_t b = index_.begin(cell);
    for (std::uint32_t k = 0; k < live_[cell]; ++k)
      if (work_[b + k].node == node) {
        work_[b + k] = work_[b + live_[cell] - 1];
        --live_[cell];
        return;
      }
  }

  const CellIndex& index_;
  const std::vector<Vec2>& nodes_;
  double range_;
  double range2_;
  std::vector<CellEntry> work_;
  std::vector<std::uint32_t> live_;
  std::vector<std::uint32_t> stamp_;
  std::vector<QueueItem> queue_;
  std::uint32_t round_ = 0;
};

}  // namespace

Topology::Topology(const TopologyConfig& config, std::span<const Vec2> sensors)
    : supernodes_(config.supernodes), range_(config.communication_range) {
  for (std::uint32_t j = 0; j < supernodes_.size(); ++j)
    if (config.live_supernodes.empty() || (j < config.live_supernodes.size() && config.live_supernodes[j])) live_.push_back(j);
  build(sensors);
}

double Topology::meanHops() const {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t k = 1; k < histogram_.size(); ++k) {
    sum += static_cast<double>(k) * static_cast<double>(histogram_[k]);
    count += histogram_[k];
  }
  return count == 0 ? 0.0 : sum / static_cast<double>(count);
}

void Topology::build(std::span<const Vec2> sensors) {
  if (supernodes_.empty()) throw std::invalid_argument("network topology: the scenario has no supernodes");
  if (live_.empty()) throw std::invalid_argument("network topology: no supernode is live");
  if (sensors.size() + supernodes_.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("network topology: too many sensors");
  const auto sensor_count = static_cast<std::uint32_t>(sensors.size());
  const auto supernode_count = static_cast<std::uint32_t>(supernodes_.size());

  // Oh et al. §V: g(i) = argmin_j |s_i - ss_j| over the live supernodes; the strict comparison
  // keeps the lowest index.
  supernode_of_.assign(sensor_count, live_.front());
  group_size_.assign(supernode_count, 0);
  for (std::uint32_t i = 0; i < sensor_count; ++i) {
    double best = common::squaredDistance(sensors[i], supernodes_[live_.front()]);
    for (const std::uint32_t j : live_) {
      const double d2 = common::squaredDistance(sensors[i], supernodes_[j]);
      if (d2 < best) {
        best = d2;
        supernode_of_[i] = j;
      }
    }
    ++group_size_[supernode_of_[i]];
  }

  hops_.assign(sensor_count, -1);
  // A negative or NaN range gives G no edges at all.
  if (range_ >= 0.0 && sensor_count > 0) {
    // Nodes of G: sensors are 0 .. n-1, the k-th live supernode is n + k.
    std::vector<Vec2> nodes(sensors.begin(), sensors.end());
    std::vector<std::uint32_t> node_of_supernode(supernode_count, 0);
    for (const std::uint32_t j : live_) {
      node_of_supernode[j] = static_cast<std::uint32_t>(nodes.size());
      nodes.push_back(supernodes_[j]);
    }
    const CellIndex index(nodes, range_);
    BreadthFirst search(index, nodes, range_);

    // Connected components first, so that each supernode's BFS below knows how many members
    // of its group it can reach and stops as soon as it has found them all, instead of
    // flooding the whole component whenever one member is cut off.
    constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> component(nodes.size(), kNone);
    search.startRound();
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
      if (component[n] != kNone) continue;
      component[n] = n;
      search.run(n, [&](std::uint32_t v, std::int32_t) {
        component[v] = n;
        return true;
      });
    }

    std::vector<std::size_t> reachable_members(supernode_count, 0);
    for (std::uint32_t i = 0; i < sensor_count; ++i)
      if (component[i] == component[node_of_supernode[supernode_of_[i]]]) ++reachable_members[supernode_of_[i]];

    for (const std::uint32_t j : live_) {
      const std::uint32_t source = node_of_supernode[j];
      std::size_t remaining = reachable_members[j];
      if (remaining == 0) continue;
      search.startRound();
      search.run(source, [&](std::uint32_t v, std::int32_t level) {
        if (v < sensor_count && supernode_of_[v] == j) {
          hops_[v] = level;
          --remaining;
        }
        return remaining > 0;
      });
    }
  }

  unreachable_ = 0;
  histogram_.assign(1, 0);
  for (const std::int32_t k : hops_) {
    if (k < 0) {
      ++unreachable_;
      continue;
    }
    const auto index = static_cast<std::size_t>(k);
    if (index >= histogram_.size()) histogram_.resize(index + 1, 0);
    ++histogram_[index];
  }
}

}  // namespace wsn::network_model

#include "common/assignment.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace wsn::common {
namespace {

/// Shortest augmenting paths with potentials (e-maxx formulation, 1-based internally) on an
/// n_rows x n_cols problem with n_rows <= n_cols and every entry finite: each row is matched.
/// Returns, for each column, its row (1-based) or 0. O(n_rows^2 n_cols) at worst; on geometric
/// costs a row's path usually ends after a few columns, so close to O(n_rows n_cols).
template <typename At>
std::vector<std::size_t> augmentingPaths(std::size_t n_rows, std::size_t n_cols, At at) {
  std::vector<double> u(n_rows + 1, 0.0), v(n_cols + 1, 0.0), min_to(n_cols + 1);
  std::vector<std::size_t> match_of_column(n_cols + 1, 0), way(n_cols + 1, 0);
  std::vector<char> used(n_cols + 1);
  for (std::size_t i = 1; i <= n_rows; ++i) {
    match_of_column[0] = i;
    std::size_t j0 = 0;
    std::fill(min_to.begin(), min_to.end(), std::numeric_limits<double>::infinity());
    std::fill(used.begin(), used.end(), 0);
    do {
      used[j0] = 1;
      const std::size_t i0 = match_of_column[j0];
      double delta = std::numeric_limits<double>::infinity();
      std::size_t j1 = 0;
      for (std::size_t j = 1; j <= n_cols; ++j) {
        if (used[j]) continue;
        const double reduced = at(i0 - 1, j - 1) - u[i0] - v[j];
        if (reduced < min_to[j]) {
          min_to[j] = reduced;
          way[j] = j0;
        }
        if (min_to[j] < delta) {
          delta = min_to[j];
          j1 = j;
        }
      }
      for (std::size_t j = 0; j <= n_cols; ++j) {
        if (used[j]) {
          u[match_of_column[j]] += delta;
          v[j] -= delta;
        } else {
          min_to[j] -= delta;
        }
      }
      j0 = j1;
    } while (match_of_column[j0] != 0);
    do {
      const std::size_t j1 = way[j0];
      match_of_column[j0] = match_of_column[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  return match_of_column;
}

/// Dense solve of one cluster: `cost` is rows x cols, row-major, non-finite entries forbidden;
/// each row may take a private "unassigned" column at `miss_cost`.
std::vector<int> solveDense(const std::vector<double>& cost, std::size_t rows, std::size_t cols, double miss_cost) {
  std::vector<int> result(rows, -1);
  if (rows == 0 || cols == 0) return result;
  double finite_sum = std::abs(miss_cost);
  for (double c : cost)
    if (std::isfinite(c)) finite_sum += std::abs(c);
  const double forbidden_cost = 4.0 * finite_sum + 4.0;  // above any sum of allowed costs
  const std::size_t n = rows + cols;  // columns: real ones, then one dummy per row; rows: real, then fillers
  const auto match_of_column = augmentingPaths(n, n, [&](std::size_t r, std::size_t c) -> double {
    if (r < rows && c < cols) {
      const double v = cost[r * cols + c];
      return std::isfinite(v) ? v : forbidden_cost;
    }
    if (r < rows) return (c - cols == r) ? miss_cost : forbidden_cost;  // row's own dummy
    return 0.0;  // filler rows absorb unused columns for free
  });
  for (std::size_t j = 1; j <= cols; ++j) {
    const std::size_t r = match_of_column[j];
    if (r >= 1 && r <= rows && std::isfinite(cost[(r - 1) * cols + (j - 1)])) result[r - 1] = static_cast<int>(j - 1);
  }
  return result;
}

/// Every pair allowed and the most rows assigned: min(rows, cols) pairs, so no padding is needed
/// (the smaller side is matched completely; the larger is transposed to the columns).
std::vector<int> solveComplete(const std::vector<double>& cost, std::size_t rows, std::size_t cols) {
  std::vector<int> result(rows, -1);
  if (rows <= cols) {
    const auto match_of_column = augmentingPaths(rows, cols, [&](std::size_t r, std::size_t c) { return cost[r * cols + c]; });
    for (std::size_t j = 1; j <= cols; ++j)
      if (match_of_column[j] != 0) result[match_of_column[j] - 1] = static_cast<int>(j - 1);
  } else {
    const auto row_of = augmentingPaths(cols, rows, [&](std::size_t c, std::size_t r) { return cost[r * cols + c]; });
    for (std::size_t r = 1; r <= rows; ++r)
      if (row_of[r] != 0) result[r - 1] = static_cast<int>(row_of[r] - 1);
  }
  return result;
}

/// Splits the problem into the connected clusters of its allowed pairs and solves each densely;
/// `miss_cost_of(cluster_cost)` gives a cluster's cost of an unassigned row, and without
/// `allow_misses` the most rows are assigned. Non-finite pairs are left out.
template <typename MissCost>
std::vector<int> solveByClusters(std::size_t rows, std::size_t cols, std::span<const AssignmentPair> pairs,
                                 bool allow_misses, MissCost miss_cost_of) {
  std::vector<int> result(rows, -1);
  if (rows == 0 || cols == 0) return result;
  // Union-find over rows (0..rows-1) and columns (rows..rows+cols-1).
  std::vector<std::size_t> parent(rows + cols);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto find = [&](std::size_t k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  for (const auto& pair : pairs) {
    if (pair.row >= rows || pair.col >= cols)
      throw std::invalid_argument("assignment: pair (" + std::to_string(pair.row) + ", " + std::to_string(pair.col) +
                                  ") outside a " + std::to_string(rows) + " x " + std::to_string(cols) + " problem");
    if (!std::isfinite(pair.cost)) continue;
    const std::size_t a = find(pair.row);
    const std::size_t b = find(rows + pair.col);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  // Members of each cluster in their original order; a cluster is named by its smallest member.
  std::vector<std::uint32_t> cluster_of(rows + cols);
  std::vector<std::uint32_t> position(rows + cols);  // index of a row / column inside its cluster
  std::vector<std::vector<std::size_t>> cluster_rows, cluster_cols;
  std::vector<std::uint32_t> cluster_named(rows + cols, std::numeric_limits<std::uint32_t>::max());
  for (std::size_t k = 0; k < rows + cols; ++k) {
    const std::size_t root = find(k);
    if (cluster_named[root] == std::numeric_limits<std::uint32_t>::max()) {
      cluster_named[root] = static_cast<std::uint32_t>(cluster_rows.size());
      cluster_rows.emplace_back();
      cluster_cols.emplace_back();
    }
    const std::uint32_t c = cluster_of[k] = cluster_named[root];
    auto& members = k < rows ? cluster_rows[c] : cluster_cols[c];
    position[k] = static_cast<std::uint32_t>(members.size());
    members.push_back(k < rows ? k : k - rows);
  }
  std::vector<std::vector<double>> local(cluster_rows.size());
  for (std::size_t c = 0; c < cluster_rows.size(); ++c)
    if (!cluster_rows[c].empty() && !cluster_cols[c].empty())
      local[c].assign(cluster_rows[c].size() * cluster_cols[c].size(), kForbidden);
  for (const auto& pair : pairs) {
    if (!std::isfinite(pair.cost)) continue;
    const std::uint32_t c = cluster_of[pair.row];
    double& entry = local[c][position[pair.row] * cluster_cols[c].size() + position[rows + pair.col]];
    entry = std::isfinite(entry) ? std::min(entry, pair.cost) : pair.cost;
  }
  for (std::size_t c = 0; c < cluster_rows.size(); ++c) {
    const auto& rs = cluster_rows[c];
    const auto& cs = cluster_cols[c];
    if (rs.empty() || cs.empty()) continue;
    const bool complete = std::all_of(local[c].begin(), local[c].end(), [](double v) { return std::isfinite(v); });
    const auto solution = complete && !allow_misses ? solveComplete(local[c], rs.size(), cs.size())
                                                    : solveDense(local[c], rs.size(), cs.size(), miss_cost_of(local[c]));
    for (std::size_t i = 0; i < rs.size(); ++i)
      if (solution[i] >= 0) result[rs[i]] = static_cast<int>(cs[static_cast<std::size_t>(solution[i])]);
  }
  return result;
}

/// Above any sum of a cluster's finite costs: assigning one more row always pays.
double lexicographicMissCost(const std::vector<double>& local) {
  double finite_sum = 0.0;
  for (double c : local)
    if (std::isfinite(c)) finite_sum += std::abs(c);
  return 2.0 * finite_sum + 1.0;
}

/// The allowed pairs of a row-major matrix (those `keep` accepts).
template <typename Keep>
std::vector<AssignmentPair> pairsOf(const std::vector<double>& cost, std::size_t rows, std::size_t cols, Keep keep) {
  if (cost.size() != rows * cols)
    throw std::invalid_argument("assignment: a cost matrix of " + std::to_string(cost.size()) + " entries for " +
                                std::to_string(rows) + " x " + std::to_string(cols));
  std::vector<AssignmentPair> pairs;
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < cols; ++c)
      if (keep(cost[r * cols + c]))
        pairs.push_back({static_cast<std::uint32_t>(r), static_cast<std::uint32_t>(c), cost[r * cols + c]});
  return pairs;
}

/// Pairs that can take part in a solution with misses at `miss_cost`.
std::vector<AssignmentPair> cheaperThan(std::span<const AssignmentPair> pairs, double miss_cost) {
  if (!std::isfinite(miss_cost)) throw std::invalid_argument("assignment: the miss cost must be finite");
  std::vector<AssignmentPair> kept;
  for (const auto& pair : pairs)
    if (std::isfinite(pair.cost) && pair.cost < miss_cost) kept.push_back(pair);
  return kept;
}

}  // namespace

std::vector<int> solveAssignment(const std::vector<double>& cost, std::size_t rows, std::size_t cols) {
  // Every pair allowed: one cluster of everything, whose matrix is `cost` itself (eq. 10's
  // matching of a thousand truths against the tracks, where listing two million pairs took longer
  // than the solve).
  if (cost.size() == rows * cols && std::all_of(cost.begin(), cost.end(), [](double v) { return std::isfinite(v); }))
    return solveComplete(cost, rows, cols);
  const auto pairs = pairsOf(cost, rows, cols, [](double v) { return std::isfinite(v); });
  return solveByClusters(rows, cols, pairs, false, lexicographicMissCost);
}

std::vector<int> solveAssignmentWithMissCost(const std::vector<double>& cost, std::size_t rows, std::size_t cols,
                                             double miss_cost) {
  if (!std::isfinite(miss_cost)) throw std::invalid_argument("assignment: the miss cost must be finite");
  const auto pairs = pairsOf(cost, rows, cols, [miss_cost](double v) { return std::isfinite(v) && v < miss_cost; });
  return solveByClusters(rows, cols, pairs, true, [miss_cost](const std::vector<double>&) { return miss_cost; });
}

std::vector<int> solveSparseAssignment(std::size_t rows, std::size_t cols, std::span<const AssignmentPair> pairs) {
  return solveByClusters(rows, cols, pairs, false, lexicographicMissCost);
}

std::vector<int> solveSparseAssignmentWithMissCost(std::size_t rows, std::size_t cols,
                                                   std::span<const AssignmentPair> pairs, double miss_cost) {
  const auto kept = cheaperThan(pairs, miss_cost);
  return solveByClusters(rows, cols, kept, true, [miss_cost](const std::vector<double>&) { return miss_cost; });
}

}  // namespace wsn::common

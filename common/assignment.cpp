#include "common/assignment.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

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

/// Splits the problem into the connected clusters of its allowed pairs (`allowed(r, c)`) and
/// solves each densely; `miss_cost_of(cluster_cost)` gives a cluster's cost of an unassigned row,
/// and without `allow_misses` the most rows are assigned.
template <typename Allowed, typename MissCost>
std::vector<int> solveByClusters(const std::vector<double>& cost, std::size_t rows, std::size_t cols, bool allow_misses,
                                 Allowed allowed, MissCost miss_cost_of) {
  std::vector<int> result(rows, -1);
  if (rows == 0 || cols == 0) return result;
  // Union-find over rows (0..rows-1) and columns (rows..rows+cols-1).
  std::vector<std::size_t> parent(rows + cols);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto find = [&](std::size_t k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < cols; ++c) {
      if (!allowed(r, c)) continue;
      const std::size_t a = find(r);
      const std::size_t b = find(rows + c);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  // Members of each cluster in their original order; a cluster is named by its smallest member.
  std::vector<std::vector<std::size_t>> cluster_rows(rows + cols);
  std::vector<std::vector<std::size_t>> cluster_cols(rows + cols);
  for (std::size_t r = 0; r < rows; ++r) cluster_rows[find(r)].push_back(r);
  for (std::size_t c = 0; c < cols; ++c) cluster_cols[find(rows + c)].push_back(c);
  std::vector<double> local;
  for (std::size_t k = 0; k < rows + cols; ++k) {
    const auto& rs = cluster_rows[k];
    const auto& cs = cluster_cols[k];
    if (rs.empty() || cs.empty()) continue;
    local.assign(rs.size() * cs.size(), kForbidden);
    for (std::size_t i = 0; i < rs.size(); ++i)
      for (std::size_t j = 0; j < cs.size(); ++j)
        if (allowed(rs[i], cs[j])) local[i * cs.size() + j] = cost[rs[i] * cols + cs[j]];
    const bool complete = std::all_of(local.begin(), local.end(), [](double v) { return std::isfinite(v); });
    const auto solution = complete && !allow_misses ? solveComplete(local, rs.size(), cs.size())
                                                    : solveDense(local, rs.size(), cs.size(), miss_cost_of(local));
    for (std::size_t i = 0; i < rs.size(); ++i)
      if (solution[i] >= 0) result[rs[i]] = static_cast<int>(cs[static_cast<std::size_t>(solution[i])]);
  }
  return result;
}

}  // namespace

std::vector<int> solveAssignment(const std::vector<double>& cost, std::size_t rows, std::size_t cols) {
  return solveByClusters(
      cost, rows, cols, false, [&](std::size_t r, std::size_t c) { return std::isfinite(cost[r * cols + c]); },
      [](const std::vector<double>& local) {
        // Above any sum of the cluster's finite costs: assigning one more row always pays.
        double finite_sum = 0.0;
        for (double c : local)
          if (std::isfinite(c)) finite_sum += std::abs(c);
        return 2.0 * finite_sum + 1.0;
      });
}

std::vector<int> solveAssignmentWithMissCost(const std::vector<double>& cost, std::size_t rows, std::size_t cols,
                                             double miss_cost) {
  if (!std::isfinite(miss_cost)) throw std::invalid_argument("solveAssignmentWithMissCost: miss_cost must be finite");
  return solveByClusters(
      cost, rows, cols, true,
      [&](std::size_t r, std::size_t c) {
        const double v = cost[r * cols + c];
        return std::isfinite(v) && v < miss_cost;
      },
      [miss_cost](const std::vector<double>&) { return miss_cost; });
}

}  // namespace wsn::common

#include "common/assignment.hpp"

#include <algorithm>
#include <cmath>

namespace wsn::common {

std::vector<int> solveAssignment(const std::vector<double>& cost, std::size_t rows, std::size_t cols) {
  std::vector<int> result(rows, -1);
  if (rows == 0 || cols == 0) return result;

  // Pad to a square matrix in which every row may also take a private "unassigned" column at a
  // cost above any sum of finite costs, so forbidden pairs are avoided whenever possible and a
  // row left without a finite partner simply stays unassigned.
  double finite_sum = 0.0;
  for (double c : cost)
    if (std::isfinite(c)) finite_sum += std::abs(c);
  const double dummy_cost = 2.0 * finite_sum + 1.0;
  const double forbidden_cost = 4.0 * finite_sum + 4.0;
  const std::size_t n = rows + cols;  // columns: real ones, then one dummy per row; rows: real, then fillers
  auto at = [&](std::size_t r, std::size_t c) -> double {
    if (r < rows && c < cols) {
      const double v = cost[r * cols + c];
      return std::isfinite(v) ? v : forbidden_cost;
    }
    if (r < rows) return (c - cols == r) ? dummy_cost : forbidden_cost;  // row's own dummy
    return 0.0;  // filler rows absorb unused columns for free
  };

  // Shortest augmenting path with potentials (e-maxx formulation, 1-based internally).
  std::vector<double> u(n + 1, 0.0), v(n + 1, 0.0), min_to(n + 1);
  std::vector<std::size_t> match_of_column(n + 1, 0), way(n + 1, 0);
  std::vector<char> used(n + 1);
  for (std::size_t i = 1; i <= n; ++i) {
    match_of_column[0] = i;
    std::size_t j0 = 0;
    std::fill(min_to.begin(), min_to.end(), std::numeric_limits<double>::infinity());
    std::fill(used.begin(), used.end(), 0);
    do {
      used[j0] = 1;
      const std::size_t i0 = match_of_column[j0];
      double delta = std::numeric_limits<double>::infinity();
      std::size_t j1 = 0;
      for (std::size_t j = 1; j <= n; ++j) {
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
      for (std::size_t j = 0; j <= n; ++j) {
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

  for (std::size_t j = 1; j <= cols; ++j) {
    const std::size_t r = match_of_column[j];
    if (r >= 1 && r <= rows && std::isfinite(cost[(r - 1) * cols + (j - 1)])) result[r - 1] = static_cast<int>(j - 1);
  }
  return result;
}

}  // namespace wsn::common

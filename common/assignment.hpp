// Optimal rectangular assignment (minimum total cost), shared by the GNN tracker, track
// fusion and the metrics' true-to-estimated matching.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace wsn::common {

/// Cost of a pair that must never be assigned.
inline constexpr double kForbidden = std::numeric_limits<double>::infinity();

/// Minimum-cost assignment of rows to columns of a rows x cols row-major cost matrix, by
/// shortest augmenting paths (Jonker-Volgenant style Hungarian method). Pairs whose cost is
/// kForbidden (or not finite) are never assigned; a row may stay unassigned. The optimum is
/// lexicographic: the most rows assigned, then the least total cost. Returns, for each row, its
/// column or -1. Ties are broken deterministically.
///
/// Rows and columns that share no allowed pair cannot compete, so each connected cluster of the
/// allowed pairs is solved on its own: O(rows x cols) to find the clusters plus O(k^3) per
/// cluster of k rows and columns, instead of O((rows + cols)^3) — the difference between
/// milliseconds and minutes for the metrics of a thousand targets.
std::vector<int> solveAssignment(const std::vector<double>& cost, std::size_t rows, std::size_t cols);

/// Minimum-cost partial assignment in which each row may also stay unassigned at `miss_cost`
/// (finite): minimises the sum of the assigned pairs' costs plus miss_cost per unassigned row.
/// This is OSPA's and GOSPA's matching with cut-off c and miss_cost = c^p: a pair costing
/// miss_cost or more is never better than leaving its row out, so it is treated as forbidden and
/// the problem splits into clusters as above. Returns, for each row, its column or -1.
std::vector<int> solveAssignmentWithMissCost(const std::vector<double>& cost, std::size_t rows, std::size_t cols,
                                             double miss_cost);

/// An allowed pair of a sparse problem: row, column and the cost of assigning them.
struct AssignmentPair {
  std::uint32_t row = 0;
  std::uint32_t col = 0;
  double cost = 0.0;
};

/// solveAssignment() on a problem given by its allowed pairs (every other pair forbidden), for
/// problems too large for a matrix: a city's truths against its tracks. Pairs may come in any
/// order; a repeated pair keeps its cheapest cost.
std::vector<int> solveSparseAssignment(std::size_t rows, std::size_t cols, std::span<const AssignmentPair> pairs);

/// solveAssignmentWithMissCost() on a problem given by its allowed pairs.
std::vector<int> solveSparseAssignmentWithMissCost(std::size_t rows, std::size_t cols,
                                                   std::span<const AssignmentPair> pairs, double miss_cost);

}  // namespace wsn::common

// Optimal rectangular assignment (minimum total cost), shared by the GNN tracker, track
// fusion and the metrics' true-to-estimated matching.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

namespace wsn::common {

/// Cost of a pair that must never be assigned.
inline constexpr double kForbidden = std::numeric_limits<double>::infinity();

/// Minimum-cost assignment of rows to columns of a rows x cols row-major cost matrix, by
/// shortest augmenting paths (Jonker-Volgenant style Hungarian method, O(n^3)). Pairs whose
/// cost is kForbidden (or not finite) are never assigned; a row may stay unassigned.
/// Returns, for each row, its column or -1. Ties are broken deterministically.
std::vector<int> solveAssignment(const std::vector<double>& cost, std::size_t rows, std::size_t cols);

}  // namespace wsn::common

#include "common/assignment.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <algorithm>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "common/rng.hpp"

namespace wsn::common {
namespace {

constexpr double F = kForbidden;

/// Size (number of assigned rows) and total cost of an assignment; checks that it is valid:
/// columns in range, used at most once, never a forbidden pair.
struct Outcome {
  int size = 0;
  double cost = 0.0;
};

Outcome outcomeOf(const std::vector<int>& assignment, const std::vector<double>& cost, std::size_t rows,
                  std::size_t cols) {
  REQUIRE(assignment.size() == rows);
  std::vector<char> used(cols, 0);
  Outcome o;
  for (std::size_t r = 0; r < rows; ++r) {
    const int c = assignment[r];
    if (c < 0) {
      CHECK(c == -1);
      continue;
    }
    REQUIRE(static_cast<std::size_t>(c) < cols);
    CHECK_FALSE(used[static_cast<std::size_t>(c)]);
    used[static_cast<std::size_t>(c)] = 1;
    const double v = cost[r * cols + static_cast<std::size_t>(c)];
    CHECK(std::isfinite(v));
    ++o.size;
    o.cost += v;
  }
  return o;
}

/// Exhaustive search over every partial assignment that avoids forbidden pairs. The solver pads
/// each row with a private "unassigned" column whose cost exceeds any sum of finite costs, so
/// its optimum is lexicographic: the most rows assigned, then the least total cost.
Outcome bruteForce(const std::vector<double>& cost, std::size_t rows, std::size_t cols) {
  Outcome best{-1, 0.0};
  std::vector<char> used(cols, 0);
  Outcome current;
  auto search = [&](auto&& self, std::size_t r) -> void {
    if (r == rows) {
      if (current.size > best.size || (current.size == best.size && current.cost < best.cost)) best = current;
      return;
    }
    self(self, r + 1);  // row r unassigned
    for (std::size_t c = 0; c < cols; ++c) {
      const double v = cost[r * cols + c];
      if (used[c] || !std::isfinite(v)) continue;
      used[c] = 1;
      ++current.size;
      current.cost += v;
      self(self, r + 1);
      current.cost -= v;
      --current.size;
      used[c] = 0;
    }
  };
  search(search, 0);
  return best;
}

TEST_CASE("a square problem gets its unique optimum", "[assignment]") {
  // Permutations and their costs: (0,1,2) 4+0+2=6, (0,2,1) 4+5+2=11, (1,0,2) 1+2+2=5,
  // (1,2,0) 1+5+3=9, (2,0,1) 3+2+2=7, (2,1,0) 3+0+3=6; the unique minimum is 5.
  const std::vector<double> cost = {4, 1, 3,  //
                                    2, 0, 5,  //
                                    3, 2, 2};
  CHECK(solveAssignment(cost, 3, 3) == std::vector<int>{1, 0, 2});
}

TEST_CASE("rectangular problems leave the surplus rows or columns unused", "[assignment]") {
  // 2 rows x 3 columns: row 0 is cheapest at column 2 (1), row 1 at column 0 (2); total 3.
  CHECK(solveAssignment({5, 4, 1,  //
                         2, 7, 3},
                        2, 3) == std::vector<int>{2, 0});
  // 3 rows x 1 column: only the cheapest row (row 1, cost 0.5) gets the column.
  CHECK(solveAssignment({3, 0.5, 2}, 3, 1) == std::vector<int>{-1, 0, -1});
}

TEST_CASE("forbidden pairs are never assigned", "[assignment]") {
  // Row 1 can only take column 2, which leaves row 0 column 0 (1): total 1 + 2 = 3.
  CHECK(solveAssignment({1, F, 5,  //
                         F, F, 2},
                        2, 3) == std::vector<int>{0, 2});
  // Both rows want only column 0: the cheaper row 0 gets it, row 1 stays unassigned.
  CHECK(solveAssignment({1, F,  //
                         2, F},
                        2, 2) == std::vector<int>{0, -1});
  // Nothing allowed: nobody is assigned.
  CHECK(solveAssignment({F, F, F, F}, 2, 2) == std::vector<int>{-1, -1});
  // NaN counts as forbidden too.
  CHECK(solveAssignment({std::nan(""), 1.0}, 1, 2) == std::vector<int>{1});
}

TEST_CASE("more assigned rows win over a lower total cost", "[assignment]") {
  // Row 1 can only take column 0. Assigning both rows costs 100 + 1 = 101; assigning row 0
  // alone to column 0 would cost 0, but leaves row 1 out: the solver assigns both.
  CHECK(solveAssignment({0, 100,  //
                         1, F},
                        2, 2) == std::vector<int>{1, 0});
}

TEST_CASE("empty problems give empty or all-unassigned results", "[assignment]") {
  CHECK(solveAssignment({}, 0, 0).empty());
  CHECK(solveAssignment({}, 0, 3).empty());
  CHECK(solveAssignment({}, 2, 0) == std::vector<int>{-1, -1});
}

TEST_CASE("the solver matches brute force on random rectangular problems", "[assignment]") {
  for (std::uint64_t trial = 0; trial < 500; ++trial) {
    Stream random(42, Purpose::kTracker, trial, 0);
    const std::size_t rows = 1 + random.below(5);
    const std::size_t cols = 1 + random.below(5);
    const double forbidden_share = 0.1 * static_cast<double>(random.below(6));  // 0 to 0.5
    const bool with_negative = random.bernoulli(0.3);
    std::vector<double> cost(rows * cols);
    for (auto& v : cost) {
      if (random.bernoulli(forbidden_share))
        v = F;
      else
        v = with_negative ? random.uniform(-10.0, 10.0) : random.uniform(0.0, 10.0);
    }
    INFO("trial " << trial << ": " << rows << " x " << cols);
    const auto assignment = solveAssignment(cost, rows, cols);
    const Outcome got = outcomeOf(assignment, cost, rows, cols);
    const Outcome best = bruteForce(cost, rows, cols);
    CHECK(got.size == best.size);
    CHECK(got.cost == Approx(best.cost).margin(1e-9));
    CHECK(solveAssignment(cost, rows, cols) == assignment);  // deterministic
  }
}

TEST_CASE("integer costs with ties still give an optimum", "[assignment]") {
  for (std::uint64_t trial = 0; trial < 200; ++trial) {
    Stream random(43, Purpose::kTracker, trial, 0);
    const std::size_t rows = 1 + random.below(5);
    const std::size_t cols = 1 + random.below(5);
    std::vector<double> cost(rows * cols);
    for (auto& v : cost) v = random.bernoulli(0.2) ? F : static_cast<double>(random.below(3));  // many ties
    INFO("trial " << trial);
    const Outcome got = outcomeOf(solveAssignment(cost, rows, cols), cost, rows, cols);
    const Outcome best = bruteForce(cost, rows, cols);
    CHECK(got.size == best.size);
    CHECK(got.cost == best.cost);  // sums of small integers are exact
  }
}

/// Exhaustive optimum of the partial assignment with `miss` per unassigned row.
double bruteForceWithMiss(const std::vector<double>& cost, std::size_t rows, std::size_t cols, double miss) {
  double best = std::numeric_limits<double>::infinity();
  std::vector<char> used(cols, 0);
  auto search = [&](auto&& self, std::size_t r, double sum) -> void {
    if (r == rows) {
      best = std::min(best, sum);
      return;
    }
    self(self, r + 1, sum + miss);
    for (std::size_t c = 0; c < cols; ++c) {
      const double v = cost[r * cols + c];
      if (used[c] || !std::isfinite(v)) continue;
      used[c] = 1;
      self(self, r + 1, sum + v);
      used[c] = 0;
    }
  };
  search(search, 0, 0.0);
  return best;
}

TEST_CASE("a row stays unassigned when every pair costs more than its miss", "[assignment]") {
  // Row 0 pairs with column 0 (1 < 3); row 1's only pairs cost 4 and 5, above its miss cost 3,
  // while the lexicographic solver would assign it to column 1.
  const std::vector<double> cost = {1, 4,  //
                                    5, 4};
  CHECK(solveAssignmentWithMissCost(cost, 2, 2, 3.0) == std::vector<int>{0, -1});
  CHECK(solveAssignment(cost, 2, 2) == std::vector<int>{0, 1});
  // Two pairs each just under the miss cost lose to one cheap pair: 0 + 3 < 2.9 + 2.9.
  CHECK(solveAssignmentWithMissCost({2.9, 0,  //
                                     F, 2.9},
                                    2, 2, 3.0) == std::vector<int>{1, -1});
  CHECK_THROWS(solveAssignmentWithMissCost({1}, 1, 1, F));
}

TEST_CASE("the miss cost solver matches brute force on random problems", "[assignment]") {
  for (std::uint64_t trial = 0; trial < 400; ++trial) {
    Stream random(44, Purpose::kTracker, trial, 0);
    const std::size_t rows = 1 + random.below(5);
    const std::size_t cols = 1 + random.below(5);
    const double miss = random.uniform(0.5, 8.0);
    std::vector<double> cost(rows * cols);
    for (auto& v : cost) v = random.bernoulli(0.2) ? F : random.uniform(0.0, 10.0);
    INFO("trial " << trial << ": " << rows << " x " << cols << ", miss " << miss);
    const auto assignment = solveAssignmentWithMissCost(cost, rows, cols, miss);
    const Outcome got = outcomeOf(assignment, cost, rows, cols);
    CHECK(got.cost + miss * static_cast<double>(rows - static_cast<std::size_t>(got.size)) ==
          Approx(bruteForceWithMiss(cost, rows, cols, miss)).margin(1e-9));
  }
}

TEST_CASE("independent clusters are solved as if each were alone", "[assignment]") {
  // 40 random 3 x 3 blocks on the diagonal of a 120 x 120 problem, everything else forbidden,
  // rows and columns shuffled: the solution is the blocks' own solutions, put back in place.
  constexpr std::size_t kBlocks = 40;
  constexpr std::size_t kSize = 3 * kBlocks;
  Stream random(45, Purpose::kTracker, 0, 0);
  std::vector<std::size_t> row_at(kSize), col_at(kSize);
  for (std::size_t k = 0; k < kSize; ++k) row_at[k] = col_at[k] = k;
  for (std::size_t k = kSize - 1; k > 0; --k) {
    std::swap(row_at[k], row_at[random.below(k + 1)]);
    std::swap(col_at[k], col_at[random.below(k + 1)]);
  }
  std::vector<double> cost(kSize * kSize, F);
  std::vector<std::vector<double>> blocks(kBlocks, std::vector<double>(9));
  for (std::size_t b = 0; b < kBlocks; ++b)
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j) {
        blocks[b][i * 3 + j] = random.bernoulli(0.2) ? F : random.uniform(0.0, 10.0);
        cost[row_at[3 * b + i] * kSize + col_at[3 * b + j]] = blocks[b][i * 3 + j];
      }
  const auto whole = solveAssignment(cost, kSize, kSize);
  const auto whole_with_miss = solveAssignmentWithMissCost(cost, kSize, kSize, 4.0);
  for (std::size_t b = 0; b < kBlocks; ++b) {
    const auto alone = solveAssignment(blocks[b], 3, 3);
    const auto alone_with_miss = solveAssignmentWithMissCost(blocks[b], 3, 3, 4.0);
    for (std::size_t i = 0; i < 3; ++i) {
      INFO("block " << b << ", row " << i);
      const int expected = alone[i] < 0 ? -1 : static_cast<int>(col_at[3 * b + static_cast<std::size_t>(alone[i])]);
      const int expected_with_miss =
          alone_with_miss[i] < 0 ? -1 : static_cast<int>(col_at[3 * b + static_cast<std::size_t>(alone_with_miss[i])]);
      CHECK(whole[row_at[3 * b + i]] == expected);
      CHECK(whole_with_miss[row_at[3 * b + i]] == expected_with_miss);
    }
  }
}

TEST_CASE("a sparse problem gives the solution of its matrix", "[assignment]") {
  for (std::uint64_t trial = 0; trial < 200; ++trial) {
    Stream random(47, Purpose::kTracker, trial, 0);
    const std::size_t rows = 1 + random.below(6);
    const std::size_t cols = 1 + random.below(6);
    std::vector<double> cost(rows * cols);
    std::vector<AssignmentPair> pairs;
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t c = 0; c < cols; ++c) {
        cost[r * cols + c] = random.bernoulli(0.4) ? F : random.uniform(0.0, 10.0);
        if (!std::isfinite(cost[r * cols + c])) continue;
        pairs.push_back({static_cast<std::uint32_t>(r), static_cast<std::uint32_t>(c), cost[r * cols + c]});
        // A repeat of the pair at a higher cost: the cheapest stands.
        if (random.bernoulli(0.2)) pairs.push_back({static_cast<std::uint32_t>(r), static_cast<std::uint32_t>(c), 20.0});
      }
    for (std::size_t k = pairs.size(); k > 1; --k) std::swap(pairs[k - 1], pairs[random.below(k)]);
    INFO("trial " << trial);
    CHECK(solveSparseAssignment(rows, cols, pairs) == solveAssignment(cost, rows, cols));
    CHECK(solveSparseAssignmentWithMissCost(rows, cols, pairs, 5.0) == solveAssignmentWithMissCost(cost, rows, cols, 5.0));
  }
  CHECK_THROWS_WITH(solveSparseAssignment(2, 2, std::vector<AssignmentPair>{{0, 2, 1.0}}),
                    Catch::Contains("pair (0, 2) outside a 2 x 2 problem"));
  CHECK_THROWS_WITH(solveAssignment({1, 2, 3}, 2, 2), Catch::Contains("3 entries for 2 x 2"));
}

}  // namespace
}  // namespace wsn::common

#include "common/assignment.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
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

}  // namespace
}  // namespace wsn::common

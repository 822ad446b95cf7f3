#include "common/near_pairs.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "common/rng.hpp"

namespace wsn::common {
namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

Pairs near(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double radius) {
  Pairs out;
  forEachPairWithin(std::span<const Vec2>(a), std::span<const Vec2>(b), radius,
                    [&](std::uint32_t i, std::uint32_t j) { out.push_back({i, j}); });
  return out;
}

TEST_CASE("pairs within a radius are those of a scan of all pairs", "[near_pairs]") {
  for (std::uint64_t trial = 0; trial < 50; ++trial) {
    Stream random(46, Purpose::kTracker, trial, 0);
    std::vector<Vec2> a(random.below(40)), b(random.below(40));
    for (auto& p : a) p = {random.uniform(0.0, 20.0), random.uniform(0.0, 20.0)};
    for (auto& p : b) p = {random.uniform(0.0, 20.0), random.uniform(0.0, 20.0)};
    const double radius = random.uniform(0.0, 8.0);
    Pairs expected;
    for (std::uint32_t i = 0; i < a.size(); ++i)
      for (std::uint32_t j = 0; j < b.size(); ++j)
        if (distance(a[i], b[j]) <= radius) expected.push_back({i, j});
    const Pairs got = near(a, b, radius);
    INFO("trial " << trial << ", radius " << radius);
    // A superset by at most the documented margin, in (i, j) order.
    CHECK(std::is_sorted(got.begin(), got.end()));
    for (const auto& pair : expected) CHECK(std::find(got.begin(), got.end(), pair) != got.end());
    for (const auto& [i, j] : got) CHECK(distance(a[i], b[j]) <= radius * (1.0 + 1e-8));
  }
}

TEST_CASE("a pair at exactly the radius is visited, and an infinite radius visits all", "[near_pairs]") {
  const std::vector<Vec2> a{{0, 0}, {10, 0}};
  const std::vector<Vec2> b{{3, 4}, {100, 100}};
  CHECK(near(a, b, 5.0) == Pairs{{0, 0}});
  CHECK(near(a, b, std::numeric_limits<double>::infinity()) == Pairs{{0, 0}, {0, 1}, {1, 0}, {1, 1}});
  CHECK(near(a, b, -1.0).empty());
  CHECK(near(a, b, std::numeric_limits<double>::quiet_NaN()).empty());
}

TEST_CASE("points with a non-finite coordinate are never paired", "[near_pairs]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Vec2> a{{0, 0}, {nan, 0}, {inf, 0}};
  const std::vector<Vec2> b{{0, 1}, {0, nan}, {-inf, 0}};
  CHECK(near(a, b, inf) == Pairs{{0, 0}});
}

}  // namespace
}  // namespace wsn::common

#include "common/voronoi.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "common/rng.hpp"

namespace wsn::common {
namespace {

using Neighbours = std::vector<std::vector<std::uint32_t>>;

double area(const std::vector<Vec2>& polygon) {
  double twice = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Vec2 p = polygon[k];
    const Vec2 q = polygon[(k + 1) % polygon.size()];
    twice += p.x * q.y - q.x * p.y;
  }
  return twice / 2.0;
}

std::vector<Vec2> grid(int side, double spacing) {
  std::vector<Vec2> sites;
  for (int row = 0; row < side; ++row)
    for (int column = 0; column < side; ++column) sites.push_back({spacing * (column + 0.5), spacing * (row + 0.5)});
  return sites;
}

TEST_CASE("the cells of a square grid of supernodes are its squares", "[voronoi]") {
  const Rect region{0, 0, 300, 300};
  const auto sites = grid(3, 100);
  for (std::uint32_t i = 0; i < sites.size(); ++i) {
    const auto cell = voronoiCell(sites, region, i);
    CHECK(area(cell) == Approx(10000.0));
    for (const Vec2 p : cell) CHECK(distance(p, sites[i]) <= std::sqrt(2.0) * 50.0 + 1e-9);
  }
}

TEST_CASE("grid cells that share an edge or only a corner are neighbours, the others not", "[voronoi]") {
  // 0 1 2 / 3 4 5 / 6 7 8, row 0 at the bottom: the centre borders all; a corner borders three.
  const auto neighbours = voronoiNeighbours(grid(3, 100), {0, 0, 300, 300});
  CHECK(neighbours[4] == std::vector<std::uint32_t>{0, 1, 2, 3, 5, 6, 7, 8});
  CHECK(neighbours[0] == std::vector<std::uint32_t>{1, 3, 4});
  CHECK(neighbours[1] == std::vector<std::uint32_t>{0, 2, 3, 4, 5});
  // Four quadrants all meet at the centre.
  CHECK(voronoiNeighbours(grid(2, 50), {0, 0, 100, 100}) == Neighbours{{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}});
}

TEST_CASE("supernodes in a row neighbour only the next ones", "[voronoi]") {
  const std::vector<Vec2> row{{5, 5}, {15, 5}, {25, 5}, {35, 5}};
  CHECK(voronoiNeighbours(row, {0, 0, 40, 10}) == Neighbours{{1}, {0, 2}, {1, 3}, {2}});
}

TEST_CASE("a supernode whose cell misses the region has no neighbours, and twins neighbour each other",
          "[voronoi]") {
  // Site 2 sits outside the region behind site 1: every point of the region is nearer to 0 or 1.
  const std::vector<Vec2> sites{{2, 5}, {8, 5}, {50, 5}, {8, 5}};
  const auto neighbours = voronoiNeighbours(sites, {0, 0, 10, 10});
  CHECK(voronoiCell(sites, {0, 0, 10, 10}, 2).empty());
  CHECK(neighbours[2].empty());
  CHECK(neighbours[1] == std::vector<std::uint32_t>{0, 3});
  CHECK(neighbours[3] == std::vector<std::uint32_t>{0, 1});
}

TEST_CASE("random supernodes: cells tile the region and neighbours are symmetric", "[voronoi]") {
  for (std::uint64_t trial = 0; trial < 20; ++trial) {
    Stream random(48, Purpose::kTracker, trial, 0);
    const Rect region{0, 0, 100, 60};
    std::vector<Vec2> sites(2 + random.below(30));
    for (auto& s : sites) s = {random.uniform(0.0, 100.0), random.uniform(0.0, 60.0)};
    double total = 0.0;
    for (std::uint32_t i = 0; i < sites.size(); ++i) total += area(voronoiCell(sites, region, i));
    CHECK(total == Approx(6000.0).epsilon(1e-9));
    const auto neighbours = voronoiNeighbours(sites, region);
    for (std::uint32_t i = 0; i < sites.size(); ++i) {
      CHECK_FALSE(neighbours[i].empty());
      for (const auto j : neighbours[i]) {
        CHECK(j != i);
        CHECK(std::find(neighbours[j].begin(), neighbours[j].end(), i) != neighbours[j].end());
      }
    }
    // A point's second-nearest supernode borders its nearest (the property re-homing relies on).
    for (int k = 0; k < 200; ++k) {
      const Vec2 p{random.uniform(0.0, 100.0), random.uniform(0.0, 60.0)};
      std::vector<std::uint32_t> order(sites.size());
      for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](auto a, auto b) { return squaredDistance(p, sites[a]) < squaredDistance(p, sites[b]); });
      const auto& near = neighbours[order[0]];
      CHECK(std::find(near.begin(), near.end(), order[1]) != near.end());
    }
  }
}

}  // namespace
}  // namespace wsn::common

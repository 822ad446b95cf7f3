#include "network_model/topology.hpp"

#include <deque>
#include <vector>

#include <catch2/catch.hpp>

#include "common/rng.hpp"
#include "network_model/calibration.hpp"

namespace nm = wsn::network_model;
using wsn::common::Vec2;

namespace {

/// Plain O(n^2) BFS over G (sensors then supernodes) as a reference for the cell-grid BFS.
std::vector<std::int32_t> referenceHops(const std::vector<Vec2>& sensors, const std::vector<Vec2>& supernodes,
                                        double range) {
  std::vector<Vec2> nodes = sensors;
  nodes.insert(nodes.end(), supernodes.begin(), supernodes.end());
  std::vector<std::int32_t> result(sensors.size(), -1);
  for (std::size_t j = 0; j < supernodes.size(); ++j) {
    std::vector<std::int32_t> level(nodes.size(), -1);
    std::deque<std::size_t> queue{sensors.size() + j};
    level[sensors.size() + j] = 0;
    while (!queue.empty()) {
      const std::size_t u = queue.front();
      queue.pop_front();
      for (std::size_t v = 0; v < nodes.size(); ++v)
        if (level[v] < 0 && wsn::common::squaredDistance(nodes[u], nodes[v]) <= range * range) {
          level[v] = level[u] + 1;
          queue.push_back(v);
        }
    }
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      std::size_t nearest = 0;
      for (std::size_t s = 1; s < supernodes.size(); ++s)
        if (wsn::common::squaredDistance(sensors[i], supernodes[s]) <
            wsn::common::squaredDistance(sensors[i], supernodes[nearest]))
          nearest = s;
      if (nearest == j) result[i] = level[i];
    }
  }
  return result;
}

}  // namespace

TEST_CASE("hop counts along a line of sensors are the distance in range units", "[network][topology]") {
  // Supernode at the origin, sensors at x = 1..5.
  const std::vector<Vec2> sensors{{1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}};
  const std::vector<Vec2> supernodes{{0, 0}};
  SECTION("range 1: each sensor only reaches its direct neighbours, so sensor at x = k is k hops") {
    const nm::Topology topology(nm::TopologyConfig{supernodes, 1.0}, sensors);
    for (std::uint32_t i = 0; i < 5; ++i) CHECK(topology.hops(i) == static_cast<std::int32_t>(i + 1));
    // Mean of 1..5 = 3.
    CHECK(topology.meanHops() == Approx(3.0).margin(1e-12));
    CHECK(topology.maxHops() == 5);
    CHECK(topology.unreachableCount() == 0);
    CHECK(topology.hopHistogram() == std::vector<std::size_t>{0, 1, 1, 1, 1, 1});
  }
  SECTION("range 2: two units per hop, so hops = ceil(x / 2) = 1, 1, 2, 2, 3") {
    const nm::Topology topology(nm::TopologyConfig{supernodes, 2.0}, sensors);
    CHECK(std::vector<std::int32_t>(topology.allHops().begin(), topology.allHops().end()) ==
          std::vector<std::int32_t>{1, 1, 2, 2, 3});
  }
  SECTION("range just below 1: nothing is connected, every sensor is unreachable") {
    const nm::Topology topology(nm::TopologyConfig{supernodes, 0.999}, sensors);
    for (std::uint32_t i = 0; i < 5; ++i) CHECK(topology.hops(i) == -1);
    CHECK(topology.unreachableCount() == 5);
    CHECK(topology.reachableCount() == 0);
    CHECK(topology.meanHops() == 0.0);
    CHECK(topology.maxHops() == 0);
  }
}

TEST_CASE("a sensor equally near two supernodes belongs to the lower index", "[network][topology]") {
  // Sensor at (1, 0) is 1 from both (0, 0) and (2, 0).
  const std::vector<Vec2> sensors{{1, 0}, {0.9, 0}, {1.1, 0}};
  const nm::Topology forward(nm::TopologyConfig{std::vector<Vec2>{{0, 0}, {2, 0}}, 1.0}, sensors);
  CHECK(forward.supernodeOf(0) == 0);
  CHECK(forward.supernodeOf(1) == 0);
  CHECK(forward.supernodeOf(2) == 1);
  const nm::Topology swapped(nm::TopologyConfig{std::vector<Vec2>{{2, 0}, {0, 0}}, 1.0}, sensors);
  CHECK(swapped.supernodeOf(0) == 0);  // the tie goes to index 0, now the supernode at (2, 0)
  CHECK(swapped.supernodeOf(1) == 1);
  CHECK(swapped.supernodeOf(2) == 0);
  CHECK(forward.groupSize(0) == 2);
  CHECK(forward.groupSize(1) == 1);
}

TEST_CASE("paths run through other groups' sensors, and a sensor cut off from its own supernode is unreachable",
          "[network][topology]") {
  // Range 1. A = (0,0), B = (4,0). The only chain is A - u - t - s - r - p (consecutive
  // distances 0.94, 0.99, 0.92, 0.98, 0.97; every other pair is > 1.45 apart), and B's only
  // neighbour is w. Nearest supernodes: u, t, p -> A (p: 1.95 vs 2.05); s, r, w -> B.
  const std::vector<Vec2> sensors{
      {0.5, 0.8},  // 0 u: A, 1 hop
      {1.2, 1.5},  // 1 t: A, 2 hops
      {2.1, 1.7},  // 2 s: B, but its chain only reaches A -> unreachable
      {2.5, 0.8},  // 3 r: B, unreachable likewise
      {1.95, 0.0},  // 4 p: A, 5 hops through s and r of B's group
      {4.5, 0.0},  // 5 w: B, 1 hop
  };
  const nm::Topology topology(nm::TopologyConfig{std::vector<Vec2>{{0, 0}, {4, 0}}, 1.0}, sensors);
  CHECK(topology.supernodeOf(2) == 1);
  CHECK(topology.supernodeOf(3) == 1);
  CHECK(topology.supernodeOf(4) == 0);
  CHECK(topology.hops(0) == 1);
  CHECK(topology.hops(1) == 2);
  CHECK(topology.hops(2) == -1);
  CHECK(topology.hops(3) == -1);
  CHECK(topology.hops(4) == 5);
  CHECK(topology.hops(5) == 1);
  CHECK(topology.unreachableCount() == 2);
  // Mean over the 4 reachable sensors: (1 + 2 + 5 + 1) / 4 = 2.25.
  CHECK(topology.meanHops() == Approx(2.25).margin(1e-12));
}

TEST_CASE("the cell-grid BFS agrees with a plain BFS on random fields", "[network][topology]") {
  for (const double range : {0.3, 1.0, 2.5, 7.0}) {
    std::vector<Vec2> sensors;
    for (std::uint32_t i = 0; i < 400; ++i) {
      wsn::common::Stream place(42, wsn::common::Purpose::kSensorPlacement, i, 0);
      sensors.push_back({place.uniform(0.0, 20.0), place.uniform(0.0, 20.0)});
    }
    const std::vector<Vec2> supernodes{{5, 5}, {15, 5}, {10, 15}};
    const nm::Topology topology(nm::TopologyConfig{supernodes, range}, sensors);
    const auto expected = referenceHops(sensors, supernodes, range);
    INFO("range " << range);
    CHECK(std::vector<std::int32_t>(topology.allHops().begin(), topology.allHops().end()) == expected);
  }
}

TEST_CASE("Oh's quadrant grid gives 2500 sensors per group and grid-walk hop counts", "[network][topology]") {
  // 100 x 100 sensors at 0.5 .. 99.5, supernodes at the quadrant centres.
  SECTION("range 1: only the 4 grid neighbours are in range; corner (0.5, 0.5) needs 48 grid steps to "
          "(24.5, 24.5), which is 0.707 from the supernode: 49 hops") {
    const nm::Topology topology = nm::ohCalibrationTopology(1.0, nm::SupernodePlacement::kQuadrants);
    REQUIRE(topology.sensorCount() == 10000);
    for (std::uint32_t j = 0; j < 4; ++j) CHECK(topology.groupSize(j) == 2500);
    CHECK(topology.unreachableCount() == 0);
    CHECK(topology.maxHops() == 49);
    CHECK(topology.hops(0) == 49);
    // Sensor (24.5, 24.5) has id 24 * 100 + 24 and is 0.707 from (25, 25).
    CHECK(topology.hops(2424) == 1);
  }
  SECTION("range sqrt(2): diagonals too, so the corner needs 24 steps + 1 = 25 hops") {
    const nm::Topology topology =
        nm::ohCalibrationTopology(std::sqrt(2.0) + 1e-12, nm::SupernodePlacement::kQuadrants);
    CHECK(topology.maxHops() == 25);
  }
}

TEST_CASE("a topology without supernodes is refused", "[network][topology]") {
  const std::vector<Vec2> sensors{{1, 0}};
  CHECK_THROWS_AS(nm::Topology(nm::TopologyConfig{std::vector<Vec2>{}, 1.0}, sensors), std::invalid_argument);
}

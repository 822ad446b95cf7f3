#include "supernode/rulebased/clustering.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace wsn::supernode::rulebased {
namespace {

// The paper's field (An et al. 2014 §2): a 50 x 50 grid at Ds = 25 m, sensors at 12.5 + 25 i,
// ids row-major (j * 50 + i); link distance 1.5 Ds, the engine's default.
constexpr double kDs = 25.0;
constexpr double kLink = 1.5 * kDs;

/// The detection of the grid sensor in column i, row j.
Detection at(int i, int j, std::int32_t level = 1) {
  return {static_cast<common::SensorId>(j * 50 + i), {12.5 + kDs * i, 12.5 + kDs * j}, level};
}

std::vector<common::SensorId> ids(const Cluster& cluster) {
  std::vector<common::SensorId> out;
  for (const auto& d : cluster.members) out.push_back(d.sensor);
  return out;
}

std::vector<std::vector<common::SensorId>> memberIds(const std::vector<Cluster>& clusters) {
  std::vector<std::vector<common::SensorId>> out;
  for (const auto& c : clusters) out.push_back(ids(c));
  return out;
}

TEST_CASE("eq. 6: each of the eight neighbours of a sensor joins its cluster", "[rulebased]") {
  // |i_r - i_b| <= 1 and |j_r - j_b| <= 1: the side neighbours are 25 m away, the diagonal ones
  // 25 sqrt(2) = 35.36 m, both within the link distance 1.5 Ds = 37.5 m.
  for (int di = -1; di <= 1; ++di)
    for (int dj = -1; dj <= 1; ++dj) {
      if (di == 0 && dj == 0) continue;
      INFO("neighbour offset (" << di << ", " << dj << ")");
      const std::vector<Detection> detections = {at(20, 20), at(20 + di, 20 + dj)};
      const auto clusters = clusterDetections(detections, kLink, kDs);
      REQUIRE(clusters.size() == 1);
      CHECK(clusters[0].size() == 2);
    }
}

TEST_CASE("eq. 6: a gap of one sensor separates two clusters in every direction", "[rulebased]") {
  // Two columns or rows apart: 50 m (side), 25 sqrt(5) = 55.9 m (knight's move) or 50 sqrt(2) =
  // 70.7 m (diagonal), all beyond 37.5 m, so each sensor is a cluster of its own.
  const std::vector<std::pair<int, int>> offsets = {{2, 0}, {0, 2}, {-2, 0}, {0, -2}, {2, 1},
                                                    {1, 2}, {-2, 1}, {2, 2}, {-2, -2}};
  for (const auto& [di, dj] : offsets) {
    INFO("offset (" << di << ", " << dj << ")");
    const std::vector<Detection> detections = {at(20, 20), at(20 + di, 20 + dj)};
    const auto clusters = clusterDetections(detections, kLink, kDs);
    REQUIRE(clusters.size() == 2);
    CHECK(clusters[0].size() == 1);
    CHECK(clusters[1].size() == 1);
  }
}

TEST_CASE("single linkage: a staircase of diagonal neighbours is one cluster, a gap splits it", "[rulebased]") {
  // (0,0), (1,1), ..., (9,9): each step is a diagonal neighbour, so all ten form one cluster
  // although its ends are 9 sqrt(2) Ds = 318 m apart. Removing (5,5) leaves (4,4) and (6,6) two
  // columns apart: two clusters, {0..4} then {6..9}.
  std::vector<Detection> staircase;
  for (int k = 0; k < 10; ++k) staircase.push_back(at(k, k));
  const auto whole = clusterDetections(staircase, kLink, kDs);
  REQUIRE(whole.size() == 1);
  CHECK(whole[0].size() == 10);

  staircase.erase(staircase.begin() + 5);
  const auto broken = clusterDetections(staircase, kLink, kDs);
  REQUIRE(broken.size() == 2);
  CHECK(ids(broken[0]) == std::vector<common::SensorId>{0, 51, 102, 153, 204});
  CHECK(ids(broken[1]) == std::vector<common::SensorId>{306, 357, 408, 459});
}

TEST_CASE("every link distance from sqrt(2) Ds up to but excluding 2 Ds gives the same 8-connected clusters", "[rulebased]") {
  // A pattern with side links, diagonal links and gaps of one sensor: an L of (3,3), (4,3), (4,4),
  // a diagonal pair (10,3), (11,4), and (13,4) two columns from (11,4).
  const std::vector<Detection> detections = {at(3, 3), at(4, 3), at(4, 4), at(10, 3), at(11, 4), at(13, 4)};
  const auto reference = memberIds(clusterDetections(detections, kLink, kDs));
  REQUIRE(reference.size() == 3);
  for (const double link : {1.415 * kDs, 1.5 * kDs, 1.99 * kDs}) {
    INFO("link distance " << link);
    CHECK(memberIds(clusterDetections(detections, link, kDs)) == reference);
  }
  // Below sqrt(2) Ds = 35.36 m the diagonal links break: (3,3)-(4,3)-(4,4) stays joined by side
  // links, (10,3) and (11,4) part: four clusters. At 2 Ds = 50 m ("at most" the link distance) the
  // gap of one sensor closes: (11,4)-(13,4) join, two clusters.
  CHECK(clusterDetections(detections, 1.4 * kDs, kDs).size() == 4);
  CHECK(clusterDetections(detections, 2.0 * kDs, kDs).size() == 2);
}

TEST_CASE("clusters are numbered by their smallest sensor id whatever the input order", "[rulebased]") {
  // Three clusters: A = {(40,2), (41,3)} (ids 140, 191), B = {(3,3), (2,4)} (ids 153, 202) and
  // C = {(0,30)} (id 1500). Row-major ids put A first although B is nearer the first column: the
  // paper's routine starts "from the sensor nearest to the first row and the first column", read
  // as the first sensor in row-major order. Members are sorted by id within a cluster.
  std::vector<Detection> detections = {at(0, 30), at(2, 4), at(41, 3), at(3, 3), at(40, 2)};
  const std::vector<std::vector<common::SensorId>> expected = {{140, 191}, {153, 202}, {1500}};
  std::sort(detections.begin(), detections.end(),
            [](const Detection& a, const Detection& b) { return a.sensor < b.sensor; });
  int orders = 0;
  do {
    ++orders;
    REQUIRE(memberIds(clusterDetections(detections, kLink, kDs)) == expected);
  } while (std::next_permutation(detections.begin(), detections.end(),
                                 [](const Detection& a, const Detection& b) { return a.sensor < b.sensor; }));
  CHECK(orders == 120);  // 5! input orders, all numbered alike
}

TEST_CASE("a sensor reported twice is kept once, with its first report", "[rulebased]") {
  // Sensor (10,10) twice, with ws = 9 then ws = 4, and (11,10) with ws = 4. The first report is kept:
  // c_x = (9 * 262.5 + 4 * 287.5) / 13 = 3512.5 / 13 = 270.19 (keeping the second would give 275.0,
  // counting both (13 * 262.5 + 4 * 287.5) / 17 = 268.38). N = 2: r = sqrt(2) 25 / 2 = 17.68.
  const std::vector<Detection> detections = {at(10, 10, 9), at(11, 10, 4), at(10, 10, 4)};
  const auto clusters = clusterDetections(detections, kLink, kDs);
  REQUIRE(clusters.size() == 1);
  CHECK(ids(clusters[0]) == std::vector<common::SensorId>{510, 511});
  CHECK(clusters[0].members[0].level == 9);
  CHECK(clusters[0].centroid.x == Approx(3512.5 / 13.0).margin(1e-9));
  CHECK(clusters[0].radius == Approx(std::sqrt(2.0) * 12.5).margin(1e-9));

  // A sensor reported twice and nothing else: one cluster of one sensor, r = 25 / 2.
  const auto single = clusterDetections(std::vector{at(5, 5, 2), at(5, 5, 2)}, kLink, kDs);
  REQUIRE(single.size() == 1);
  CHECK(single[0].size() == 1);
  CHECK(single[0].radius == Approx(12.5).margin(1e-9));
}

TEST_CASE("eq. 10: the centroid weighs each sensor position by its level", "[rulebased]") {
  // A 2 x 2 block at x, y in {262.5, 287.5} with ws = 1 (10,10), 2 (11,10), 3 (10,11), 4 (11,11):
  // sum ws = 10; c_x = (262.5 (1 + 3) + 287.5 (2 + 4)) / 10 = (1050 + 1725) / 10 = 277.5;
  // c_y = (262.5 (1 + 2) + 287.5 (3 + 4)) / 10 = (787.5 + 2012.5) / 10 = 280.0.
  // (The unweighted centroid would be (275, 275).)
  const std::vector<Detection> detections = {at(10, 10, 1), at(11, 10, 2), at(10, 11, 3), at(11, 11, 4)};
  const auto clusters = clusterDetections(detections, kLink, kDs);
  REQUIRE(clusters.size() == 1);
  CHECK(clusters[0].centroid.x == Approx(277.5).margin(1e-9));
  CHECK(clusters[0].centroid.y == Approx(280.0).margin(1e-9));

  // A row of three with ws = 1, 3, 2 at x = 262.5, 287.5, 312.5:
  // c_x = (262.5 + 3 * 287.5 + 2 * 312.5) / 6 = 1750 / 6 = 291.67, c_y = 262.5.
  const auto row = clusterDetections(std::vector{at(10, 10, 1), at(11, 10, 3), at(12, 10, 2)}, kLink, kDs);
  REQUIRE(row.size() == 1);
  CHECK(row[0].centroid.x == Approx(1750.0 / 6.0).margin(1e-9));
  CHECK(row[0].centroid.y == Approx(262.5).margin(1e-9));
}

TEST_CASE("eq. 10: a report with level 0 weighs 1", "[rulebased]") {
  // ws = 0 (a fused report without a level) and ws = 3 side by side: weights 1 and 3,
  // c_x = (262.5 + 3 * 287.5) / 4 = 1125 / 4 = 281.25 (with weight 0 it would be 287.5).
  const auto mixed = clusterDetections(std::vector{at(10, 10, 0), at(11, 10, 3)}, kLink, kDs);
  REQUIRE(mixed.size() == 1);
  CHECK(mixed[0].centroid.x == Approx(281.25).margin(1e-9));
  CHECK(centroidWeight(at(0, 0, 0)) == 1.0);
  CHECK(centroidWeight(at(0, 0, 7)) == 7.0);

  // Levels all 0: the plain mean (262.5 + 287.5 + 312.5) / 3 = 287.5, no division by zero.
  const auto zeros = clusterDetections(std::vector{at(12, 10, 0), at(10, 10, 0), at(11, 10, 0)}, kLink, kDs);
  REQUIRE(zeros.size() == 1);
  CHECK(zeros[0].centroid.x == Approx(287.5).margin(1e-9));
  CHECK(std::isfinite(zeros[0].centroid.y));
}

TEST_CASE("the strongest sensor is the member with the largest level, ties to the smaller id", "[rulebased]") {
  // A 3 x 2 block with one level 6 at (12,11): it is the strongest wherever it is listed.
  const std::vector<Detection> block = {at(10, 10, 2), at(11, 10, 3), at(12, 10, 1),
                                        at(10, 11, 1), at(12, 11, 6), at(11, 11, 5)};
  const auto clusters = clusterDetections(block, kLink, kDs);
  REQUIRE(clusters.size() == 1);
  CHECK(clusters[0].strongest == common::Vec2{312.5, 287.5});

  // Levels 5, 5, 2 listed from the largest id down: (10,10) and (12,10) tie at 5; the smaller id,
  // (10,10) at x = 262.5, is the strongest.
  const auto tie = clusterDetections(std::vector{at(12, 10, 5), at(11, 10, 2), at(10, 10, 5)}, kLink, kDs);
  REQUIRE(tie.size() == 1);
  CHECK(tie[0].strongest == common::Vec2{262.5, 262.5});

  // All levels 0 (unknown): every member ties, the smallest id wins.
  const auto unknown = clusterDetections(std::vector{at(11, 11, 0), at(11, 10, 0)}, kLink, kDs);
  REQUIRE(unknown.size() == 1);
  CHECK(unknown[0].strongest == common::Vec2{287.5, 262.5});
}

TEST_CASE("eq. 21: the averaged radius is sqrt(N) Ds / 2 over the distinct members", "[rulebased]") {
  // N = 1: 12.5 m; N = 4: 25 m; N = 9: 37.5 m (a 3 x 3 block); N = 0: 0.
  CHECK(clusterRadius(1, kDs) == Approx(12.5).margin(1e-12));
  CHECK(clusterRadius(4, kDs) == Approx(25.0).margin(1e-12));
  CHECK(clusterRadius(9, kDs) == Approx(37.5).margin(1e-12));
  CHECK(clusterRadius(0, kDs) == 0.0);
  std::vector<Detection> block;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) block.push_back(at(20 + i, 20 + j));
  block.push_back(at(21, 21));  // a duplicate does not count
  const auto clusters = clusterDetections(block, kLink, kDs);
  REQUIRE(clusters.size() == 1);
  CHECK(clusters[0].size() == 9);
  CHECK(clusters[0].radius == Approx(37.5).margin(1e-12));
  // The block's centroid is its middle sensor (21,21): (537.5, 537.5).
  CHECK(clusters[0].centroid.x == Approx(537.5).margin(1e-9));
  CHECK(clusters[0].centroid.y == Approx(537.5).margin(1e-9));
}

TEST_CASE("no detections make no clusters", "[rulebased]") {
  CHECK(clusterDetections(std::vector<Detection>{}, kLink, kDs).empty());
}

}  // namespace
}  // namespace wsn::supernode::rulebased

#include "supernode/rulebased/clustering.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

namespace wsn::supernode::rulebased {
namespace {

constexpr double kDs = 25.0;
constexpr double kLink = 1.5 * kDs;

/// The detection of the grid sensor in column i, row j of a 50-wide grid at Ds = 25 m.
Detection at(int i, int j, int level = 1) {
  return {static_cast<common::SensorId>(j * 50 + i), {12.5 + kDs * i, 12.5 + kDs * j}, level};
}

TEST_CASE("eq. 6: diagonal neighbours join a cluster, a gap of one sensor separates", "[rulebased]") {
  // (10,10)-(11,11) touch diagonally (|di|, |dj| <= 1); (13,11) is two columns from (11,11).
  const std::vector<Detection> detections = {at(10, 10), at(11, 11), at(13, 11)};
  const auto clusters = clusterDetections(detections, kLink, kDs);
  REQUIRE(clusters.size() == 2);
  CHECK(clusters[0].size() == 2);
  CHECK(clusters[1].size() == 1);
}

TEST_CASE("clusters are numbered from the sensor nearest the first row and column", "[rulebased]") {
  // Given in reverse: the cluster holding sensor (5, 2) (id 105) comes before the one at (30, 40).
  const std::vector<Detection> detections = {at(30, 40), at(31, 40), at(6, 3), at(5, 2)};
  const auto clusters = clusterDetections(detections, kLink, kDs);
  REQUIRE(clusters.size() == 2);
  CHECK(clusters[0].members.front().sensor == 105);
  CHECK(clusters[1].members.front().sensor == 40 * 50 + 30);
  // Members are sorted by id within a cluster.
  CHECK(clusters[0].members[1].sensor == 3 * 50 + 6);
}

TEST_CASE("eq. 10 and 21: weighted centroid, strongest sensor and averaged radius", "[rulebased]") {
  // Sensors at x = 262.5, 287.5, 312.5 (y = 262.5) with ws = 1, 3, 2:
  // c_x = (262.5 + 3 * 287.5 + 2 * 312.5) / 6 = 1750 / 6 = 291.667; r = sqrt(3) 25 / 2 = 21.65.
  const std::vector<Detection> detections = {at(10, 10, 1), at(11, 10, 3), at(12, 10, 2)};
  const auto clusters = clusterDetections(detections, kLink, kDs);
  REQUIRE(clusters.size() == 1);
  CHECK(clusters[0].centroid.x == Approx(1750.0 / 6.0));
  CHECK(clusters[0].centroid.y == Approx(262.5));
  CHECK(clusters[0].strongest == common::Vec2{287.5, 262.5});
  CHECK(clusters[0].radius == Approx(std::sqrt(3.0) * 12.5));
  CHECK(clusterRadius(4, kDs) == Approx(25.0));
}

TEST_CASE("a report without a level weighs 1, the strongest tie goes to the smaller id", "[rulebased]") {
  // Levels 0 and 0 (fused Oh reports): the plain mean; equal levels: the first (smaller id) is strongest.
  const std::vector<Detection> detections = {at(11, 10, 0), at(10, 10, 0)};
  const auto clusters = clusterDetections(detections, kLink, kDs);
  REQUIRE(clusters.size() == 1);
  CHECK(clusters[0].centroid.x == Approx(275.0));
  CHECK(clusters[0].strongest == common::Vec2{262.5, 262.5});
}

TEST_CASE("a sensor reported twice is counted once", "[rulebased]") {
  const std::vector<Detection> detections = {at(10, 10, 4), at(10, 10, 9), at(11, 10, 4)};
  const auto clusters = clusterDetections(detections, kLink, kDs);
  REQUIRE(clusters.size() == 1);
  CHECK(clusters[0].size() == 2);
  CHECK(clusters[0].centroid.x == Approx(275.0));  // the first report of sensor (10,10), level 4, kept
  CHECK(clusterDetections({}, kLink, kDs).empty());
}

}  // namespace
}  // namespace wsn::supernode::rulebased

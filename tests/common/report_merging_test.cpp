// Same-tick merging of nearby reports (common/report_merging.hpp): clusters around the strongest
// report, the merged report's position, label, sensor and delivery, and the radius that joins one
// target's reports. Every expected value is worked out by hand in a comment.
#include "common/report_merging.hpp"

#include <catch2/catch.hpp>

#include <vector>

namespace wsn::common {
namespace {

Report report(SensorId sensor, double x, double y, TargetId target, std::int32_t level) {
  return Report{1, sensor, x, y, target, level, {}};
}

TEST_CASE("reports within the radius of the strongest join it and the others start their own cluster",
          "[report_merging]") {
  // Levels 90 at (0, 0), 200 at (1, 0), 50 at (2, 0), 120 at (5, 0). In order of level: (1, 0)
  // starts cluster A, (5, 0) starts B (4 away), (0, 0) and (2, 0) are 1 from A: they join it.
  // Single linkage at radius 1 would chain nothing more here, but (3, 0) added at level 10 would
  // be 2 from A and 2 from B: its own cluster, where single linkage would join A and B through it.
  const std::vector<Report> items{report(1, 0, 0, 0, 90), report(2, 1, 0, 0, 200), report(3, 2, 0, 0, 50),
                                  report(4, 5, 0, 1, 120), report(5, 3, 0, 1, 10)};
  const auto cluster = strongestFirstClusters(std::span<const Report>(items), 1.0);
  // Seeds in item order: item 1 (A), item 3 (B), item 4 (its own): numbered 0, 1, 2.
  CHECK(cluster == std::vector<std::size_t>{0, 0, 0, 1, 2});
}

TEST_CASE("a merged report is the level-weighted centre of mass of its cluster with the majority label",
          "[report_merging]") {
  // Cluster of levels 90, 200, 50 at x = 0, 1, 2: x = (0 * 90 + 1 * 200 + 2 * 50) / 340 = 300 / 340.
  // Labels 0, 0, 7: target 0. The strongest member's sensor (2) and level (200) stay.
  const std::vector<Report> items{report(1, 0, 0, 0, 90), report(2, 1, 0, 0, 200), report(3, 2, 0, 7, 50),
                                  report(4, 5, 1, 1, 120)};
  const auto merged = mergeNearby(std::span<const Report>(items), 1.0);
  REQUIRE(merged.size() == 2);
  CHECK(merged[0].x == Approx(300.0 / 340.0));
  CHECK(merged[0].y == 0.0);
  CHECK(merged[0].sensor == 2);
  CHECK(merged[0].power_level == 200);
  CHECK(merged[0].target == 0);
  CHECK(merged[1] == items[3]);  // alone: unchanged
}

TEST_CASE("a tie of labels goes to the smaller target id and level 0 weighs as 1", "[report_merging]") {
  // Two reports at x = 0 and 1, levels 0 and 0 (weights 1 and 1): x = 0.5; labels 4 and -1 (a false
  // alarm): one vote each, the smaller id, -1, wins.
  const std::vector<Report> items{report(8, 0, 0, 4, 0), report(9, 1, 0, kFalseAlarm, 0)};
  const auto merged = mergeNearby(std::span<const Report>(items), 1.5);
  REQUIRE(merged.size() == 1);
  CHECK(merged[0].x == 0.5);
  CHECK(merged[0].target == kFalseAlarm);
  CHECK(merged[0].sensor == 8);  // equal levels: the first is the strongest
}

TEST_CASE("reports of a kind other than position are never merged", "[report_merging]") {
  // Two plain positions 0.5 and a presence (a position with its R) 0.2 from the first merge; a
  // bearing reported at the same place (its sensor's) stays as it is, after the merged one.
  Measurement bearing;
  bearing.kind = MeasurementKind::bearing;
  bearing.values = {0.3};
  bearing.noise = {1e-3};
  bearing.sensor = SensorPose{0.0, 0.0, 0.0};
  Measurement presence = Measurement::position(0.2, 0.0);
  presence.noise = {1.0, 0.0, 0.0, 1.0};
  std::vector<Report> items{report(1, 0, 0, 0, 5), report(2, 0.5, 0, 0, 6), report(3, 0, 0, 0, 0),
                            report(4, 0.2, 0, 0, 0)};
  items[2].measurement = MeasurementRef(bearing);
  items[3].measurement = MeasurementRef(presence);
  const auto merged = mergeNearby(std::span<const Report>(items), 1.0);
  REQUIRE(merged.size() == 2);
  // Levels 5, 6 and 0 (weighing 1) at x = 0, 0.5 and 0.2: x = (0 + 3 + 0.2) / 12, from sensor 2,
  // the strongest; a centre of mass has no R of its own.
  CHECK(merged[0].sensor == 2);
  CHECK(merged[0].x == Approx(3.2 / 12.0));
  CHECK_FALSE(merged[0].measurement);
  CHECK(merged[1] == items[2]);
}

TEST_CASE("a radius of zero or a single report leaves the reports as they are", "[report_merging]") {
  const std::vector<Report> items{report(1, 0, 0, 0, 5), report(2, 0.1, 0, 0, 6)};
  CHECK(mergeNearby(std::span<const Report>(items), 0.0) == items);
  CHECK(mergeNearby(std::span<const Report>(items.data(), 1), 3.0) == std::vector<Report>{items[0]});
}

TEST_CASE("merged observations keep their earliest delivery", "[report_merging]") {
  // Generated at tick 4, delivered at 6 and 4: the cluster was there from tick 4.
  const std::vector<Observation> items{Observation{4, 6, 1, 0.0, 0.0, 0, 10, {}},
                                       Observation{4, 4, 2, 0.5, 0.0, 0, 20, {}}};
  const auto merged = mergeNearby(std::span<const Observation>(items), 1.0);
  REQUIRE(merged.size() == 1);
  CHECK(merged[0].tick_delivered == 4);
  CHECK(merged[0].sensor == 2);
  CHECK(merged[0].x == Approx(1.0 / 3.0));  // (0 x 10 + 0.5 x 20) / 30
}

TEST_CASE("the reach from the strongest report is the radius that joins one target's reports",
          "[report_merging]") {
  // Strongest at (1, 1); the others at (0, 1) (distance 1) and (2, 2) (distance sqrt 2).
  const std::vector<Report> items{report(1, 0, 1, 0, 10), report(2, 1, 1, 0, 99), report(3, 2, 2, 0, 50)};
  const double reach = reachFromStrongest(std::span<const Report>(items));
  CHECK(reach == Approx(std::sqrt(2.0)));
  // At that radius the three are one cluster; just below it, (2, 2) is a cluster of its own.
  CHECK(mergeNearby(std::span<const Report>(items), reach).size() == 1);
  CHECK(mergeNearby(std::span<const Report>(items), reach * 0.999).size() == 2);
  CHECK(reachFromStrongest(std::span<const Report>(items.data(), 1)) == 0.0);
}

}  // namespace
}  // namespace wsn::common

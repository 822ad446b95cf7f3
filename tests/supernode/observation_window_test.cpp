#include "supernode/observation_window.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <stdexcept>
#include <vector>

#include "tests/supernode/test_support.hpp"

namespace wsn::supernode {
namespace {

using test::observation;

common::Observation withSensor(std::int32_t tick, common::SensorId sensor, double x, double y) {
  return common::Observation{tick, tick, sensor, x, y, 0};
}

TEST_CASE("the oldest tick of the window is max(1, newest - ws + 1)", "[window]") {
  ObservationWindow window(10);
  CHECK(window.newestTick() == 0);
  window.advanceTo(3);
  CHECK(window.oldestTick() == 1);  // 3 - 10 + 1 = -6, clamped to the first tick
  window.advanceTo(15);
  CHECK(window.oldestTick() == 6);  // 15 - 10 + 1
  CHECK(window.newestTick() == 15);
}

TEST_CASE("an observation goes into the slot of the tick it was generated, in canonical order", "[window]") {
  ObservationWindow window(3);
  window.advanceTo(5);  // slots 3, 4, 5
  CHECK(window.insert(withSensor(4, 7, 1.0, 1.0)));
  CHECK(window.insert(withSensor(4, 2, 9.0, 9.0)));
  CHECK(window.insert(withSensor(5, 2, 1.0, 3.0)));
  CHECK(window.insert(withSensor(5, 2, 0.5, 3.0)));
  CHECK(window.insert(withSensor(5, 2, 0.5, 2.0)));

  const auto four = window.slot(4);
  REQUIRE(four.size() == 2);
  CHECK(four[0].sensor == 2);  // sensor first, whatever the arrival order
  CHECK(four[1].sensor == 7);
  const auto five = window.slot(5);
  REQUIRE(five.size() == 3);
  CHECK(five[0].x == 0.5);  // same sensor: by x, then y
  CHECK(five[0].y == 2.0);
  CHECK(five[1].x == 0.5);
  CHECK(five[1].y == 3.0);
  CHECK(five[2].x == 1.0);
  CHECK(window.slot(3).empty());
  CHECK(window.size() == 5);
  CHECK(window.droppedStale() == 0);
}

TEST_CASE("a slot holds the same observations in the same order for every arrival order", "[window]") {
  // Observations that differ only in a tie-breaking field (delivery tick, target, power level,
  // measurement) too: the supernode files deliveries unsorted, so the order must be total.
  common::Measurement bearing;
  bearing.kind = common::MeasurementKind::bearing;
  bearing.values = {0.5};
  bearing.sensor = common::SensorPose{1.0, 1.0, 0.0};
  std::vector<common::Observation> arrivals = {
      withSensor(4, 3, 1.0, 1.0), withSensor(4, 3, 1.0, 1.0), withSensor(4, 1, 2.0, 2.0), withSensor(4, 3, 1.0, 1.0),
      withSensor(4, 3, 1.0, 1.0), withSensor(4, 3, 1.0, 1.0)};
  arrivals[1].tick_delivered = 5;
  arrivals[3].power_level = 2;
  arrivals[4].measurement = common::MeasurementRef(bearing);
  arrivals[5].target = 9;

  std::vector<std::size_t> order(arrivals.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::vector<common::Observation> first;
  int permutations = 0;
  do {
    ObservationWindow window(3);
    window.advanceTo(5);
    for (const std::size_t i : order) window.insert(arrivals[i]);
    const auto slot = window.slot(4);
    const std::vector<common::Observation> filed(slot.begin(), slot.end());
    if (first.empty()) first = filed;
    REQUIRE(filed == first);
    ++permutations;
  } while (std::next_permutation(order.begin(), order.end()));
  CHECK(permutations == 720);  // 6!
  CHECK(first.front().sensor == 1);
}

TEST_CASE("observations older than the window or from the future are dropped and counted", "[window]") {
  ObservationWindow window(3);
  window.advanceTo(5);
  CHECK_FALSE(window.insert(observation(2, 5, 1.0, 1.0)));  // 2 < oldest 3
  CHECK_FALSE(window.insert(observation(6, 5, 1.0, 1.0)));  // not generated yet
  CHECK(window.insert(observation(3, 5, 1.0, 1.0)));        // exactly the oldest slot
  CHECK(window.droppedStale() == 2);
  CHECK(window.size() == 1);

  ObservationWindow empty(3);  // nothing can be filed before the first advance
  CHECK_FALSE(empty.insert(observation(1, 1, 1.0, 1.0)));
  CHECK(empty.droppedStale() == 1);
}

TEST_CASE("sliding the window drops the slots that leave it and keeps the rest", "[window]") {
  ObservationWindow window(3);
  window.advanceTo(5);
  for (std::int32_t t = 3; t <= 5; ++t) REQUIRE(window.insert(observation(t, 5, t, 1.0)));

  window.advanceTo(6);  // slots 4, 5, 6
  CHECK(window.slot(3).empty());
  REQUIRE(window.slot(4).size() == 1);
  CHECK(window.slot(4)[0].x == 4.0);
  REQUIRE(window.slot(5).size() == 1);
  CHECK(window.slot(6).empty());
  CHECK(window.size() == 2);

  window.advanceTo(4);  // ticks only move forward: no effect
  CHECK(window.newestTick() == 6);
  CHECK(window.size() == 2);

  window.advanceTo(20);  // a jump longer than the window empties it
  CHECK(window.oldestTick() == 18);
  CHECK(window.size() == 0);
  CHECK(window.insert(observation(18, 20, 1.0, 1.0)));
  CHECK(window.slot(18).size() == 1);
}

TEST_CASE("a window of fewer than one tick is rejected", "[window]") {
  CHECK_THROWS_AS(ObservationWindow(0), std::invalid_argument);
}

TEST_CASE("a merged window merges each slot and keeps the canonical order", "[window]") {
  ObservationWindow window(3);
  window.advanceTo(2);
  // Tick 1: two reports 0.5 apart (one cluster) and one 10 away; tick 2: one report.
  window.insert(withSensor(1, 7, 10.0, 10.0));
  window.insert(withSensor(1, 3, 10.5, 10.0));
  window.insert(withSensor(1, 9, 20.0, 10.0));
  window.insert(withSensor(2, 4, 30.0, 30.0));
  const ObservationWindow merged = window.merged(1.0);
  REQUIRE(merged.slot(1).size() == 2);
  // Equal levels: the first in canonical order (sensor 3) is the strongest; the mean is 10.25.
  CHECK(merged.slot(1)[0].sensor == 3);
  CHECK(merged.slot(1)[0].x == 10.25);
  CHECK(merged.slot(1)[1].sensor == 9);
  REQUIRE(merged.slot(2).size() == 1);
  CHECK(merged.slot(2)[0] == window.slot(2)[0]);
  CHECK(merged.newestTick() == 2);
  CHECK(merged.oldestTick() == window.oldestTick());
  // Radius 0: the same window.
  const ObservationWindow same = window.merged(0.0);
  for (std::int32_t t = 1; t <= 2; ++t)
    CHECK(std::vector<common::Observation>(same.slot(t).begin(), same.slot(t).end()) ==
          std::vector<common::Observation>(window.slot(t).begin(), window.slot(t).end()));
}

}  // namespace
}  // namespace wsn::supernode

// Waypoint targets in the truth: exact motion along the route, stops, the end.
#include <catch2/catch.hpp>
#include <cstdint>
#include <vector>

#include "common/truth.hpp"

namespace wsn::common {
namespace {

TargetSpec route(std::int32_t appear, std::vector<Vec2> waypoints, double speed, std::vector<WaypointStop> stops = {}) {
  TargetSpec t;
  t.appear_tick = appear;
  t.waypoints = std::move(waypoints);
  t.speed = speed;
  t.stops = std::move(stops);
  t.position = t.waypoints.front();
  return t;
}

/// Target 0's states at ticks 1..ticks; a tick it is not alive has no entry.
struct Sample {
  std::int32_t tick;
  TargetState state;
};
std::vector<Sample> trajectory(const TargetSpec& spec, std::int32_t ticks) {
  Scenario s;
  s.run.ticks = ticks;
  s.targets.scripted = {spec};
  const Truth truth(truthConfig(s));
  std::vector<Sample> out;
  for (std::int32_t t = 1; t <= ticks; ++t)
    for (const auto& target : truth.at(t))
      if (target.id == 0) out.push_back({t, target});
  return out;
}

void checkState(const Sample& sample, std::int32_t tick, double x, double y, double vx, double vy) {
  INFO("tick " << tick);
  CHECK(sample.tick == tick);
  CHECK(sample.state.x == Approx(x).margin(1e-12));
  CHECK(sample.state.y == Approx(y).margin(1e-12));
  CHECK(sample.state.vx == Approx(vx).margin(1e-12));
  CHECK(sample.state.vy == Approx(vy).margin(1e-12));
}

TEST_CASE("a waypoint target passing a vertex mid-tick goes on along the next leg and ends at the last", "[truth]") {
  // East 10 then north 20 at 4 per tick: x = 10, 14, 18 at ticks 1-3; tick 4 covers the 2 left to
  // (20, 10) and 4 - 2 = 2 up the next leg, (20, 12), now heading north. Then y = 16, 20, 24, 28
  // at ticks 5-8; tick 9 has 2 left and ends at (20, 30), still; tick 10 it is gone.
  const auto samples = trajectory(route(1, {{10, 10}, {20, 10}, {20, 30}}, 4.0), 20);
  REQUIRE(samples.size() == 9);
  checkState(samples[0], 1, 10, 10, 4, 0);
  checkState(samples[2], 3, 18, 10, 4, 0);
  checkState(samples[3], 4, 20, 12, 0, 4);
  checkState(samples[7], 8, 20, 28, 0, 4);
  checkState(samples[8], 9, 20, 30, 0, 0);
}

TEST_CASE("a waypoint target with speeds accelerates uniformly along a leg and keeps the next leg's speed", "[truth]") {
  // East 30 from 2 to 4 per tick, then north at 4: a = (4^2 - 2^2) / (2 x 30) = 0.2 per tick^2, so t
  // ticks after it appears s = 2t + 0.1 t^2 and v = 2 + 0.2 t. Tick 6 (t = 5): s = 12.5, v = 3.
  // At t = 10 it reaches (30, 0) at 4 exactly; tick 12 (t = 11) is 4 up the next leg, (30, 4).
  TargetSpec spec = route(1, {{0, 0}, {30, 0}, {30, 30}}, 0.0);
  spec.speeds = {2.0, 4.0, 4.0};
  const auto samples = trajectory(spec, 13);
  REQUIRE(samples.size() == 13);
  checkState(samples[0], 1, 0, 0, 2, 0);
  checkState(samples[1], 2, 2.1, 0, 2.2, 0);
  checkState(samples[5], 6, 12.5, 0, 3, 0);
  checkState(samples[9], 10, 26.1, 0, 3.8, 0);
  checkState(samples[11], 12, 30, 4, 0, 4);
  checkState(samples[12], 13, 30, 8, 0, 4);
}

TEST_CASE("a waypoint target slowing into a waypoint carries the tick's time left onto the next leg", "[truth]") {
  // East 10 from 6 to 4 per tick: a = (16 - 36) / 20 = -1. Tick 2 (t = 1): s = 6 - 0.5 = 5.5, v = 5.
  // It reaches (10, 0) at t = (4 - 6) / -1 = 2, so tick 3 ends exactly there, at 4 heading north.
  // Tick 4 is one tick of the second leg, 4 to 8 per tick over 20: a = (64 - 16) / 40 = 1.2,
  // s = 4 + 0.6 = 4.6 and v = 5.2.
  TargetSpec spec = route(1, {{0, 0}, {10, 0}, {10, 20}}, 0.0);
  spec.speeds = {6.0, 4.0, 8.0};
  const auto samples = trajectory(spec, 4);
  REQUIRE(samples.size() == 4);
  checkState(samples[1], 2, 5.5, 0, 5, 0);
  checkState(samples[2], 3, 10, 0, 0, 4);
  checkState(samples[3], 4, 10, 4.6, 0, 5.2);
}

TEST_CASE("a waypoint target halts the stop's ticks at rest, then drives on", "[truth]") {
  // East along y = 10 at 3 per tick: x = 10, 13, 16, 19 at ticks 1-4. Tick 5 reaches (20, 10)
  // with 2 to spare, but the stop ends the tick there; ticks 6 and 7 are the 2 ticks of rest. Tick
  // 8 moves 3 to (23, 10), then 26, 29, and tick 11 ends at (30, 10). Tick 12 it is gone.
  const auto samples = trajectory(route(1, {{10, 10}, {20, 10}, {30, 10}}, 3.0, {{1, 2}}), 20);
  REQUIRE(samples.size() == 11);
  checkState(samples[3], 4, 19, 10, 3, 0);
  checkState(samples[4], 5, 20, 10, 0, 0);
  checkState(samples[5], 6, 20, 10, 0, 0);
  checkState(samples[6], 7, 20, 10, 0, 0);
  checkState(samples[7], 8, 23, 10, 3, 0);
  checkState(samples[10], 11, 30, 10, 0, 0);
}

TEST_CASE("stops at the first and the last waypoint hold the target there", "[truth]") {
  // Appearing at tick 3 with 1 tick of rest at (0, 0): still at ticks 3 and 4. Then 5 per tick:
  // (5, 0) at tick 5, (10, 0) at tick 6, where 2 ticks of rest keep it at ticks 7 and 8. Gone at 9.
  const auto samples = trajectory(route(3, {{0, 0}, {10, 0}}, 5.0, {{0, 1}, {1, 2}}), 20);
  REQUIRE(samples.size() == 6);
  checkState(samples[0], 3, 0, 0, 0, 0);
  checkState(samples[1], 4, 0, 0, 0, 0);
  checkState(samples[2], 5, 5, 0, 5, 0);
  checkState(samples[3], 6, 10, 0, 0, 0);
  checkState(samples[5], 8, 10, 0, 0, 0);
}

TEST_CASE("disappear_tick ends a waypoint target before its last waypoint", "[truth]") {
  // The first case's route, gone from tick 5: alive at ticks 1-4 only.
  TargetSpec spec = route(1, {{10, 10}, {20, 10}, {20, 30}}, 4.0);
  spec.disappear_tick = 5;
  const auto samples = trajectory(spec, 20);
  REQUIRE(samples.size() == 4);
  checkState(samples[3], 4, 20, 12, 0, 4);
}

TEST_CASE("a waypoint target leaves the other targets where they were", "[truth]") {
  // A route draws nothing from the random streams, so a noisy scripted target beside it moves the
  // same with and without it. (Random births would not compare: their ids, which key their
  // streams, follow the scripted ones.)
  Scenario s;
  s.run.ticks = 30;
  TargetSpec noisy;
  noisy.position = {50, 50};
  noisy.velocity = {0.5, 0.5};
  s.targets.scripted = {noisy};
  const Truth without(truthConfig(s));
  s.targets.scripted.push_back(route(1, {{0, 0}, {100, 100}}, 2.0));
  const Truth with(truthConfig(s));
  for (std::int32_t t = 1; t <= 30; ++t) {
    INFO("tick " << t);
    REQUIRE(without.at(t).size() == 1);
    REQUIRE(with.at(t).size() == 2);  // the route is 100 sqrt 2 = 141 long: 71 ticks at 2
    CHECK(with.at(t).front() == without.at(t).front());
  }
}

TEST_CASE("the truth carries a scripted target's class", "[truth]") {
  Scenario s;
  TargetSpec tank = route(1, {{0, 0}, {10, 0}}, 1.0);
  tank.target_class = TargetClass::kTracked;
  s.targets.scripted = {tank};
  s.targets.count = 1;
  const Truth truth(truthConfig(s));
  CHECK(truth.targetClass(0) == TargetClass::kTracked);
  CHECK(truth.targetClass(1) == TargetClass::kUnknown);  // drawn
  CHECK(truth.targetClass(7) == TargetClass::kUnknown);  // no such target
}

}  // namespace
}  // namespace wsn::common

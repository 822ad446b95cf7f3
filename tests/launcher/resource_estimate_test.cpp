// The resource estimate behind `wsntrack validate`'s warnings (launcher/resource_estimate.cpp): the
// counts it starts from, and warnings for huge scenarios only.
#include "launcher/resource_estimate.hpp"

#include <catch2/catch.hpp>
#include <cmath>

namespace wsn::launcher {
namespace {

common::Scenario defaultLike() {
  common::Scenario scenario;  // a 100 x 100 grid at spacing 1, range 11.6, 100 ticks
  scenario.supernodes = {{25, 25}, {75, 25}, {25, 75}, {75, 75}};
  common::TargetSpec target;
  target.appear_tick = 1;
  target.disappear_tick = 61;
  scenario.targets.scripted.assign(10, target);
  return scenario;
}

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

TEST_CASE("the estimate counts sensors, neighbours and target-ticks of the scenario", "[launcher][estimate]") {
  const auto e = estimateResources(defaultLike());
  CHECK(e.sensors == 10000);
  CHECK(e.neighbours == Approx(M_PI * 11.6 * 11.6));
  CHECK(e.targets == 10);
  CHECK(e.target_ticks == 600);  // ticks 1 .. 60 each
  CHECK(e.seconds < 10);
  CHECK(e.memory_bytes < 100e6);
  // The default scenario fits any machine with a gigabyte.
  CHECK(resourceWarnings(e, 1 * kGiB).empty());
}

TEST_CASE("a 10^7-sensor grid warns about time, 100000 born targets too", "[launcher][estimate]") {
  auto huge = defaultLike();
  huge.sensors.spacing = 0.0317;  // 3154^2 = 9.95e6 sensors
  const auto grid = estimateResources(huge);
  CHECK(grid.sensors == 3154.0 * 3154.0);
  const auto warnings = resourceWarnings(grid, 24 * kGiB);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].rfind("warning: estimated run time ", 0) == 0);
  CHECK(warnings[0].find("9.95M sensors") != std::string::npos);
  // On a small machine the memory warns as well.
  CHECK(resourceWarnings(grid, 2 * kGiB).size() == 2);

  auto crowded = defaultLike();
  crowded.targets.birth_rate = 0.1;  // 1000 births a tick over 100 x 100, for 100 ticks
  const auto born = estimateResources(crowded);
  CHECK(born.targets == Approx(100010));
  const auto crowded_warnings = resourceWarnings(born, 24 * kGiB);
  REQUIRE(crowded_warnings.size() == 1);
  CHECK(crowded_warnings[0].find("100k targets") != std::string::npos);
}

TEST_CASE("a random layout counts its sensors and never more neighbours than sensors", "[launcher][estimate]") {
  auto scenario = defaultLike();
  scenario.sensors.kind = common::SensorLayoutConfig::Kind::kRandom;
  scenario.sensors.count = 50;
  const auto e = estimateResources(scenario);
  CHECK(e.sensors == 50);
  CHECK(e.neighbours == 50);
}

TEST_CASE("MemTotal is read from /proc/meminfo", "[launcher][estimate]") {
  CHECK(totalRamBytes() > 64e6);
}

}  // namespace
}  // namespace wsn::launcher

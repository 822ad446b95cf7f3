// The scenario's terrain section and waypoint targets: read, checked with file:line errors, and
// written back into a resolved scenario that reads back to the same scenario.
#include <catch2/catch.hpp>
#include <string>

#include "scenario/writer.hpp"
#include "tests/scenario/test_support.hpp"

namespace wsn::scenario {
namespace {

using namespace common;

using Catch::Matchers::Contains;

using test_support::errorOf;
using test_support::parse;

/// Two roads meeting at (50, 50), a building and a wood, in the default region [0, 100]^2.
const std::string kTerrain =
    "terrain:\n"
    "  roads:\n"
    "    - name: main\n"
    "      points: [[0, 0], [50, 50], [100, 50]]\n"
    "    - {name: side, points: [[50, 50], [50, 100]]}\n"
    "  masks:\n"
    "    - {name: depot, kind: building, polygon: [[60, 60], [80, 60], [80, 80], [60, 80]]}\n"
    "    - {name: wood, kind: vegetation, polygon: [[10, 60], [30, 60], [20, 90]]}\n";

TEST_CASE("a terrain section gives named roads and masks that a resolved scenario keeps", "[scenario][terrain]") {
  const Scenario s = parse(kTerrain);
  REQUIRE(s.terrain.roads.size() == 2);
  CHECK(s.terrain.roads[0].name == "main");
  CHECK(s.terrain.roads[0].points == std::vector<Vec2>{{0, 0}, {50, 50}, {100, 50}});
  CHECK(s.terrain.roads[1].points == std::vector<Vec2>{{50, 50}, {50, 100}});
  REQUIRE(s.terrain.masks.size() == 2);
  CHECK(s.terrain.masks[0].kind == MaskKind::kBuilding);
  CHECK(s.terrain.masks[1].kind == MaskKind::kVegetation);
  CHECK(s.terrain.masks[1].polygon.size() == 3);

  const std::string resolved = resolvedScenarioYaml(s);
  CHECK_THAT(resolved, Contains("terrain:\n  roads:\n    - {name: \"main\", points: [["));
  CHECK_THAT(resolved, Contains("    - {name: \"depot\", kind: building, polygon: [["));
  CHECK(parse(resolved) == s);

  // The sections the terrain makes: main splits at (50, 50), where side starts.
  CHECK(Terrain(s.terrain).sections().size() == 3);
}

TEST_CASE("a scenario without terrain writes no terrain section", "[scenario][terrain]") {
  const Scenario s = parse("name: plain\n");
  CHECK(s.terrain.empty());
  CHECK_THAT(resolvedScenarioYaml(s), !Contains("terrain"));
  // An empty section is no terrain either.
  CHECK(parse("terrain: {}\n").terrain.empty());
  CHECK_THAT(resolvedScenarioYaml(parse("terrain:\n  roads: []\n")), !Contains("terrain"));
}

TEST_CASE("terrain errors name the line and what was expected", "[scenario][terrain][errors]") {
  // A road of one point.
  CHECK(errorOf("terrain:\n  roads:\n    - {name: r, points: [[0, 0]]}\n") ==
        "s.yaml:3: 'terrain.roads[0].points' has 1 point; a road needs at least 2");
  // A polygon of two points.
  CHECK(errorOf("terrain:\n  masks:\n    - {name: m, kind: building, polygon: [[0, 0], [5, 5]]}\n") ==
        "s.yaml:3: 'terrain.masks[0].polygon' has 2 points; a polygon needs at least 3");
  // A bow tie: (0, 0)-(10, 10) crosses (10, 0)-(0, 10) at (5, 5).
  CHECK(errorOf("terrain:\n  masks:\n    - name: m\n      kind: building\n"
                "      polygon: [[0, 0], [10, 10], [10, 0], [0, 10]]\n") ==
        "s.yaml:5: 'terrain.masks[0].polygon' is not a simple polygon: its edges cross or fold back, or it has no "
        "area; expected an outline that goes round once");
  // An unknown kind, on its own line.
  CHECK_THAT(errorOf("terrain:\n  masks:\n    - name: m\n      kind: rock\n      polygon: [[0, 0], [5, 0], [5, 5]]\n"),
             Contains("s.yaml:4: 'terrain.masks[0].kind'") && Contains("building, vegetation") && Contains("rock"));
  // A point outside the default region [0, 100]^2, on its own line (the sixth).
  CHECK(errorOf("terrain:\n  roads:\n    - name: r\n      points:\n        - [0, 0]\n        - [150, 0]\n") ==
        "s.yaml:6: 'terrain.roads[0].points[1]' (150, 0) is outside the region [0, 100] x [0, 100]");
  // Two roads of one name: the second name's line.
  CHECK(errorOf("terrain:\n  roads:\n    - {name: r, points: [[0, 0], [1, 1]]}\n"
                "    - name: r\n      points: [[2, 2], [3, 3]]\n") ==
        "s.yaml:4: 'terrain.roads[1].name' 'r' is already the name of 'terrain.roads[0]'; expected unique names");
  // A road that stands still between two points.
  CHECK(errorOf("terrain:\n  roads:\n    - name: r\n      points:\n        - [0, 0]\n        - [0, 0]\n") ==
        "s.yaml:6: 'terrain.roads[0].points[1]' (0, 0) repeats the point before it; expected a leg of nonzero length");
  // A mask without its kind.
  CHECK_THAT(errorOf("terrain:\n  masks:\n    - {name: m, polygon: [[0, 0], [5, 0], [5, 5]]}\n"),
             Contains("s.yaml:3:") && Contains("kind"));
  // An unknown key.
  CHECK_THAT(errorOf("terrain:\n  rivers: []\n"), Contains("s.yaml:2: unknown key 'rivers' in 'terrain'"));
}

TEST_CASE("a waypoint target starts at its first waypoint and reads back the same", "[scenario][terrain]") {
  const Scenario s = parse(
      "targets:\n  scripted:\n"
      "    - {waypoints: [[10, 10], [20, 10], [20, 30]], speed: 4, stops: [{at: 1, ticks: 2}], class: tracked}\n"
      "    - {x: 5, y: 5, vx: 1, vy: 0, class: human}\n");
  REQUIRE(s.targets.scripted.size() == 2);
  const TargetSpec& route = s.targets.scripted[0];
  CHECK(route.position == Vec2{10, 10});
  CHECK(route.velocity == Vec2{4, 0});  // speed 4 along the first leg, east
  CHECK(route.speed == 4.0);
  CHECK(route.stops == std::vector<WaypointStop>{{1, 2}});
  CHECK(route.target_class == TargetClass::kTracked);
  CHECK(s.targets.scripted[1].target_class == TargetClass::kHuman);

  const std::string resolved = resolvedScenarioYaml(s);
  CHECK_THAT(resolved, Contains("waypoints: [["));
  CHECK_THAT(resolved, Contains("stops: [{at: 1, ticks: 2}], class: tracked}"));
  CHECK_THAT(resolved, !Contains("vx: 4"));
  CHECK(parse(resolved) == s);
}

TEST_CASE("a waypoint target with a speed per waypoint starts at the first and reads back the same", "[scenario][terrain]") {
  const Scenario s = parse("targets:\n  scripted:\n    - {waypoints: [[10, 10], [10, 40], [40, 40]], speeds: [2, 4, 4]}\n");
  const TargetSpec& route = s.targets.scripted.at(0);
  CHECK(route.speeds == std::vector<double>{2, 4, 4});
  CHECK(route.speed == 0.0);
  CHECK(route.velocity == Vec2{0, 2});  // the first waypoint's speed, north
  CHECK(route.topSpeed() == 4.0);
  const std::string resolved = resolvedScenarioYaml(s);
  CHECK_THAT(resolved, Contains("speeds: [2, 4, 4]"));
  CHECK(parse(resolved) == s);
}

TEST_CASE("speeds errors name the line and what was expected", "[scenario][terrain][errors]") {
  CHECK(errorOf("targets:\n  scripted:\n    - {waypoints: [[0, 0], [5, 0]], speeds: [1, 2, 3]}\n") ==
        "s.yaml:3: 'targets.scripted[0].speeds' has 3 speeds for 2 waypoints; expected one per waypoint");
  CHECK(errorOf("targets:\n  scripted:\n    - {waypoints: [[0, 0], [5, 0]], speed: 1, speeds: [1, 2]}\n") ==
        "s.yaml:3: 'targets.scripted[0].speeds' and 'speed' both given; expected one speed for the route or one per "
        "waypoint, not both");
  CHECK_THAT(errorOf("targets:\n  scripted:\n    - {waypoints: [[0, 0], [5, 0]], speeds: [1, 0]}\n"),
             Contains("s.yaml:3:") && Contains("'targets.scripted[0].speeds[1]'") && Contains("(0, 1e6]"));
  CHECK_THAT(errorOf("targets:\n  scripted:\n    - {waypoints: [[0, 0], [5, 0]], speeds: 3}\n"),
             Contains("s.yaml:3: 'targets.scripted[0].speeds' must be a list of speeds, one per waypoint"));
  CHECK(errorOf("targets:\n  scripted:\n    - {x: 1, y: 1, vx: 0, vy: 0, speeds: [1, 2]}\n") ==
        "s.yaml:3: 'targets.scripted[0].speeds' applies only with 'waypoints'");
}

TEST_CASE("a scripted target without a class writes what it wrote before", "[scenario][terrain]") {
  const Scenario s = parse("targets:\n  scripted:\n    - {x: 5, y: 5, vx: 1, vy: 0}\n");
  CHECK(s.targets.scripted[0].target_class == TargetClass::kUnknown);
  // (", class:" and ", speed:" since targets.speed_class holds both words.)
  CHECK_THAT(resolvedScenarioYaml(s), !Contains(", class:") && !Contains("waypoints") && !Contains(", speed:"));
}

TEST_CASE("waypoint errors name the line and what was expected", "[scenario][terrain][errors]") {
  // A start given twice.
  CHECK(errorOf("targets:\n  scripted:\n    - waypoints: [[0, 0], [5, 0]]\n      speed: 1\n      x: 3\n") ==
        "s.yaml:5: 'targets.scripted[0].x' does not apply with 'waypoints': the target starts at the first waypoint "
        "and moves at 'speed'");
  // No speed.
  CHECK_THAT(errorOf("targets:\n  scripted:\n    - waypoints: [[0, 0], [5, 0]]\n"),
             Contains("s.yaml:3:") && Contains("speed"));
  // A speed without waypoints.
  CHECK(errorOf("targets:\n  scripted:\n    - {x: 1, y: 1, vx: 0, vy: 0, speed: 2}\n") ==
        "s.yaml:3: 'targets.scripted[0].speed' applies only with 'waypoints'");
  // One waypoint.
  CHECK(errorOf("targets:\n  scripted:\n    - {waypoints: [[0, 0]], speed: 1}\n") ==
        "s.yaml:3: 'targets.scripted[0].waypoints' has 1 point; a route needs at least 2");
  // A waypoint outside the region.
  CHECK(errorOf("targets:\n  scripted:\n    - {waypoints: [[0, 0], [0, 101]], speed: 1}\n") ==
        "s.yaml:3: 'targets.scripted[0].waypoints[1]' (0, 101) is outside the region [0, 100] x [0, 100]");
  // A stop at waypoint 2 of a route of waypoints 0 and 1.
  CHECK(errorOf("targets:\n  scripted:\n    - waypoints: [[0, 0], [5, 0]]\n      speed: 1\n"
                "      stops:\n        - {at: 2, ticks: 3}\n") ==
        "s.yaml:6: 'targets.scripted[0].stops[0].at' 2 is not a waypoint; expected 0 to 1");
  // Stops out of route order.
  CHECK(errorOf("targets:\n  scripted:\n    - waypoints: [[0, 0], [5, 0], [5, 5]]\n      speed: 1\n"
                "      stops:\n        - {at: 1, ticks: 3}\n        - {at: 1, ticks: 1}\n") ==
        "s.yaml:7: 'targets.scripted[0].stops[1].at' 1 must come after the previous stop's waypoint 1; expected "
        "stops in route order, one per waypoint");
  // A stop of no ticks.
  CHECK_THAT(errorOf("targets:\n  scripted:\n    - {waypoints: [[0, 0], [5, 0]], speed: 1, stops: [{at: 0, ticks: 0}]}\n"),
             Contains("s.yaml:3: 'targets.scripted[0].stops[0].ticks'"));
  // An unknown class.
  CHECK_THAT(errorOf("targets:\n  scripted:\n    - {x: 1, y: 1, vx: 0, vy: 0, class: tank}\n"),
             Contains("s.yaml:3: 'targets.scripted[0].class'") && Contains("wheeled_light"));
}

}  // namespace
}  // namespace wsn::scenario

#include "common/terrain.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

namespace wsn::common {
namespace {

/// The square [40, 60]^2, counter-clockwise.
const std::vector<Vec2> kBlock{{40.0, 40.0}, {60.0, 40.0}, {60.0, 60.0}, {40.0, 60.0}};

Terrain withMask(MaskKind kind, std::vector<Vec2> polygon) {
  TerrainConfig config;
  config.masks.push_back({"mask", kind, std::move(polygon)});
  return Terrain(config);
}

TEST_CASE("a projection finds the nearest section, the distance along it and its direction", "[terrain]") {
  // main runs east through (100, 0), where side starts north: a junction, so main has two sections.
  TerrainConfig config;
  config.roads.push_back({"main", {{0.0, 0.0}, {100.0, 0.0}, {200.0, 0.0}}});
  config.roads.push_back({"side", {{100.0, 0.0}, {100.0, 50.0}}});
  const Terrain terrain(config);
  REQUIRE(terrain.sections().size() == 3);

  // (150, 10): 10 from main's second section (foot (150, 0)), 50 from side (foot (100, 10)).
  // Along is measured from the section's start (100, 0): 150 - 100 = 50.
  const auto east = terrain.project({150.0, 10.0});
  REQUIRE(east);
  CHECK(east->section == 1);
  CHECK(east->foot == Vec2{150.0, 0.0});
  CHECK(east->distance == Approx(10.0));
  CHECK(east->along == Approx(50.0));
  CHECK(east->direction == Vec2{1.0, 0.0});

  // (103, 30): 3 from side (foot (100, 30), 30 along it), 30 from main (foot (103, 0)).
  const auto north = terrain.project({103.0, 30.0});
  REQUIRE(north);
  CHECK(north->section == 2);
  CHECK(north->foot == Vec2{100.0, 30.0});
  CHECK(north->distance == Approx(3.0));
  CHECK(north->along == Approx(30.0));
  CHECK(north->direction == Vec2{0.0, 1.0});

  CHECK_FALSE(Terrain().project({0.0, 0.0}));
}

TEST_CASE("a projection names the segment of the section that holds the foot", "[terrain]") {
  // One section that bends at (10, 0): (12, 5) is 2 from its second segment (foot (10, 5)) and
  // 5.4 from the first's end, so the foot is on segment 1, 10 + 5 = 15 along the section.
  TerrainConfig config;
  config.roads.push_back({"bend", {{0.0, 0.0}, {10.0, 0.0}, {10.0, 10.0}}});
  const Terrain terrain(config);
  const auto p = terrain.project({12.0, 5.0});
  REQUIRE(p);
  CHECK(p->segment == 1);
  CHECK(p->foot == Vec2{10.0, 5.0});
  CHECK(p->along == Approx(15.0));
  CHECK(terrain.project({4.0, -1.0})->segment == 0);
}

TEST_CASE("a position past a dead end is off the road, one beside it or past a junction is not", "[terrain]") {
  // main runs east from (0, 0) to (200, 0), a dead end at both ends; side runs north from main's
  // vertex (100, 0), a junction, to (100, 50), a dead end.
  TerrainConfig config;
  config.roads.push_back({"main", {{0.0, 0.0}, {100.0, 0.0}, {200.0, 0.0}}});
  config.roads.push_back({"side", {{100.0, 0.0}, {100.0, 50.0}}});
  const Terrain terrain(config);
  REQUIRE(terrain.sections().size() == 3);
  CHECK(terrain.sections()[0].dead_end_first);
  CHECK_FALSE(terrain.sections()[0].dead_end_last);  // the junction
  CHECK_FALSE(terrain.sections()[1].dead_end_first);
  CHECK(terrain.sections()[1].dead_end_last);
  CHECK_FALSE(terrain.sections()[2].dead_end_first);
  CHECK(terrain.sections()[2].dead_end_last);

  // 5 past main's east end: the foot is the end, 5 away, and the target has left the road.
  const auto east = terrain.project({205.0, 0.0});
  REQUIRE(east);
  CHECK(east->foot == Vec2{200.0, 0.0});
  CHECK(east->distance == Approx(5.0));
  CHECK(east->past_dead_end);
  CHECK(terrain.project({-3.0, 1.0})->past_dead_end);  // past the west end, a little aside
  CHECK(terrain.project({102.0, 58.0})->past_dead_end);  // past side's end
  // Beside the road, even at its very end, it is on the road's gate as before.
  CHECK_FALSE(terrain.project({200.0, 4.0})->past_dead_end);
  CHECK_FALSE(terrain.project({150.0, -4.0})->past_dead_end);
  // Around the junction the foot is never a dead end: (104, -2) projects onto main.
  CHECK_FALSE(terrain.project({104.0, -2.0})->past_dead_end);
}

TEST_CASE("the foot point on a polyline measures its distance along from the first point", "[terrain]") {
  // East 100, then north 100: (97, 60) is 3 from the second segment, at 100 + 60 = 160 along.
  const std::vector<Vec2> bend{{0.0, 0.0}, {100.0, 0.0}, {100.0, 100.0}};
  const auto foot = footPoint(bend, {97.0, 60.0});
  REQUIRE(foot);
  CHECK(foot->segment == 1);
  CHECK(foot->distance == Approx(3.0));
  CHECK(foot->along == Approx(160.0));
}

TEST_CASE("junctions are the vertices roads share exactly, and they split roads into sections", "[terrain]") {
  TerrainConfig config;
  config.roads.push_back({"a", {{0.0, 0.0}, {50.0, 50.0}, {100.0, 0.0}}});      // b starts at its middle vertex
  config.roads.push_back({"b", {{50.0, 50.0}, {50.0, 100.0}}});                 // ends on c's vertex
  config.roads.push_back({"c", {{0.0, 100.0}, {50.0, 100.0}, {100.0, 100.0}}});
  // d crosses a at (25, 25) and (75, 25) with no shared vertex: a bridge, not a junction.
  config.roads.push_back({"d", {{0.0, 25.0}, {100.0, 25.0}}});
  // e passes (50, 50.000001), close to the junction but not on it.
  config.roads.push_back({"e", {{40.0, 50.000001}, {50.0, 50.000001}, {60.0, 50.000001}}});
  const Terrain terrain(config);

  // Two junctions, ordered by (x, y): (50, 50) of a and b, (50, 100) of b and c.
  REQUIRE(terrain.junctions().size() == 2);
  CHECK(terrain.junctions()[0].point == Vec2{50.0, 50.0});
  CHECK(terrain.junctions()[0].roads == std::vector<std::size_t>{0, 1});
  CHECK(terrain.junctions()[1].point == Vec2{50.0, 100.0});
  CHECK(terrain.junctions()[1].roads == std::vector<std::size_t>{1, 2});

  // Sections: a 2 (split at (50, 50)), b 1 (junctions only at its ends), c 2, d 1, e 1 = 7.
  const auto& sections = terrain.sections();
  REQUIRE(sections.size() == 7);
  CHECK(sections[0].road == 0);
  CHECK(sections[0].first_point == 0);
  CHECK(sections[0].last_point == 1);
  CHECK(sections[0].length == Approx(50.0 * std::sqrt(2.0)));  // (0, 0) to (50, 50)
  CHECK(sections[1].first_point == 1);
  CHECK(sections[1].last_point == 2);
  CHECK(sections[2].road == 1);
  CHECK(sections[2].points.size() == 2);
  CHECK(sections[3].road == 2);
  CHECK(sections[3].points.back() == Vec2{50.0, 100.0});
  CHECK(sections[4].points.front() == Vec2{50.0, 100.0});
  CHECK(sections[5].road == 3);
  CHECK(sections[6].points.size() == 3);
}

TEST_CASE("a point is inside a polygon by the crossing rule, with its boundary inside", "[terrain]") {
  CHECK(insidePolygon(kBlock, {50.0, 50.0}));
  CHECK_FALSE(insidePolygon(kBlock, {65.0, 50.0}));
  CHECK(insidePolygon(kBlock, {60.0, 50.0}));  // on the east wall
  CHECK_FALSE(strictlyInsidePolygon(kBlock, {60.0, 50.0}));
  CHECK(insidePolygon(kBlock, {40.0, 40.0}));  // a corner
  CHECK(strictlyInsidePolygon(kBlock, {50.0, 50.0}));

  // An L: the square [0, 10]^2 without its top-right [4, 10]^2.
  const std::vector<Vec2> ell{{0.0, 0.0}, {10.0, 0.0}, {10.0, 4.0}, {4.0, 4.0}, {4.0, 10.0}, {0.0, 10.0}};
  CHECK_FALSE(insidePolygon(ell, {7.0, 7.0}));  // in the notch
  CHECK(insidePolygon(ell, {2.0, 8.0}));
  CHECK(insidePolygon(ell, {7.0, 2.0}));
  // (2, 4): its ray along y = 4 runs over the edge (10, 4)-(4, 4) and the vertex (4, 4); it is
  // inside the L's lower arm all the same.
  CHECK(strictlyInsidePolygon(ell, {2.0, 4.0}));
  CHECK_FALSE(insidePolygon(std::vector<Vec2>{{0.0, 0.0}, {1.0, 1.0}}, {0.5, 0.5}));  // not a polygon
}

TEST_CASE("a building blocks a line of sight through it or from inside it but not one touching it", "[terrain]") {
  const Terrain terrain = withMask(MaskKind::kBuilding, kBlock);
  // Through the middle: enters at (40, 50), leaves at (60, 50).
  CHECK_FALSE(terrain.lineOfSight({0.0, 50.0}, {100.0, 50.0}));
  // Through two opposite corners (40, 40) and (60, 60): every crossing is at a vertex, yet the
  // piece between them, midpoint (50, 50), is inside.
  CHECK_FALSE(terrain.lineOfSight({30.0, 30.0}, {70.0, 70.0}));
  // Along the south wall y = 40: touches the building over 20 but never enters it.
  CHECK(terrain.lineOfSight({0.0, 40.0}, {100.0, 40.0}));
  // x + y = 120 touches the building only at its corner (60, 60).
  CHECK(terrain.lineOfSight({40.0, 80.0}, {80.0, 40.0}));
  // Both ends inside, or one: blocked.
  CHECK_FALSE(terrain.lineOfSight({45.0, 45.0}, {55.0, 55.0}));
  CHECK_FALSE(terrain.lineOfSight({50.0, 50.0}, {100.0, 50.0}));
  // From a point on the east wall outwards: it sees out.
  CHECK(terrain.lineOfSight({60.0, 50.0}, {100.0, 50.0}));
  // Stopping short of the building, and a segment of zero length outside it.
  CHECK(terrain.lineOfSight({0.0, 50.0}, {39.0, 50.0}));
  CHECK(terrain.lineOfSight({0.0, 0.0}, {0.0, 0.0}));
  CHECK_FALSE(terrain.lineOfSight({50.0, 50.0}, {50.0, 50.0}));
}

TEST_CASE("vegetation blocks the optical line of sight but not a sensor that sees through foliage", "[terrain]") {
  const Terrain terrain = withMask(MaskKind::kVegetation, kBlock);
  CHECK_FALSE(terrain.lineOfSight({0.0, 50.0}, {100.0, 50.0}));
  CHECK(terrain.blockedBy({0.0, 50.0}, {100.0, 50.0}, MaskKind::kVegetation));
  CHECK_FALSE(terrain.blockedBy({0.0, 50.0}, {100.0, 50.0}, MaskKind::kBuilding));
  CHECK(terrain.masksContaining({50.0, 50.0}) == std::vector<std::size_t>{0});
  CHECK(terrain.masksContaining({0.0, 0.0}).empty());
}

TEST_CASE("a line of sight past a concave mask's notch is clear", "[terrain]") {
  // The L of the point-in-polygon case: y = 7 from x = 5 to 20 runs in the notch only.
  const Terrain terrain = withMask(
      MaskKind::kBuilding, {{0.0, 0.0}, {10.0, 0.0}, {10.0, 4.0}, {4.0, 4.0}, {4.0, 10.0}, {0.0, 10.0}});
  CHECK(terrain.lineOfSight({5.0, 7.0}, {20.0, 7.0}));
  // x = 5 from below the L enters its lower arm and ends inside it.
  CHECK_FALSE(terrain.lineOfSight({5.0, -5.0}, {5.0, 3.0}));
}

TEST_CASE("a simple polygon has no crossing or folded edges and a nonzero area", "[terrain]") {
  CHECK(isSimplePolygon(kBlock));
  CHECK_FALSE(isSimplePolygon(std::vector<Vec2>{{0.0, 0.0}, {10.0, 10.0}, {10.0, 0.0}, {0.0, 10.0}}));  // bow tie
  CHECK_FALSE(isSimplePolygon(std::vector<Vec2>{{0.0, 0.0}, {5.0, 0.0}, {10.0, 0.0}}));             // no area
  // (10, 0) -> (5, 0) folds back over (0, 0) -> (10, 0).
  CHECK_FALSE(isSimplePolygon(std::vector<Vec2>{{0.0, 0.0}, {10.0, 0.0}, {5.0, 0.0}, {5.0, 5.0}}));
  // A vertex of one edge touching a non-adjacent edge.
  CHECK_FALSE(isSimplePolygon(std::vector<Vec2>{{0.0, 0.0}, {10.0, 0.0}, {10.0, 10.0}, {5.0, 0.0}, {0.0, 10.0}}));
  CHECK_FALSE(isSimplePolygon(std::vector<Vec2>{{0.0, 0.0}, {10.0, 0.0}}));
}

}  // namespace
}  // namespace wsn::common

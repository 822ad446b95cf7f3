#include "common/sensor_coverage.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

namespace wsn::common {
namespace {

constexpr double kPi = std::numbers::pi;

/// A 10 x 10 building at [40, 50] x [-5, 5] and a wood at [40, 50] x [20, 30].
Terrain blocks() {
  TerrainConfig c;
  c.masks.push_back({"house", MaskKind::kBuilding, {{40, -5}, {50, -5}, {50, 5}, {40, 5}}});
  c.masks.push_back({"wood", MaskKind::kVegetation, {{40, 20}, {50, 20}, {50, 30}, {40, 30}}});
  return Terrain(c);
}

TEST_CASE("a sector covers its range and its field of view up to the edges", "[coverage]") {
  const Vec2 at{0, 0};
  // Heading +y, 90 deg wide: the edges are the two diagonals.
  CHECK(inSector(at, kPi / 2, kPi / 2, 10.0, {0, 10}));              // on the range, on the axis
  CHECK_FALSE(inSector(at, kPi / 2, kPi / 2, 10.0, {0, 10.001}));    // just beyond the range
  CHECK(inSector(at, kPi / 2, kPi / 2, 10.0, {5, 5}));               // on an edge: 45 deg off the axis
  CHECK_FALSE(inSector(at, kPi / 2, kPi / 2, 10.0, {5.1, 4.9}));     // just outside it
  CHECK_FALSE(inSector(at, kPi / 2, kPi / 2, 10.0, {0, -5}));        // behind
  // A full circle covers every bearing, the one at exactly -pi from the heading too.
  CHECK(inSector(at, 0.0, 2 * kPi, 10.0, {-5, 0}));
}

TEST_CASE("masks hide a target from the sensors they block and from no other", "[coverage]") {
  const Terrain terrain = blocks();
  const Vec2 sensor{0, 0};
  const Vec2 behind_house{60, 0};
  const Vec2 behind_wood{60, 30};  // the line from the origin runs through the wood from (40, 20) to (50, 25)
  REQUIRE(terrain.blockedBy(sensor, behind_wood, MaskKind::kVegetation));
  CHECK(hiddenBy(&terrain, SightBlockers::buildings_and_vegetation, sensor, behind_house));
  CHECK(hiddenBy(&terrain, SightBlockers::buildings_and_vegetation, sensor, behind_wood));
  CHECK(hiddenBy(&terrain, SightBlockers::buildings, sensor, behind_house));
  CHECK_FALSE(hiddenBy(&terrain, SightBlockers::buildings, sensor, behind_wood));  // a radar sees through foliage
  CHECK_FALSE(hiddenBy(&terrain, SightBlockers::none, sensor, behind_house));      // a presence sensor hears
  CHECK_FALSE(hiddenBy(nullptr, SightBlockers::buildings_and_vegetation, sensor, behind_house));
}

TEST_CASE("PD x Pe is the sensor's PD in its sector and sight and 0 elsewhere", "[coverage]") {
  const Terrain terrain = blocks();
  const SensorCoverage camera{7, {0, 0}, 0.0, kPi / 2, 100.0, 0.8, SightBlockers::buildings_and_vegetation};
  CHECK(detectionProbabilityAt(camera, {30, 10}, &terrain) == 0.8);
  CHECK(detectionProbabilityAt(camera, {60, 0}, &terrain) == 0.0);    // behind the house
  CHECK(detectionProbabilityAt(camera, {0, 60}, &terrain) == 0.0);    // outside the 90 deg sector
  CHECK(detectionProbabilityAt(camera, {101, 0}, &terrain) == 0.0);   // beyond the range
  CHECK(detectionProbabilityAt(camera, {60, 0}, nullptr) == 0.8);     // open ground
}


SensorCoverage disc(SensorId id, Vec2 at, double range, double pd) {
  SensorCoverage c;
  c.sensor = id;
  c.position = at;
  c.fov = 2 * kPi;
  c.range = range;
  c.detection_probability = pd;
  return c;
}

TEST_CASE("a point seen by two sensors is missed only when both miss it", "[coverage]") {
  const std::vector<SensorCoverage> field = {disc(0, {0, 0}, 10, 0.8), disc(1, {10, 0}, 10, 0.5)};
  CHECK(sensedProbabilityAt(field, {5, 0}, nullptr) == Approx(1.0 - 0.2 * 0.5));
  CHECK(sensedProbabilityAt(field, {-5, 0}, nullptr) == Approx(0.8));
  CHECK(sensedProbabilityAt(field, {30, 0}, nullptr) == 0.0);
  CHECK(sensedProbabilityAt({}, {0, 0}, nullptr) == 0.0);
}

TEST_CASE("the region mean of sensing is the covered share of the region times its PD", "[coverage]") {
  // One disc of radius 10 and PD 0.6 inside a 100 x 100 region: pi 10^2 / 10^4 x 0.6 = 0.01885,
  // up to the grid's rendering of the disc (a 1 m grid: within 1 %).
  const Rect region{0, 0, 100, 100};
  const double mean = meanSensedProbability({disc(0, {50, 50}, 10, 0.6)}, region, nullptr, 100);
  CHECK(mean == Approx(kPi * 100.0 / 1e4 * 0.6).epsilon(0.01));
  // Two overlapping discs count their common part once, at 1 - (1 - pd)^2.
  const double both = meanSensedProbability({disc(0, {50, 50}, 10, 0.6), disc(1, {50, 50}, 10, 0.6)}, region, nullptr, 100);
  CHECK(both == Approx(kPi * 100.0 / 1e4 * (1.0 - 0.4 * 0.4)).epsilon(0.01));
  CHECK(meanSensedProbability({}, region, nullptr) == 0.0);
}

TEST_CASE("the detection share is sensing over its region mean and 1 without coverage", "[coverage]") {
  const DetectionShare none;
  CHECK(none.uniform());
  CHECK(none.at({3, 4}) == 1.0);
  const DetectionShare field({disc(0, {0, 0}, 10, 0.8)}, nullptr, 0.04);
  CHECK_FALSE(field.uniform());
  CHECK(field.at({1, 1}) == Approx(0.8 / 0.04));
  CHECK(field.at({50, 50}) == 0.0);
  // A field whose sensors see nothing of the region has no scale to share out by: uniform.
  const DetectionShare blind({disc(0, {0, 0}, 10, 0.8)}, nullptr, 0.0);
  CHECK(blind.uniform());
  CHECK(blind.at({1, 1}) == 1.0);
}

}  // namespace
}  // namespace wsn::common

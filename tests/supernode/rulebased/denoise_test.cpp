#include "supernode/rulebased/denoise.hpp"

#include <catch2/catch.hpp>

#include <stdexcept>
#include <utility>
#include <vector>

namespace wsn::supernode::rulebased {
namespace {

constexpr double kDs = 25.0;

Detection sensor(common::SensorId id, double x, double y) { return {id, {x, y}, 1}; }

std::vector<common::SensorId> ids(const std::vector<Detection>& detections) {
  std::vector<common::SensorId> out;
  for (const auto& d : detections) out.push_back(d.sensor);
  return out;
}

TEST_CASE("step 1, eq. 11: a detection passes when its sensor detected in the two previous ticks", "[rulebased]") {
  PersistenceFilter filter(3);
  // Sensor 1 detects at ticks 1-4 (a target); sensor 2 at ticks 1-2 only (noise of 0.2 s); sensor 3
  // from tick 2 on.
  CHECK(filter.apply(1, std::vector{sensor(1, 0, 0), sensor(2, 50, 0)}).empty());
  CHECK(filter.apply(2, std::vector{sensor(1, 0, 0), sensor(2, 50, 0), sensor(3, 90, 0)}).empty());
  CHECK(ids(filter.apply(3, std::vector{sensor(1, 0, 0), sensor(3, 90, 0)})) == std::vector<common::SensorId>{1});
  CHECK(ids(filter.apply(4, std::vector{sensor(1, 0, 0), sensor(3, 90, 0)})) == std::vector<common::SensorId>{1, 3});
}

TEST_CASE("step 1: a tick without detections breaks the persistence", "[rulebased]") {
  PersistenceFilter filter(3);
  filter.apply(1, std::vector{sensor(1, 0, 0)});
  filter.apply(2, std::vector{sensor(1, 0, 0)});
  // Tick 3 is never fed (no detection at all): at tick 4 sensor 1 has not detected at 3.
  CHECK(filter.apply(4, std::vector{sensor(1, 0, 0)}).empty());
  CHECK(filter.apply(5, std::vector{sensor(1, 0, 0)}).empty());
  CHECK(ids(filter.apply(6, std::vector{sensor(1, 0, 0)})) == std::vector<common::SensorId>{1});
  CHECK_THROWS_AS(PersistenceFilter(0), std::invalid_argument);
  // One tick of persistence keeps everything.
  PersistenceFilter pass(1);
  CHECK(pass.apply(1, std::vector{sensor(7, 0, 0)}).size() == 1);
}

TEST_CASE("step 2, eq. 13-14: one target among scattered noise keeps the target's sensors only", "[rulebased]") {
  // Four target sensors around (0, 0) and two noise sensors 500 m away from everything: m = 6.
  // Each target sensor has n_j = 4 >= m / 2 = 3 (L_j = 2 <= 3); each noise sensor n_j = 1 (L_j = 5 > 3).
  const std::vector<Detection> survivors = {sensor(1, 0, 0),   sensor(2, 25, 0),  sensor(3, 0, 25),
                                            sensor(4, 25, 25), sensor(5, 500, 0), sensor(6, 0, 500)};
  CHECK(ids(spatialFilter(survivors, 3 * kDs, 3)) == std::vector<common::SensorId>{1, 2, 3, 4});
}

TEST_CASE("step 2 with few survivors is the paper's rule exactly", "[rulebased]") {
  // m = 3: two target sensors and one noise sensor. Paper: L_j > 1.5 drops j. Target sensors have
  // L = 1 (kept), the noise sensor L = 2 (dropped). min(m / 2, 3) = 1.5 is the paper's threshold.
  const std::vector<Detection> survivors = {sensor(1, 0, 0), sensor(2, 25, 0), sensor(3, 400, 0)};
  CHECK(ids(spatialFilter(survivors, 3 * kDs, 3)) == std::vector<common::SensorId>{1, 2});
}

TEST_CASE("step 2 generalised: several targets survive where the paper's rule would drop them", "[rulebased]") {
  // Three targets of 4 sensors each, far apart, plus one noise sensor: m = 13. The paper's rule keeps
  // j only when n_j >= 6.5: it would drop every target. With min(6.5, 3) = 3 the targets stay.
  std::vector<Detection> survivors;
  common::SensorId id = 0;
  for (const double cx : {0.0, 400.0, 800.0})
    for (const auto& [dx, dy] : {std::pair{0.0, 0.0}, {25.0, 0.0}, {0.0, 25.0}, {25.0, 25.0}})
      survivors.push_back(sensor(id++, cx + dx, dy));
  survivors.push_back(sensor(99, 400, 600));
  const auto kept = spatialFilter(survivors, 3 * kDs, 3);
  CHECK(kept.size() == 12);
  CHECK(ids(kept).back() == 11);
  const auto paper = spatialFilter(survivors, 3 * kDs, 100);  // min(6.5, 100): the paper's m / 2
  CHECK(paper.empty());
}

TEST_CASE("step 3, eq. 15: the jump gate accepts up to 3 Ds, inclusive", "[rulebased]") {
  CHECK(withinJump({0, 0}, {75, 0}, 3 * kDs));
  CHECK(withinJump({0, 0}, {45, 60}, 3 * kDs));  // exactly 75 m
  CHECK_FALSE(withinJump({0, 0}, {45, 60.01}, 3 * kDs));
}

}  // namespace
}  // namespace wsn::supernode::rulebased

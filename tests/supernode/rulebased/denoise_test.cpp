#include "supernode/rulebased/denoise.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "common/rng.hpp"

namespace wsn::supernode::rulebased {
namespace {

// An et al. 2013 §3.3 on the paper's grid: Ds = 25 m, the spatial test's radius 3 Ds = 75 m.
constexpr double kDs = 25.0;
constexpr double kRadius = 3.0 * kDs;

using Ids = std::vector<common::SensorId>;

/// The detection of the grid sensor in column i, row j (id j * 50 + i).
Detection at(int i, int j, std::int32_t level = 1) {
  return {static_cast<common::SensorId>(j * 50 + i), {12.5 + kDs * i, 12.5 + kDs * j}, level};
}

Ids ids(const std::vector<Detection>& detections) {
  Ids out;
  for (const auto& d : detections) out.push_back(d.sensor);
  return out;
}

/// The paper's step 2 as its pseudo-code writes it (2013 Algorithm, lines 6-17): L(j) counts the
/// survivors farther than 3 Ds from j (eq. 13-14); j is kept when L(j) <= m / 2.
std::vector<Detection> paperSpatialTest(const std::vector<Detection>& survivors, double radius) {
  const double m = static_cast<double>(survivors.size());
  std::vector<Detection> kept;
  for (const auto& j : survivors) {
    int far = 0;
    for (const auto& l : survivors)
      if (common::distance(j.position, l.position) > radius) ++far;
    if (far <= m / 2.0) kept.push_back(j);
  }
  return kept;
}

/// A 2 x 2 block of sensors with its lower-left sensor in column i, row j: a target's cluster.
std::vector<Detection> block(int i, int j) { return {at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)}; }

std::vector<Detection> concat(std::initializer_list<std::vector<Detection>> parts) {
  std::vector<Detection> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// ---- Step 1: persistence (eq. 9-11) --------------------------------------------------------------

TEST_CASE("eq. 11: a sensor passes from its third consecutive detecting tick on", "[rulebased]") {
  // f_k-2 f_k-1 f_k = 1 first holds at the third tick of a detection that starts at tick 1.
  PersistenceFilter filter(3);
  const std::vector<Detection> target = {at(10, 10), at(11, 10)};
  CHECK(filter.apply(1, target).empty());
  CHECK(filter.apply(2, target).empty());
  for (std::int32_t tick = 3; tick <= 6; ++tick) {
    INFO("tick " << tick);
    CHECK(ids(filter.apply(tick, target)) == Ids{510, 511});
  }
}

TEST_CASE("eq. 11: noise lasting two ticks never passes, wherever it starts", "[rulebased]") {
  // Sensor 777 is noisy at ticks s and s + 1 only; a target sensor (510) detects every tick so
  // that every tick is fed. At s + 1 the noise has two ticks, one short of three; at s + 2 it is gone.
  for (std::int32_t start = 1; start <= 5; ++start) {
    INFO("noise at ticks " << start << " and " << start + 1);
    PersistenceFilter filter(3);
    for (std::int32_t tick = 1; tick <= 10; ++tick) {
      std::vector<Detection> detections = {at(10, 10)};
      if (tick == start || tick == start + 1) detections.push_back(at(27, 15));  // id 777
      const auto kept = ids(filter.apply(tick, detections));
      CHECK(kept == (tick >= 3 ? Ids{510} : Ids{}));
    }
  }
}

TEST_CASE("eq. 11: noise lasting three ticks passes at its third tick, and only then", "[rulebased]") {
  // Noise at s, s + 1, s + 2: f_s f_s+1 f_s+2 = 1 at k = s + 2; at s + 3 the sensor is silent.
  for (std::int32_t start = 1; start <= 4; ++start) {
    INFO("noise at ticks " << start << " to " << start + 2);
    PersistenceFilter filter(3);
    for (std::int32_t tick = 1; tick <= 9; ++tick) {
      std::vector<Detection> detections = {at(10, 10)};
      if (tick >= start && tick <= start + 2) detections.push_back(at(27, 15));
      const auto kept = ids(filter.apply(tick, detections));
      Ids expected;
      if (tick >= 3) expected.push_back(510);
      if (tick == start + 2) expected.push_back(777);
      INFO("tick " << tick);
      CHECK(kept == expected);
    }
  }
}

TEST_CASE("eq. 11: a tick without the sensor's detection starts its count again", "[rulebased]") {
  const std::vector<Detection> one = {at(10, 10)};
  const std::vector<Detection> other = {at(40, 40)};

  SECTION("the sensor is silent for one tick while others detect") {
    // 510 detects at 1-3 (passes at 3), is silent at 4, detects again from 5: it passes again at 7.
    PersistenceFilter filter(3);
    filter.apply(1, one);
    filter.apply(2, one);
    CHECK(ids(filter.apply(3, one)) == Ids{510});
    CHECK(filter.apply(4, other).empty());
    CHECK(filter.apply(5, one).empty());
    CHECK(filter.apply(6, one).empty());
    CHECK(ids(filter.apply(7, one)) == Ids{510});
  }
  SECTION("a tick is never fed") {
    // No detection at all at tick 4, so the supernode never feeds it: at 5 the history holds 2 and 3,
    // not 3 and 4, and nothing passes until 7.
    PersistenceFilter filter(3);
    filter.apply(1, one);
    filter.apply(2, one);
    CHECK(ids(filter.apply(3, one)) == Ids{510});
    CHECK(filter.apply(5, one).empty());
    CHECK(filter.apply(6, one).empty());
    CHECK(ids(filter.apply(7, one)) == Ids{510});
  }
  SECTION("a tick is fed without detections") {
    PersistenceFilter filter(3);
    filter.apply(1, one);
    filter.apply(2, one);
    CHECK(filter.apply(3, std::vector<Detection>{}).empty());
    CHECK(filter.apply(4, one).empty());
    CHECK(filter.apply(5, one).empty());
    CHECK(ids(filter.apply(6, one)) == Ids{510});
  }
}

TEST_CASE("eq. 11: the persistence length is a parameter, and one tick keeps everything", "[rulebased]") {
  // Four ticks: a detection starting at tick 1 passes from tick 4.
  PersistenceFilter four(4);
  const std::vector<Detection> one = {at(10, 10)};
  for (std::int32_t tick = 1; tick <= 3; ++tick) CHECK(four.apply(tick, one).empty());
  CHECK(ids(four.apply(4, one)) == Ids{510});

  // One tick: f_k = 1 alone, every detection passes at once.
  PersistenceFilter pass(1);
  CHECK(ids(pass.apply(1, std::vector{at(7, 0), at(3, 0)})) == Ids{7, 3});
  CHECK_THROWS_AS(PersistenceFilter(0), std::invalid_argument);
}

TEST_CASE("eq. 11: what passes keeps its input order and level", "[rulebased]") {
  PersistenceFilter filter(3);
  const std::vector<Detection> unordered = {at(30, 30, 4), at(10, 10, 2), at(20, 20, 7)};
  filter.apply(1, unordered);
  filter.apply(2, unordered);
  const auto kept = filter.apply(3, unordered);
  CHECK(ids(kept) == Ids{1530, 510, 1020});
  REQUIRE(kept.size() == 3);
  CHECK(kept[0] == unordered[0]);
  CHECK(kept[2].level == 7);
}

// ---- Step 2: spatial test (eq. 12-14) ------------------------------------------------------------

TEST_CASE("eq. 14: one target among scattered noise keeps the target's sensors only", "[rulebased]") {
  // A target block of 4 sensors around (275, 275) and one noise sensor far away: m = 5.
  // Target sensors: L_j = 1 (the noise) <= m / 2 = 2.5, kept. Noise: L_j = 4 > 2.5, dropped.
  // min(m / 2, min_cluster = 3) = 2.5: with m < 2 min_cluster the rule is the paper's.
  const auto survivors = concat({block(10, 10), {at(40, 30)}});
  const auto kept = spatialFilter(survivors, kRadius, 3);
  CHECK(ids(kept) == Ids{510, 511, 560, 561});
  CHECK(ids(kept) == ids(paperSpatialTest(survivors, kRadius)));
}

TEST_CASE("eq. 14: with fewer than 2 min_cluster survivors the rule is the paper's exactly", "[rulebased]") {
  // One target (the sensors within 40 m of a random point, at most 12: an SR = 40 m footprint) and
  // 0-7 noisy sensors scattered at random, so m <= 19 < 2 min_cluster = 20: min(m / 2, min_cluster)
  // is m / 2, and n_j >= m / 2 is L_j = m - n_j <= m / 2, the paper's test. 200 random layouts,
  // each compared with the paper's pseudo-code.
  const std::int32_t min_cluster = 10;
  int trials_with_noise_dropped = 0;
  for (std::uint64_t trial = 0; trial < 200; ++trial) {
    common::Stream random(20130303, common::Purpose::kSensorNoise, trial, 0);
    const common::Vec2 target{random.uniform(100.0, 1150.0), random.uniform(100.0, 1150.0)};
    std::vector<Detection> survivors;
    for (int j = 0; j < 50; ++j)
      for (int i = 0; i < 50; ++i)
        if (common::distance(at(i, j).position, target) <= 40.0) survivors.push_back(at(i, j));
    const auto noise = static_cast<int>(random.below(8));
    for (int n = 0; n < noise; ++n)
      survivors.push_back(at(static_cast<int>(random.below(50)), static_cast<int>(random.below(50))));
    REQUIRE(survivors.size() < 2 * static_cast<std::size_t>(min_cluster));
    INFO("trial " << trial << ", m = " << survivors.size());
    const auto kept = spatialFilter(survivors, kRadius, min_cluster);
    CHECK(ids(kept) == ids(paperSpatialTest(survivors, kRadius)));
    if (kept.size() < survivors.size()) ++trials_with_noise_dropped;
  }
  // The comparison is not vacuous: in most layouts the test removes something.
  CHECK(trials_with_noise_dropped > 100);
}

TEST_CASE("eq. 14 generalised: two target groups that the paper's rule drops are kept", "[rulebased]") {
  // Two targets of 4 sensors each, 500 m apart, and one noise sensor: m = 9, m / 2 = 4.5.
  // Paper: each target sensor has n_j = 4, L_j = 5 > 4.5, dropped: it keeps nothing.
  // Generalised: n_j = 4 >= min(4.5, 3) = 3, kept; the noise has n_j = 1 < 3, dropped.
  const auto survivors = concat({block(5, 5), block(25, 5), {at(40, 40)}});
  CHECK(paperSpatialTest(survivors, kRadius).empty());
  CHECK(ids(spatialFilter(survivors, kRadius, 3)) == ids(concat({block(5, 5), block(25, 5)})));

  // Without the noise, m = 8: two equal groups sit exactly at n_j = m / 2 = 4, which both rules keep.
  const auto clean = concat({block(5, 5), block(25, 5)});
  CHECK(paperSpatialTest(clean, kRadius).size() == 8);
  CHECK(spatialFilter(clean, kRadius, 3).size() == 8);

  // Unequal groups of 6 and 3 and a noise sensor: m = 10. Paper: the 6 have L = 4 <= 5, kept; the 3
  // have L = 7 > 5, dropped. Generalised: the 3 have n_j = 3 >= min(5, 3), kept.
  const std::vector<Detection> six = {at(5, 5), at(6, 5), at(7, 5), at(5, 6), at(6, 6), at(7, 6)};
  const std::vector<Detection> three = {at(30, 5), at(31, 5), at(30, 6)};
  const auto unequal = concat({six, three, {at(40, 40)}});
  CHECK(ids(paperSpatialTest(unequal, kRadius)) == ids(six));
  CHECK(ids(spatialFilter(unequal, kRadius, 3)) == ids(concat({six, three})));
}

TEST_CASE("eq. 14 generalised: three target groups that the paper's rule drops are kept", "[rulebased]") {
  // Three targets of 4 sensors and two isolated noise sensors: m = 14, m / 2 = 7. Each target sensor
  // has n_j = 4 (L_j = 10 > 7): the paper drops every sensor. Generalised: 4 >= min(7, 3), kept; the
  // noise (n_j = 1) dropped.
  const auto targets = concat({block(5, 5), block(25, 5), block(15, 30)});
  const auto survivors = concat({targets, {at(45, 45)}, {at(2, 45)}});
  CHECK(paperSpatialTest(survivors, kRadius).empty());
  CHECK(ids(spatialFilter(survivors, kRadius, 3)) == ids(targets));
}

TEST_CASE("eq. 14: isolated noise is dropped whatever the number of targets", "[rulebased]") {
  // A lone sensor (n_j = 1) and a pair of adjacent noisy sensors (n_j = 2) next to two targets:
  // m = 4 + 4 + 1 + 2 = 11, threshold min(5.5, 3) = 3: both noises fall below it.
  const auto targets = concat({block(5, 5), block(25, 25)});
  const auto survivors = concat({targets, {at(45, 2)}, {at(2, 45), at(3, 45)}});
  CHECK(ids(spatialFilter(survivors, kRadius, 3)) == ids(targets));

  // A group of min_cluster = 3 noisy sensors, though, is as dense as a target: the price of the
  // generalisation once m >= 2 min_cluster. (The paper's rule, m / 2 = 5.5, drops it with n_j = 3,
  // and both targets with n_j = 4 too.)
  const auto dense = concat({targets, {at(45, 2), at(46, 2), at(45, 3)}});
  CHECK(spatialFilter(dense, kRadius, 3).size() == 11);
  CHECK(paperSpatialTest(dense, kRadius).size() == 0);
}

TEST_CASE("eq. 13-14: a survivor exactly 3 Ds away counts as near", "[rulebased]") {
  // Sensors at x = 12.5, 87.5, 162.5 (columns 0, 3, 6): neighbours exactly 75 m apart. d > 3 Ds is
  // far (eq. 14), so d = 75 m is near: n = 2, 3, 2 >= m / 2 = 1.5, all kept. Were 75 m far, the ends
  // would have n = 1 < 1.5 and be dropped.
  const std::vector<Detection> survivors = {at(0, 0), at(3, 0), at(6, 0)};
  CHECK(ids(spatialFilter(survivors, kRadius, 3)) == Ids{0, 3, 6});
  CHECK(ids(paperSpatialTest(survivors, kRadius)) == Ids{0, 3, 6});
  // One more column out (x = 187.5, 100 m from 87.5): m = 3 with {0, 3} and {7}: (7) has n = 1 < 1.5.
  CHECK(ids(spatialFilter(std::vector{at(0, 0), at(3, 0), at(7, 0)}, kRadius, 3)) == Ids{0, 3});
  CHECK(spatialFilter(std::vector<Detection>{}, kRadius, 3).empty());
}

// ---- Step 3: centroid jump (eq. 15) --------------------------------------------------------------

TEST_CASE("eq. 15: a centroid may move up to 3 Ds, boundary included", "[rulebased]") {
  // |d_c,k-1 - d_c,k| > 3 Ds discards; exactly 75 m (along an axis, or 45-60-75 diagonally) is kept.
  CHECK(withinJump({0, 0}, {0, 0}, kRadius));
  CHECK(withinJump({100, 100}, {175, 100}, kRadius));
  CHECK(withinJump({100, 100}, {145, 160}, kRadius));
  CHECK(withinJump({145, 160}, {100, 100}, kRadius));
  CHECK_FALSE(withinJump({100, 100}, {175.01, 100}, kRadius));
  CHECK_FALSE(withinJump({100, 100}, {145, 160.01}, kRadius));
  CHECK_FALSE(withinJump({0, 0}, {600, 600}, kRadius));
}

}  // namespace
}  // namespace wsn::supernode::rulebased

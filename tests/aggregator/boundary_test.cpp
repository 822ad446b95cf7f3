#include "aggregator/boundary.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "aggregator/clear_mot.hpp"
#include "tests/aggregator/test_support.hpp"

using wsn::aggregator::BoundaryAccumulator;
using wsn::aggregator::BoundaryClassifier;
using wsn::aggregator::BoundarySummary;
using wsn::aggregator::ClearMotAccumulator;
using wsn::common::TargetState;
using wsn::common::TrackEstimate;
using wsn::common::Vec2;

using wsn::aggregator::test::target;
using wsn::aggregator::test::track;

namespace {

/// The supernodes of oh_quadrants.yaml.
const std::vector<Vec2> kQuadrants = {{25, 25}, {75, 25}, {25, 75}, {75, 75}};
/// Two supernodes with the bisector x = 50.
const std::vector<Vec2> kPair = {{25, 25}, {75, 25}};

/// Feeds one tick through CLEAR-MOT and the boundary split, as RunScorer does.
void addTick(ClearMotAccumulator& mot, BoundaryAccumulator& split, std::int32_t t, const std::vector<TargetState>& truth,
             const std::vector<TrackEstimate>& tracks) {
  split.add(truth, mot.add(t, truth, tracks));
}

}  // namespace

TEST_CASE("the distance to the bisector of the two nearest supernodes follows its formula", "[boundary]") {
  const BoundaryClassifier quadrants(kQuadrants, 5.0);
  // (47, 25): nearest a = (25, 25) (d² = 484), second b = (75, 25) (d² = 784):
  //   (784 − 484) / (2 · 50) = 3.
  CHECK(quadrants.bisectorDistance({47, 25}) == Approx(3.0).margin(1e-12));
  // (48, 30): a = (25, 25) (529 + 25 = 554), b = (75, 25) (729 + 25 = 754), (25, 75) is 2554:
  //   (754 − 554) / 100 = 2.
  CHECK(quadrants.bisectorDistance({48, 30}) == Approx(2.0).margin(1e-12));
  // On a supernode: b ties between (75, 25) and (25, 75) (both 2500): (2500 − 0) / 100 = 25.
  CHECK(quadrants.bisectorDistance({25, 25}) == Approx(25.0).margin(1e-12));
  // The centre is equally far from all four: on the boundary, s = 0.
  CHECK(quadrants.bisectorDistance({50, 50}) == Approx(0.0).margin(1e-12));
  // (40, 25): (35² − 15²) / 100 = 10, interior at band 5.
  CHECK(quadrants.bisectorDistance({40, 25}) == Approx(10.0).margin(1e-12));
  CHECK(quadrants.atBoundary({47, 25}));
  CHECK(quadrants.atBoundary({50, 50}));
  CHECK_FALSE(quadrants.atBoundary({40, 25}));
  CHECK_FALSE(quadrants.atBoundary({25, 25}));
}

TEST_CASE("the band is inclusive", "[boundary]") {
  const BoundaryClassifier pair(kPair, 5.0);
  // (45, 25): (30² − 20²) / 100 = 5 exactly: at the boundary. (44.9, 25): 5.1, interior.
  CHECK(pair.bisectorDistance({45, 25}) == 5.0);
  CHECK(pair.atBoundary({45, 25}));
  CHECK(pair.bisectorDistance({44.9, 25}) == Approx(5.1).margin(1e-9));
  CHECK_FALSE(pair.atBoundary({44.9, 25}));
  // The other side of the bisector mirrors it.
  CHECK(pair.atBoundary({55, 25}));
  CHECK_FALSE(pair.atBoundary({55.1, 25}));
}

TEST_CASE("with one supernode no point is at a boundary", "[boundary]") {
  const BoundaryClassifier single({{50, 50}}, 1e6);
  CHECK(std::isinf(single.bisectorDistance({50, 50})));
  CHECK_FALSE(single.atBoundary({50, 50}));
  CHECK_FALSE(single.atBoundary({0, 0}));
}

TEST_CASE("the boundary split rejects bad settings and foreign events", "[boundary]") {
  CHECK_THROWS_AS(BoundaryClassifier(kPair, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(BoundaryClassifier(kPair, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  CHECK_THROWS_AS(BoundaryClassifier({{1, 2}, {3, 4}, {1, 2}}, 5.0), std::invalid_argument);
  CHECK_THROWS_AS(BoundaryAccumulator(kPair, 5.0, 0.0), std::invalid_argument);
  CHECK_NOTHROW(BoundaryClassifier(kPair, 0.0));

  // An event about a target that is not in the truth given.
  BoundaryAccumulator split(kPair, 5.0, 2.0);
  wsn::aggregator::ClearMotTick events;
  events.id_switches = {7};
  CHECK_THROWS_AS(split.add({target(1, 0, 0)}, events), std::invalid_argument);
}

TEST_CASE("a second track on a tracked target is a duplicate where that target is", "[boundary]") {
  // Bisector x = 50, band 5, T = 3.
  //   target 1 at (47, 25): s = 3, boundary; tracks 10 on it and 11 at (48, 25) (d = 1).
  //   target 2 at (25, 25): s = 25, interior; tracks 20 on it and 21 at (25, 27) (d = 2).
  //   track 99 at (60, 60): unmatched but 35+ from every target: a false track, no duplicate.
  // CLEAR-MOT matches 1-10 and 2-20 (total distance 0); 11, 21 and 99 are left over.
  ClearMotAccumulator mot(3.0);
  BoundaryAccumulator split(kPair, 5.0, 3.0);
  addTick(mot, split, 1, {target(1, 47, 25), target(2, 25, 25)},
          {track(10, 47, 25), track(11, 48, 25), track(20, 25, 25), track(21, 25, 27), track(99, 60, 60)});
  const BoundarySummary s = split.summary();
  CHECK(s.band == 5.0);
  CHECK(s.supernodes == 2);
  CHECK(s.mot_threshold == 3.0);
  CHECK(s.boundary.target_ticks == 1);
  CHECK(s.interior.target_ticks == 1);
  CHECK(s.boundary.duplicate_track_ticks == 1);
  CHECK(s.interior.duplicate_track_ticks == 1);
  CHECK(mot.summary().false_positives == 3);
}

TEST_CASE("a duplicate near two tracked targets counts once, at the nearer", "[boundary]") {
  // Bisector x = 50, band 5, T = 5.
  //   target 3 at (52, 25): nearest (75, 25) (d² = 529), then (25, 25) (729): s = 2, boundary.
  //   target 4 at (56, 25): (361 vs 961) s = 6, interior.
  // Tracks 30 and 40 on them; track 41 at (54.5, 25) is 2.5 from target 3 and 1.5 from target 4,
  // both < T. CLEAR-MOT keeps 3-30, 4-40 (total 0 beats 2.5 + 0), so 41 is a duplicate, placed at
  // target 4: interior.
  ClearMotAccumulator mot(5.0);
  BoundaryAccumulator split(kPair, 5.0, 5.0);
  addTick(mot, split, 1, {target(3, 52, 25), target(4, 56, 25)}, {track(30, 52, 25), track(40, 56, 25), track(41, 54.5, 25)});
  const BoundarySummary s = split.summary();
  CHECK(s.boundary.duplicate_track_ticks == 0);
  CHECK(s.interior.duplicate_track_ticks == 1);
  CHECK(s.boundary.target_ticks == 1);
  CHECK(s.interior.target_ticks == 1);
}

TEST_CASE("a track at exactly T from its target is no duplicate", "[boundary]") {
  // CLEAR-MOT's correspondence needs d < T; the duplicate test uses the same strict bound.
  ClearMotAccumulator mot(3.0);
  BoundaryAccumulator split(kPair, 5.0, 3.0);
  addTick(mot, split, 1, {target(1, 25, 25)}, {track(10, 25, 25), track(11, 28, 25)});
  CHECK(split.summary().interior.duplicate_track_ticks == 0);
}

namespace {

/// Target 1 crosses the bisector x = 50 along y = 25 at x = 44, 46, 48, 51 (ticks 1-4); track 10
/// follows it at ticks 1-3 and track 11 takes over at tick 4: one identity switch at tick 4.
/// Target 2 sits at (25, 40); track 20 follows it except at tick 3: one fragmentation at tick 4.
void crossingRun(ClearMotAccumulator& mot, BoundaryAccumulator& split) {
  const double xs[] = {44, 46, 48, 51};
  for (int t = 1; t <= 4; ++t) {
    const double x = xs[t - 1];
    std::vector<TrackEstimate> tracks = {track(t < 4 ? 10 : 11, x, 25)};
    if (t != 3) tracks.push_back(track(20, 25, 40));
    addTick(mot, split, t, {target(1, x, 25), target(2, 25, 40)}, tracks);
  }
}

}  // namespace

TEST_CASE("identity switches and fragmentations are placed where the target is when counted", "[boundary]") {
  // Band 2. Target 1 at x = 44: s = (31² − 19²) / 100 = 6; 46: 4; 48: 2 (at the band); 51: (26² −
  // 24²) / 100 = 1. So its ticks 1-2 are interior, 3-4 boundary, and the switch at tick 4 is a
  // boundary event. Target 2 at (25, 40): s = (2725 − 225) / 100 = 25, interior: its
  // fragmentation (counted at tick 4, when the match resumes) is an interior event.
  ClearMotAccumulator mot(2.0);
  BoundaryAccumulator split(kPair, 2.0, 2.0);
  crossingRun(mot, split);
  const BoundarySummary s = split.summary();
  CHECK(s.boundary.target_ticks == 2);
  CHECK(s.interior.target_ticks == 6);
  CHECK(s.boundary.id_switches == 1);
  CHECK(s.boundary.fragmentations == 0);
  CHECK(s.interior.id_switches == 0);
  CHECK(s.interior.fragmentations == 1);
  CHECK(s.boundary.duplicate_track_ticks + s.interior.duplicate_track_ticks == 0);
  // The split covers CLEAR-MOT's totals exactly.
  CHECK(mot.summary().id_switches == 1);
  CHECK(mot.summary().fragmentations == 1);
}

TEST_CASE("with one supernode every event is interior", "[boundary]") {
  ClearMotAccumulator mot(2.0);
  BoundaryAccumulator split({{50, 50}}, 5.0, 2.0);
  crossingRun(mot, split);
  const BoundarySummary s = split.summary();
  CHECK(s.supernodes == 1);
  CHECK(s.boundary.target_ticks == 0);
  CHECK(s.boundary.id_switches == 0);
  CHECK(s.boundary.fragmentations == 0);
  CHECK(s.boundary.duplicate_track_ticks == 0);
  CHECK(s.interior.target_ticks == 8);
  CHECK(s.interior.id_switches == 1);
  CHECK(s.interior.fragmentations == 1);
}

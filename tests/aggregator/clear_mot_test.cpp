#include "aggregator/clear_mot.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "tests/aggregator/test_support.hpp"

using wsn::aggregator::ClearMotAccumulator;
using wsn::aggregator::ClearMotSummary;
using wsn::aggregator::ClearMotTick;
using wsn::common::TargetState;
using wsn::common::TrackEstimate;

using wsn::aggregator::test::target;
using wsn::aggregator::test::track;

TEST_CASE("a perfect tracker scores MOTA 1 and MOTP 0 without switches", "[clear_mot]") {
  ClearMotAccumulator acc(2.0);
  for (int t = 1; t <= 5; ++t) {
    // Two targets crossing at t = 3; the tracks follow them exactly with fixed ids.
    const double a = t, b = 6 - t;
    acc.add(t, {target(1, a, 0), target(2, b, 0)}, {track(10, a, 0), track(20, b, 0)});
  }
  const ClearMotSummary s = acc.summary();
  CHECK(s.ground_truth == 10);
  CHECK(s.matches == 10);
  CHECK(s.misses == 0);
  CHECK(s.false_positives == 0);
  CHECK(s.id_switches == 0);
  CHECK(s.fragmentations == 0);
  CHECK(s.mota_defined);
  CHECK(s.mota == Approx(1.0).margin(1e-12));
  CHECK(s.motp_defined);
  CHECK(s.motp == Approx(0.0).margin(1e-12));
}

TEST_CASE("swapped track ids count one identity switch per target", "[clear_mot]") {
  // Targets 1 at (0, 0) and 2 at (10, 0), T = 2. Ticks 1-2: track 10 at (0.3, 0.4) (d = 0.5),
  // track 20 at (10, 0) (d = 0). Ticks 3-4: the tracks swap places. At tick 3 the kept
  // correspondences 1-10, 2-20 are 10 m apart, so both are dropped and re-assigned 1-20 (0.5),
  // 2-10 (0): two mismatches. Tick 4 keeps them.
  // MOTA = 1 − (0 + 0 + 2) / 8 = 0.75; MOTP = 4 · 0.5 / 8 = 0.25.
  ClearMotAccumulator acc(2.0);
  acc.add(1, {target(1, 0, 0), target(2, 10, 0)}, {track(10, 0.3, 0.4), track(20, 10, 0)});
  acc.add(2, {target(1, 0, 0), target(2, 10, 0)}, {track(10, 0.3, 0.4), track(20, 10, 0)});
  acc.add(3, {target(1, 0, 0), target(2, 10, 0)}, {track(10, 10, 0), track(20, 0.3, 0.4)});
  acc.add(4, {target(1, 0, 0), target(2, 10, 0)}, {track(10, 10, 0), track(20, 0.3, 0.4)});
  const ClearMotSummary s = acc.summary();
  CHECK(s.id_switches == 2);
  CHECK(s.matches == 8);
  CHECK(s.misses == 0);
  CHECK(s.false_positives == 0);
  CHECK(s.fragmentations == 0);
  CHECK(s.mota == Approx(0.75).margin(1e-12));
  CHECK(s.motp == Approx(0.25).margin(1e-12));
}

TEST_CASE("a still-valid correspondence is kept even when another track is closer", "[clear_mot]") {
  // Target 1 at (0, 0), T = 2. Tick 1: only track 10 at (1.5, 0): matched, d = 1.5.
  // Tick 2: track 10 still at (1.5, 0) and a new track 20 at (0.1, 0). The paper keeps 1-10
  // (1.5 < T) instead of re-assigning to the closer 20, so no switch; 20 is a false positive.
  // MOTA = 1 − (0 + 1 + 0) / 2 = 0.5; MOTP = (1.5 + 1.5) / 2 = 1.5.
  ClearMotAccumulator acc(2.0);
  acc.add(1, {target(1, 0, 0)}, {track(10, 1.5, 0)});
  acc.add(2, {target(1, 0, 0)}, {track(10, 1.5, 0), track(20, 0.1, 0)});
  const ClearMotSummary s = acc.summary();
  CHECK(s.id_switches == 0);
  CHECK(s.false_positives == 1);
  CHECK(s.mota == Approx(0.5).margin(1e-12));
  CHECK(s.motp == Approx(1.5).margin(1e-12));
}

TEST_CASE("a miss in the middle of a track is one miss and one fragmentation", "[clear_mot]") {
  // Target 1 at (0, 0) for 4 ticks, T = 1; track 10 on it at ticks 1, 2, 4 only.
  // Misses 1 (tick 3), fragmentation 1 (matched, unmatched, matched), no switch.
  // MOTA = 1 − 1/4 = 0.75; MOTP = 0.
  ClearMotAccumulator acc(1.0);
  acc.add(1, {target(1, 0, 0)}, {track(10, 0, 0)});
  acc.add(2, {target(1, 0, 0)}, {track(10, 0, 0)});
  acc.add(3, {target(1, 0, 0)}, {});
  acc.add(4, {target(1, 0, 0)}, {track(10, 0, 0)});
  const ClearMotSummary s = acc.summary();
  CHECK(s.misses == 1);
  CHECK(s.fragmentations == 1);
  CHECK(s.id_switches == 0);
  CHECK(s.mota == Approx(0.75).margin(1e-12));
  CHECK(s.motp == Approx(0.0).margin(1e-12));
}

TEST_CASE("a target re-found by a new track after a gap is a fragmentation and a switch", "[clear_mot]") {
  // As above, but at tick 4 a new track 11 finds the target: the last match was 10, so one
  // mismatch; MOTA = 1 − (1 miss + 1 switch) / 4 = 0.5. A gap that is never resumed (ticks 5
  // and 6 unmatched) adds misses but no fragmentation.
  ClearMotAccumulator acc(1.0);
  acc.add(1, {target(1, 0, 0)}, {track(10, 0, 0)});
  acc.add(2, {target(1, 0, 0)}, {track(10, 0, 0)});
  acc.add(3, {target(1, 0, 0)}, {});
  acc.add(4, {target(1, 0, 0)}, {track(11, 0, 0)});
  ClearMotSummary s = acc.summary();
  CHECK(s.fragmentations == 1);
  CHECK(s.id_switches == 1);
  CHECK(s.mota == Approx(0.5).margin(1e-12));
  acc.add(5, {target(1, 0, 0)}, {});
  acc.add(6, {target(1, 0, 0)}, {});
  s = acc.summary();
  CHECK(s.fragmentations == 1);
  CHECK(s.misses == 3);
  // MOTA = 1 − (3 + 0 + 1) / 6 = 1/3.
  CHECK(s.mota == Approx(1.0 / 3.0).margin(1e-12));
}

TEST_CASE("a target missed at its start is a miss but no fragmentation", "[clear_mot]") {
  ClearMotAccumulator acc(1.0);
  acc.add(1, {target(1, 0, 0)}, {});
  acc.add(2, {target(1, 0, 0)}, {track(10, 0, 0)});
  const ClearMotSummary s = acc.summary();
  CHECK(s.misses == 1);
  CHECK(s.fragmentations == 0);
  CHECK(s.id_switches == 0);
}

TEST_CASE("a false track far from every target is a false positive each tick", "[clear_mot]") {
  // One target tracked exactly plus track 99 at (50, 50) for 2 ticks, T = 5:
  // g = 2, fp = 2, MOTA = 1 − 2/2 = 0; MOTP = 0.
  ClearMotAccumulator acc(5.0);
  acc.add(1, {target(1, 0, 0)}, {track(1, 0, 0), track(99, 50, 50)});
  acc.add(2, {target(1, 0, 0)}, {track(1, 0, 0), track(99, 50, 50)});
  const ClearMotSummary s = acc.summary();
  CHECK(s.false_positives == 2);
  CHECK(s.misses == 0);
  CHECK(s.mota == Approx(0.0).margin(1e-12));
  CHECK(s.motp == Approx(0.0).margin(1e-12));
}

TEST_CASE("a pair at exactly the match threshold does not correspond", "[clear_mot]") {
  // d = ‖(3, 4)‖ = 5 = T: a miss and a false positive; MOTA = 1 − 2/1 = −1; MOTP undefined.
  ClearMotAccumulator acc(5.0);
  acc.add(1, {target(1, 0, 0)}, {track(1, 3, 4)});
  const ClearMotSummary s = acc.summary();
  CHECK(s.matches == 0);
  CHECK(s.misses == 1);
  CHECK(s.false_positives == 1);
  CHECK(s.mota == Approx(-1.0).margin(1e-12));
  CHECK_FALSE(s.motp_defined);
  CHECK(s.motp == 0.0);
}

TEST_CASE("the assignment maximises matches before minimising distance", "[clear_mot]") {
  // Targets 1 at (0, 0), 2 at (2, 0); tracks 10 at (1, 0), 20 at (-1.5, 0); T = 2.
  // Greedy nearest for target 1 would take 10 (d = 1) and leave 2 unmatched (d(2, 20) = 3.5).
  // The optimum matches both: 1-20 (1.5) and 2-10 (1). MOTP = 2.5 / 2 = 1.25.
  ClearMotAccumulator acc(2.0);
  acc.add(1, {target(1, 0, 0), target(2, 2, 0)}, {track(10, 1, 0), track(20, -1.5, 0)});
  const ClearMotSummary s = acc.summary();
  CHECK(s.matches == 2);
  CHECK(s.motp == Approx(1.25).margin(1e-12));
}

TEST_CASE("empty truth leaves MOTA undefined and counts every track as false", "[clear_mot]") {
  ClearMotAccumulator acc(1.0);
  acc.add(1, {}, {track(1, 0, 0)});
  acc.add(2, {}, {});
  const ClearMotSummary s = acc.summary();
  CHECK(s.ticks == 2);
  CHECK(s.false_positives == 1);
  CHECK_FALSE(s.mota_defined);
  CHECK(s.mota == 0.0);
  CHECK_FALSE(s.motp_defined);
}

TEST_CASE("empty tracks make every target a miss and MOTA zero", "[clear_mot]") {
  ClearMotAccumulator acc(1.0);
  acc.add(1, {target(1, 0, 0), target(2, 5, 5)}, {});
  const ClearMotSummary s = acc.summary();
  CHECK(s.misses == 2);
  CHECK(s.mota == Approx(0.0).margin(1e-12));
}

TEST_CASE("non-finite tracks are ignored and ticks must increase", "[clear_mot]") {
  ClearMotAccumulator acc(1.0);
  acc.add(1, {target(1, 0, 0)}, {track(1, 0, 0), track(2, std::numeric_limits<double>::quiet_NaN(), 0)});
  const ClearMotSummary s = acc.summary();
  CHECK(s.tracks_ignored_nonfinite == 1);
  CHECK(s.false_positives == 0);
  CHECK_THROWS_AS(acc.add(1, {}, {}), std::invalid_argument);
  CHECK_THROWS_AS(ClearMotAccumulator(0.0), std::invalid_argument);
}

TEST_CASE("add reports the tick's matches, misses, false positives and events", "[clear_mot]") {
  // T = 2. Tick 1: targets 1 at (0, 0), 2 at (10, 0), 3 at (20, 0); track 10 on 1 (d = 0.5),
  // track 20 on 2, track 99 far off. Target 3 missed.
  // Tick 2: target 1 taken by a new track 11 (switch), target 2 still by 20, target 3 missed.
  // Tick 3: target 1 missed, target 3 missed. Tick 4: target 1 back on 11 (a fragmentation,
  // no switch: 11 was its last track), target 3 still missed.
  ClearMotAccumulator acc(2.0);
  const ClearMotTick t1 = acc.add(1, {target(1, 0, 0), target(2, 10, 0), target(3, 20, 0)},
                                  {track(10, 0.5, 0), track(20, 10, 0), track(99, 50, 50)});
  REQUIRE(t1.matches.size() == 2);
  CHECK(t1.matches[0].target == 1);
  CHECK(t1.matches[0].track == 10);
  CHECK(t1.matches[0].distance == Approx(0.5).margin(1e-12));
  CHECK(t1.matches[1].target == 2);
  CHECK(t1.matches[1].track == 20);
  CHECK(t1.misses == std::vector<wsn::common::TargetId>{3});
  REQUIRE(t1.false_positives.size() == 1);
  CHECK(t1.false_positives[0].track == 99);
  CHECK(t1.id_switches.empty());
  CHECK(t1.fragmentations.empty());

  const ClearMotTick t2 =
      acc.add(2, {target(1, 0, 0), target(2, 10, 0), target(3, 20, 0)}, {track(11, 0, 0), track(20, 10, 0)});
  CHECK(t2.id_switches == std::vector<wsn::common::TargetId>{1});
  CHECK(t2.fragmentations.empty());
  CHECK(t2.false_positives.empty());

  const ClearMotTick t3 = acc.add(3, {target(1, 0, 0), target(3, 20, 0)}, {});
  CHECK(t3.misses == std::vector<wsn::common::TargetId>{1, 3});
  CHECK(t3.matches.empty());

  const ClearMotTick t4 = acc.add(4, {target(1, 0, 0), target(3, 20, 0)}, {track(11, 0, 0)});
  CHECK(t4.fragmentations == std::vector<wsn::common::TargetId>{1});
  CHECK(t4.id_switches.empty());

  // The events add up to the summary's counts.
  const ClearMotSummary s = acc.summary();
  CHECK(s.id_switches == 1);
  CHECK(s.fragmentations == 1);
  CHECK(s.false_positives == 1);
  CHECK(s.misses == 1 + 1 + 2 + 1);
}

#include "aggregator/track_quality.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "tests/aggregator/test_support.hpp"

using wsn::aggregator::TargetQuality;
using wsn::aggregator::TrackQualityAccumulator;
using wsn::aggregator::TrackQualitySummary;
using wsn::common::TargetState;
using wsn::common::TrackEstimate;

using wsn::aggregator::test::target;
using wsn::aggregator::test::track;

namespace {

constexpr double kNoGate = std::numeric_limits<double>::infinity();

}  // namespace

TEST_CASE("RSE and TLR and mean position error of one target follow their definitions", "[track_quality]") {
  // Target 1 moves along x at 1 m/s for 4 ticks; track 7 exists at ticks 1-3 only, with
  // position errors (0, 3), (4, 0), (0, 0) and velocity error (0, 3) at tick 3 only.
  //   RSE_pos = sqrt((9 + 16 + 0) / 3) = sqrt(25/3) = 2.886751
  //   RSE_vel = sqrt((0 + 0 + 9) / 3) = sqrt(3) = 1.732051
  //   ⟨dx⟩    = (3 + 4 + 0) / 3 = 2.333333
  //   TLR     = 3 associated ticks / 4 alive ticks = 0.75
  TrackQualityAccumulator acc(10.0);
  acc.add({target(1, 1, 0, 1, 0)}, {track(7, 1, 3, 1, 0)});
  acc.add({target(1, 2, 0, 1, 0)}, {track(7, 6, 0, 1, 0)});
  acc.add({target(1, 3, 0, 1, 0)}, {track(7, 3, 0, 1, 3)});
  acc.add({target(1, 4, 0, 1, 0)}, {});
  const TrackQualitySummary s = acc.summary();
  REQUIRE(s.targets.size() == 1);
  const TargetQuality& q = s.targets[0];
  CHECK(q.id == 1);
  CHECK(q.ticks_alive == 4);
  CHECK(q.ticks_associated == 3);
  CHECK(q.errors_defined);
  CHECK(q.rse_position == Approx(std::sqrt(25.0 / 3.0)).margin(1e-12));
  CHECK(q.rse_velocity == Approx(std::sqrt(3.0)).margin(1e-12));
  CHECK(q.mean_position_error == Approx(7.0 / 3.0).margin(1e-12));
  CHECK(q.tlr == Approx(0.75).margin(1e-12));
  CHECK(s.false_track_ticks == 0);
}

TEST_CASE("a perfect tracker has zero errors and TLR 1 for every target", "[track_quality]") {
  TrackQualityAccumulator acc(5.0);
  for (int t = 1; t <= 3; ++t)
    acc.add({target(1, t, 0, 1, 0), target(2, 0, t, 0, 1)}, {track(5, t, 0, 1, 0), track(6, 0, t, 0, 1)});
  const TrackQualitySummary s = acc.summary();
  REQUIRE(s.targets.size() == 2);
  for (const auto& q : s.targets) {
    CHECK(q.tlr == Approx(1.0).margin(1e-12));
    CHECK(q.rse_position == Approx(0.0).margin(1e-12));
    CHECK(q.rse_velocity == Approx(0.0).margin(1e-12));
    CHECK(q.mean_position_error == Approx(0.0).margin(1e-12));
  }
}

TEST_CASE("the association is unique: one track serves at most one target", "[track_quality]") {
  // Targets 1 at (0, 0) and 2 at (4, 0), one track at (1, 0), no gate. The assignment gives the
  // track to target 1 (d = 1 < 3): target 1 TLR 1, ⟨dx⟩ 1; target 2 TLR 0, errors undefined.
  TrackQualityAccumulator acc(kNoGate);
  acc.add({target(1, 0, 0), target(2, 4, 0)}, {track(9, 1, 0)});
  const TrackQualitySummary s = acc.summary();
  REQUIRE(s.targets.size() == 2);
  CHECK(s.targets[0].tlr == Approx(1.0).margin(1e-12));
  CHECK(s.targets[0].mean_position_error == Approx(1.0).margin(1e-12));
  CHECK(s.targets[1].tlr == Approx(0.0).margin(1e-12));
  CHECK_FALSE(s.targets[1].errors_defined);
  CHECK(s.targets[1].rse_position == 0.0);
  CHECK(s.false_track_ticks == 0);
}

TEST_CASE("tracks left over after the assignment are false tracks", "[track_quality]") {
  // More tracks than targets: target 1 at (0, 0); tracks at (0, 1), (0, 2), (30, 30).
  // The nearest (d = 1) is associated; the other two are false at this tick.
  TrackQualityAccumulator acc(kNoGate);
  acc.add({target(1, 0, 0)}, {track(1, 0, 2), track(2, 0, 1), track(3, 30, 30)});
  const TrackQualitySummary s = acc.summary();
  REQUIRE(s.targets.size() == 1);
  CHECK(s.targets[0].rse_position == Approx(1.0).margin(1e-12));
  CHECK(s.false_track_ticks == 2);
}

TEST_CASE("the gate keeps a distant track from being associated", "[track_quality]") {
  // Track 5 m away with a 3 m gate: not associated, TLR 0, and the track is false.
  TrackQualityAccumulator acc(3.0);
  acc.add({target(1, 0, 0)}, {track(1, 3, 4)});
  const TrackQualitySummary s = acc.summary();
  REQUIRE(s.targets.size() == 1);
  CHECK(s.targets[0].ticks_associated == 0);
  CHECK(s.targets[0].tlr == 0.0);
  CHECK(s.false_track_ticks == 1);
}

TEST_CASE("empty truth gives no targets and counts every track as false", "[track_quality]") {
  TrackQualityAccumulator acc(kNoGate);
  acc.add({}, {track(1, 0, 0), track(2, 1, 1)});
  acc.add({}, {});
  const TrackQualitySummary s = acc.summary();
  CHECK(s.targets.empty());
  CHECK(s.false_track_ticks == 2);
}

TEST_CASE("empty tracks leave every target untracked", "[track_quality]") {
  TrackQualityAccumulator acc(kNoGate);
  acc.add({target(1, 0, 0), target(2, 5, 5)}, {});
  const TrackQualitySummary s = acc.summary();
  REQUIRE(s.targets.size() == 2);
  for (const auto& q : s.targets) {
    CHECK(q.ticks_alive == 1);
    CHECK(q.tlr == 0.0);
    CHECK_FALSE(q.errors_defined);
  }
}

TEST_CASE("track quality ignores non-finite tracks and rejects a non-positive gate", "[track_quality]") {
  TrackQualityAccumulator acc(kNoGate);
  acc.add({target(1, 0, 0)}, {track(1, std::numeric_limits<double>::quiet_NaN(), 0)});
  const TrackQualitySummary s = acc.summary();
  CHECK(s.tracks_ignored_nonfinite == 1);
  CHECK(s.false_track_ticks == 0);
  CHECK(s.targets[0].ticks_associated == 0);
  CHECK_THROWS_AS(TrackQualityAccumulator(0.0), std::invalid_argument);
  CHECK_THROWS_AS(TrackQualityAccumulator(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

TEST_CASE("run means weigh every target once: RSE and dx over tracked targets, TLR over all", "[track_quality]") {
  // Target 1: tracked at both ticks with position errors 3 and 4 (velocity errors 0):
  //   RSE_pos = sqrt((9 + 16) / 2) = 3.535534, ⟨dx⟩ = 3.5, TLR 1.
  // Target 2: tracked at tick 1 only, error 1: RSE_pos = 1, ⟨dx⟩ = 1, TLR 0.5.
  // Target 3: never tracked (no track within the gate of 5): TLR 0, left out of the error means.
  //   mean RSE_pos = (3.535534 + 1) / 2, mean ⟨dx⟩ = (3.5 + 1) / 2 = 2.25,
  //   mean TLR = (1 + 0.5 + 0) / 3 = 0.5.
  TrackQualityAccumulator acc(5.0);
  acc.add({target(1, 0, 0), target(2, 20, 0), target(3, 40, 0)}, {track(1, 0, 3), track(2, 21, 0)});
  acc.add({target(1, 0, 0), target(2, 20, 0), target(3, 40, 0)}, {track(1, 4, 0)});
  const TrackQualitySummary s = acc.summary();
  CHECK(s.means_defined);
  CHECK(s.mean_rse_position == Approx((std::sqrt(12.5) + 1.0) / 2.0).margin(1e-12));
  CHECK(s.mean_rse_velocity == Approx(0.0).margin(1e-12));
  CHECK(s.mean_position_error == Approx(2.25).margin(1e-12));
  CHECK(s.mean_tlr == Approx(0.5).margin(1e-12));
}

TEST_CASE("run means are undefined when no target was ever tracked", "[track_quality]") {
  TrackQualityAccumulator none(kNoGate);
  CHECK_FALSE(none.summary().means_defined);
  CHECK(none.summary().mean_tlr == 0.0);
  TrackQualityAccumulator untracked(kNoGate);
  untracked.add({target(1, 0, 0)}, {});
  const TrackQualitySummary s = untracked.summary();
  CHECK_FALSE(s.means_defined);
  CHECK(s.mean_rse_position == 0.0);
  CHECK(s.mean_tlr == 0.0);
}

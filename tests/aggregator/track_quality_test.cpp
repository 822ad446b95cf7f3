#include "aggregator/track_quality.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
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
  // No target moves, so each path-length TLR is its duration TLR.
  CHECK(s.mean_tlr_length == Approx(0.5).margin(1e-12));
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
  CHECK(s.mean_tlr_length == 0.0);
}

TEST_CASE("path-length TLR weighs each tick by the distance the target moved, unlike duration TLR", "[track_quality]") {
  // Target 1 moves along x through 0, 1, 2, 3, 4, 8 at ticks 1-6 (1 m/s, then 4 m/s): the segments
  // ending at ticks 2-6 are 1, 1, 1, 1, 4, path P = 8. A track sits on it at ticks 1-5 only.
  //   TLR     = 5 / 6 = 0.833333
  //   TLR_len = (1 + 1 + 1 + 1) / 8 = 0.5  (tick 1 ends no segment, tick 6's 4 m is unassociated)
  // Target 2 follows the same path 100 m higher, tracked at tick 6 only: the fast last segment.
  //   TLR     = 1 / 6 = 0.166667
  //   TLR_len = 4 / 8 = 0.5
  const std::vector<double> xs{0, 1, 2, 3, 4, 8};
  TrackQualityAccumulator acc(1.0);
  for (std::size_t k = 0; k < xs.size(); ++k) {
    std::vector<TrackEstimate> tracks;
    if (k < 5) tracks.push_back(track(1, xs[k], 0));
    if (k == 5) tracks.push_back(track(2, xs[k], 100));
    acc.add({target(1, xs[k], 0), target(2, xs[k], 100)}, tracks);
  }
  const TrackQualitySummary s = acc.summary();
  REQUIRE(s.targets.size() == 2);
  const TargetQuality& a = s.targets[0];
  CHECK(a.tlr == Approx(5.0 / 6.0).margin(1e-12));
  CHECK(a.path_length == Approx(8.0).margin(1e-12));
  CHECK(a.path_length_associated == Approx(4.0).margin(1e-12));
  CHECK(a.tlr_length == Approx(0.5).margin(1e-12));
  const TargetQuality& b = s.targets[1];
  CHECK(b.tlr == Approx(1.0 / 6.0).margin(1e-12));
  CHECK(b.path_length == Approx(8.0).margin(1e-12));
  CHECK(b.path_length_associated == Approx(4.0).margin(1e-12));
  CHECK(b.tlr_length == Approx(0.5).margin(1e-12));
  CHECK(s.mean_tlr == Approx(0.5).margin(1e-12));
  CHECK(s.mean_tlr_length == Approx(0.5).margin(1e-12));
}

TEST_CASE("path-length TLR of a stopped target is its duration TLR and 0 for one tracked only while stopped",
          "[track_quality]") {
  // Target 1 stands at (5, 5) for 4 ticks, tracked at the first only: P = 0, so TLR_len = TLR = 0.25.
  // Target 2 moves 3 m then 4 m (ticks 1-3: (50, 0), (53, 0), (53, 4)) and stands there at ticks
  // 4-5; tracked at ticks 1, 4 and 5, the ticks at which it ends no move: P = 7, P^A = 0,
  // TLR = 3 / 5 = 0.6, TLR_len = 0.
  TrackQualityAccumulator acc(1.0);
  acc.add({target(1, 5, 5), target(2, 50, 0)}, {track(1, 5, 5), track(2, 50, 0)});
  acc.add({target(1, 5, 5), target(2, 53, 0)}, {});
  acc.add({target(1, 5, 5), target(2, 53, 4)}, {});
  acc.add({target(1, 5, 5), target(2, 53, 4)}, {track(2, 53, 4)});
  acc.add({target(2, 53, 4)}, {track(2, 53, 4)});
  const TrackQualitySummary s = acc.summary();
  REQUIRE(s.targets.size() == 2);
  CHECK(s.targets[0].path_length == 0.0);
  CHECK(s.targets[0].tlr == Approx(0.25).margin(1e-12));
  CHECK(s.targets[0].tlr_length == Approx(0.25).margin(1e-12));
  CHECK(s.targets[1].path_length == Approx(7.0).margin(1e-12));
  CHECK(s.targets[1].path_length_associated == 0.0);
  CHECK(s.targets[1].tlr == Approx(0.6).margin(1e-12));
  CHECK(s.targets[1].tlr_length == 0.0);
  CHECK(s.mean_tlr_length == Approx(0.125).margin(1e-12));
}

TEST_CASE("path-length TLR counts no segment across ticks at which the target is absent", "[track_quality]") {
  // Target 1 at (0, 0), (3, 4), absent one tick, then (100, 0) and (106, 8), tracked throughout:
  // P = 5 + 10 = 15 (the jump over the gap is no segment), P^A = 15, TLR_len = 1. Untracked at the
  // last tick instead: P^A = 5, TLR_len = 1/3.
  for (const bool last_tracked : {true, false}) {
    TrackQualityAccumulator acc(1.0);
    acc.add({target(1, 0, 0)}, {track(1, 0, 0)});
    acc.add({target(1, 3, 4)}, {track(1, 3, 4)});
    acc.add({}, {});
    acc.add({target(1, 100, 0)}, {track(1, 100, 0)});
    acc.add({target(1, 106, 8)}, last_tracked ? std::vector<TrackEstimate>{track(1, 106, 8)}
                                               : std::vector<TrackEstimate>{});
    const TrackQualitySummary s = acc.summary();
    REQUIRE(s.targets.size() == 1);
    CHECK(s.targets[0].path_length == Approx(15.0).margin(1e-12));
    CHECK(s.targets[0].tlr_length == Approx(last_tracked ? 1.0 : 5.0 / 15.0).margin(1e-12));
  }
}

// Re-homing a dead supernode's tracking group (supernode/rehome.hpp): g() over the live
// supernodes, the dead one's last tracks as handoffs to the adopters, a tracker that hands its
// tracks to live supernodes only, and a tracker that starts afresh after a pause.
#include "supernode/rehome.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "supernode/supernode_tracker.hpp"
#include "tests/supernode/test_support.hpp"

namespace wsn::supernode {
namespace {

using test::observation;

/// Three supernodes on the x axis at 0, 10 and 20.
const std::vector<common::Vec2> kLine = {{0, 0}, {10, 0}, {20, 0}};

TEST_CASE("the nearest live supernode skips the dead ones, ties going to the lower index", "[rehome]") {
  // Empty mask: all live.
  CHECK(nearestLiveSupernode(kLine, {}, {9, 0}) == 1);
  CHECK(nearestLiveSupernode(kLine, {}, {5, 0}) == 0);   // tie between 0 and 1
  CHECK(nearestLiveSupernode(kLine, {}, {15, 3}) == 1);  // tie between 1 and 2
  CHECK(nearestLiveSupernode(kLine, {true, true, true}, {9, 0}) == 1);
  // Supernode 1 dead: its cell is split between 0 and 2 at x = 10.
  const std::vector<bool> without1 = {true, false, true};
  CHECK(nearestLiveSupernode(kLine, without1, {9, 0}) == 0);
  CHECK(nearestLiveSupernode(kLine, without1, {11, 0}) == 2);
  CHECK(nearestLiveSupernode(kLine, without1, {10, 0}) == 0);  // tie
  CHECK(nearestLiveSupernode(kLine, without1, {10, -4}) == 0);  // tie
  // Supernode 0 dead: the search does not start from it.
  CHECK(nearestLiveSupernode(kLine, {false, true, true}, {0, 0}) == 1);
  CHECK(nearestLiveSupernode(kLine, {false, false, true}, {-50, 0}) == 2);
  CHECK(nearestLiveSupernode(kLine, {false, true, true}, {15, 0}) == 1);  // tie between 1 and 2
  // None live: 0.
  CHECK(nearestLiveSupernode(kLine, {false, false, false}, {19, 0}) == 0);
}

common::TrackEstimate estimate(common::TrackId id, double x, double vx, std::int32_t last_seen) {
  common::TrackEstimate t;
  t.track = id;
  t.x = x;
  t.y = 1.0;
  t.vx = vx;
  t.vy = 0.0;
  t.last_seen_tick = last_seen;
  for (std::size_t k = 0; k < 16; ++k) t.covariance[k] = static_cast<double>(id) + 0.01 * static_cast<double>(k);
  return t;
}

TEST_CASE("orphaned tracks go to the live supernode nearest their next position, ids kept, sorted",
          "[rehome]") {
  // Supernode 1 died; Δ = 5, ws = 7; the dead supernode's last tick was 15.
  const OrphanContext context{kLine, {true, false, true}, 5.0, 7};
  auto a = estimate(30, 4.0, -1.0, 15);   // next x = -1: supernode 0
  auto b = estimate(10, 9.0, 0.6, 12);    // next x = 12: supernode 2 (x alone, 9, and x + v, 9.6, are 0's)
  auto nan = estimate(20, 8.0, std::numeric_limits<double>::quiet_NaN(), 15);
  auto c = estimate(25, 10.0, 0.0, 0);    // next x = 10: the tie goes to 0; never seen: no misses
  auto inf = estimate(5, std::numeric_limits<double>::infinity(), 0.0, 15);
  c.class_probabilities = {0.25, 0.75};
  const auto out = orphanHandoffs({a, b, nan, c, inf}, 15, context);
  REQUIRE(out.size() == 3);
  CHECK(out[0].track == 10);
  CHECK(out[1].track == 25);
  CHECK(out[2].track == 30);
  CHECK(out[0].to_supernode == 2);
  CHECK(out[1].to_supernode == 0);
  CHECK(out[2].to_supernode == 0);
  // Misses: the ticks since the track was last seen.
  CHECK(out[0].misses == 3);
  CHECK(out[1].misses == 0);
  CHECK(out[2].misses == 0);
  for (const auto& h : out) {
    CHECK(h.last_tick == 15);
    CHECK(h.hits == 7);
    CHECK(h.confirmed);
  }
  // State and covariance as the dead supernode reported them.
  CHECK(out[0].state == std::array<double, 4>{9.0, 1.0, 0.6, 0.0});
  CHECK(out[0].covariance == b.covariance);
  CHECK(out[2].covariance == a.covariance);
  CHECK(out[1].class_probabilities == std::vector<double>{0.25, 0.75});
  CHECK(out[0].class_probabilities.empty());

  // With every supernode live, b's next position (12) is 1's.
  const OrphanContext all{kLine, {}, 5.0, 7};
  CHECK(orphanHandoffs({b}, 15, all).at(0).to_supernode == 1);
  // With Δ = 1 b's next position is 9.6, still 0's.
  const OrphanContext short_tick{kLine, {true, false, true}, 1.0, 7};
  CHECK(orphanHandoffs({b}, 15, short_tick).at(0).to_supernode == 0);
  CHECK(orphanHandoffs({}, 15, context).empty());
}

/// A tracker of supernode 0 among {(25, 50), (75, 50), (75, 49)} following x = 40.5 + t,
/// y = 50 + 0.2 t: its prediction crosses x = 50 for tick 10 (supernode_tracker_test's crossing).
/// Returns the first handoff it releases, if any, with the tick it was released at.
struct Released {
  std::optional<common::TrackHandoff> handoff;
  std::int32_t tick = 0;
  std::vector<common::TrackId> tracks_at_end;  ///< confirmed, at the last tick
  common::TrackId first_track = 0;            ///< the first confirmed track
};

Released crossing(const std::optional<std::vector<bool>>& live) {
  auto s = test::gnnScenario();
  s.supernodes = {{25.0, 50.0}, {75.0, 50.0}, {75.0, 49.0}};
  SupernodeTracker tracker = test::trackerFor(s, 0);
  if (live) tracker.setLiveSupernodes(*live);
  Released r;
  for (std::int32_t t = 1; t <= 14; ++t) {
    const auto out = tracker.step(t, std::vector<common::Observation>{observation(t, t, 40.5 + t, 50.0 + 0.2 * t)}, {});
    if (!r.handoff && !out.handoffs.empty()) {
      r.handoff = out.handoffs.front();
      r.tick = t;
    }
    r.tracks_at_end.clear();
    for (const auto& track : out.tracks) r.tracks_at_end.push_back(track.track);
    if (r.first_track == 0 && !out.tracks.empty()) r.first_track = out.tracks.front().track;
  }
  return r;
}

TEST_CASE("a track predicted into a dead supernode's cell goes to the nearest live one", "[rehome][tracker]") {
  // All live: (50.5, 52) is nearest (75, 50) of supernode 1.
  const Released all = crossing(std::nullopt);
  REQUIRE(all.handoff.has_value());
  CHECK(all.tick == 9);
  CHECK(all.handoff->to_supernode == 1);
  CHECK(all.handoff->track == all.first_track);
  // Supernode 1 dead: (75, 49) of supernode 2 is nearer than (25, 50).
  const Released without1 = crossing(std::vector<bool>{true, false, true});
  REQUIRE(without1.handoff.has_value());
  CHECK(without1.tick == 9);
  CHECK(without1.handoff->to_supernode == 2);
  CHECK(without1.handoff->track == all.handoff->track);
  // Only supernode 0 live: its group is the whole region, and it keeps the track.
  const Released alone = crossing(std::vector<bool>{true, false, false});
  CHECK_FALSE(alone.handoff.has_value());
  CHECK(alone.tracks_at_end == std::vector<common::TrackId>{all.first_track});
}

TEST_CASE("a tracker started afresh settles nothing before its first tick", "[rehome][tracker]") {
  const auto s = test::gnnScenario(10);
  SupernodeTracker fresh(supernodeConfig(s, 0), 21);
  // ws = 10: tick 21 leaves the window after tick 30.
  for (std::int32_t t = 21; t <= 29; ++t) {
    const auto out = fresh.step(t, {}, {});
    INFO("tick " << t);
    CHECK(out.settled.by_tick.empty());
  }
  const auto at30 = fresh.step(30, {}, {});
  CHECK(at30.settled.first == 21);
  CHECK(at30.settled.by_tick.size() == 1);
  CHECK(fresh.step(31, {}, {}).settled.first == 22);
  fresh.step(32, {}, {});  // settles 23
  const auto rest = fresh.settleRemaining();
  CHECK(rest.first == 24);
  CHECK(rest.last() == 32);

  // Whereas a tracker from the run's start, first stepped at 21, settles ticks 1 to 12 there.
  SupernodeTracker from_start(supernodeConfig(s, 0));
  const auto first = from_start.step(21, {}, {});
  CHECK(first.settled.first == 1);
  CHECK(first.settled.by_tick.size() == 12);

  // Stopped before its window filled, it settles from its first tick on.
  SupernodeTracker short_lived(supernodeConfig(s, 0), 21);
  for (std::int32_t t = 21; t <= 25; ++t) short_lived.step(t, {}, {});
  const auto remaining = short_lived.settleRemaining();
  CHECK(remaining.first == 21);
  CHECK(remaining.by_tick.size() == 5);
}

}  // namespace
}  // namespace wsn::supernode

#include "aggregator/track_merger.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

using wsn::aggregator::SupernodeTracks;
using wsn::aggregator::TrackMerger;
using wsn::aggregator::TrackMergerConfig;
using wsn::common::TrackEstimate;
using wsn::common::TrackId;

namespace {

/// A supernode's track id, as common/messages.hpp defines it.
TrackId id(std::uint32_t supernode, std::uint64_t serial) { return (TrackId{supernode} + 1) << 48 | serial; }

TrackEstimate track(TrackId track_id, double x, double y, double vx = 1.0, double vy = 0.0) {
  return {track_id, x, y, vx, vy, {}, 0, {}, {}};
}

bool sortedById(const std::vector<TrackEstimate>& tracks) {
  return std::is_sorted(tracks.begin(), tracks.end(), [](const auto& a, const auto& b) { return a.track < b.track; });
}

}  // namespace

TEST_CASE("Duplicate tracks at a tracking-group boundary merge into one", "[aggregator][merger]") {
  TrackMerger merger;
  const TrackId a = id(0, 1);
  const TrackId b = id(1, 1);
  // 0.5 apart, well inside the 3-separation gate: one target. Id: the smaller, a. State: the mean,
  // x = (10 + 10.5) / 2 = 10.25, vx = (1 + 1.2) / 2 = 1.1.
  const auto global = merger.merge(1, {{0, {track(a, 10, 10, 1.0)}}, {1, {track(b, 10.5, 10, 1.2)}}});
  REQUIRE(global.size() == 1);
  CHECK(global[0].track == a);
  CHECK(global[0].x == Approx(10.25).margin(1e-12));
  CHECK(global[0].y == Approx(10.0).margin(1e-12));
  CHECK(global[0].vx == Approx(1.1).margin(1e-12));
}

TEST_CASE("A merged global track keeps its id across ticks", "[aggregator][merger]") {
  const TrackId a = id(0, 1);
  const TrackId b = id(1, 1);
  SECTION("the first supernode's track alone, then both, then only the second") {
    TrackMerger merger;
    CHECK(merger.merge(1, {{0, {track(a, 10, 10)}}, {1, {}}}).at(0).track == a);
    CHECK(merger.merge(2, {{0, {track(a, 11, 10)}}, {1, {track(b, 11.3, 10)}}}).at(0).track == a);
    // Only b is left, but b belonged to global track a at tick 2: still a.
    const auto third = merger.merge(3, {{0, {}}, {1, {track(b, 12, 10)}}});
    REQUIRE(third.size() == 1);
    CHECK(third[0].track == a);
    CHECK(third[0].x == 12.0);
    CHECK(merger.merge(4, {{1, {track(b, 13, 10)}}}).at(0).track == a);
    // Without that memory b would be called b.
    TrackMerger fresh;
    CHECK(fresh.merge(3, {{1, {track(b, 12, 10)}}}).at(0).track == b);
  }
  SECTION("the previous global id wins over the smaller id") {
    TrackMerger merger;
    CHECK(merger.merge(1, {{1, {track(b, 10, 10)}}}).at(0).track == b);
    // a < b joins the target b has been tracking: the global track stays b.
    CHECK(merger.merge(2, {{0, {track(a, 11, 10)}}, {1, {track(b, 11.3, 10)}}}).at(0).track == b);
    CHECK(merger.merge(3, {{0, {track(a, 12, 10)}}}).at(0).track == b);
  }
}

TEST_CASE("A handed-over track keeps its id", "[aggregator][merger]") {
  TrackMerger merger;
  const TrackId a = id(0, 7);
  CHECK(merger.merge(1, {{0, {track(a, 49, 10)}}, {1, {}}}).at(0).track == a);
  // Tick 2: both report a (sender not yet released it): one target, id a.
  const auto both = merger.merge(2, {{0, {track(a, 50, 10)}}, {1, {track(a, 50.2, 10)}}});
  REQUIRE(both.size() == 1);
  CHECK(both[0].track == a);
  CHECK(both[0].x == Approx(50.1).margin(1e-12));
  // Tick 3: only the receiver.
  CHECK(merger.merge(3, {{0, {}}, {1, {track(a, 51, 10)}}}).at(0).track == a);
}

TEST_CASE("Far-apart tracks stay separate", "[aggregator][merger]") {
  TrackMerger merger;
  const auto global = merger.merge(1, {{0, {track(id(0, 1), 10, 10)}}, {1, {track(id(1, 1), 20, 10)}}});
  REQUIRE(global.size() == 2);
  CHECK(global[0] == track(id(0, 1), 10, 10));
  CHECK(global[1] == track(id(1, 1), 20, 10));
}

TEST_CASE("The gate is inclusive at gate_distance", "[aggregator][merger]") {
  // Default gate 3: (0,0)-(3,0) is exactly 3 apart -> merged; (0,0)-(3.001,0) -> separate.
  TrackMerger merger;
  CHECK(merger.merge(1, {{0, {track(id(0, 1), 0, 0)}}, {1, {track(id(1, 1), 3, 0)}}}).size() == 1);
  CHECK(merger.merge(2, {{0, {track(id(0, 2), 0, 50)}}, {1, {track(id(1, 2), 3.001, 50)}}}).size() == 2);
  // A custom gate of 1: 1.5 apart stays separate.
  TrackMerger narrow(TrackMergerConfig{1.0, 10});
  CHECK(narrow.merge(1, {{0, {track(id(0, 1), 0, 0)}}, {1, {track(id(1, 1), 1.5, 0)}}}).size() == 2);
}

TEST_CASE("Tracks of one supernode are never merged with each other", "[aggregator][merger]") {
  TrackMerger merger;
  // 0.5 apart but from the same supernode: its tracker says two targets.
  CHECK(merger.merge(1, {{0, {track(id(0, 1), 0, 0), track(id(0, 2), 0.5, 0)}}}).size() == 2);
}

TEST_CASE("Pairs across supernodes are formed by optimal assignment", "[aggregator][merger]") {
  TrackMerger merger;
  // Two targets 2.5 apart, each seen by both supernodes; every cross pair is inside the gate.
  // Squared distances: a1-b1 0.04, a2-b2 0.01 (total 0.05) vs a1-b2 5.76, a2-b1 5.29 (total 11.05).
  const auto global = merger.merge(1, {{0, {track(id(0, 1), 0, 0), track(id(0, 2), 2.5, 0)}},
                                       {1, {track(id(1, 1), 0.2, 0), track(id(1, 2), 2.4, 0)}}});
  REQUIRE(global.size() == 2);
  // Means: (0 + 0.2) / 2 = 0.1 and (2.5 + 2.4) / 2 = 2.45; ids are the first supernode's (smaller).
  CHECK(global[0].track == id(0, 1));
  CHECK(global[0].x == Approx(0.1).margin(1e-12));
  CHECK(global[1].track == id(0, 2));
  CHECK(global[1].x == Approx(2.45).margin(1e-12));
}

TEST_CASE("Three supernodes at a corner merge into one track", "[aggregator][merger]") {
  TrackMerger merger;
  // Pairwise within 3 of each other: one target, mean ((0 + 1 + 0.5) / 3, (0 + 0 + 1) / 3) = (0.5, 1/3).
  const auto global = merger.merge(
      1, {{2, {track(id(2, 4), 0.5, 1)}}, {0, {track(id(0, 9), 0, 0)}}, {1, {track(id(1, 3), 1, 0)}}});
  REQUIRE(global.size() == 1);
  CHECK(global[0].track == id(0, 9));
  CHECK(global[0].x == Approx(0.5).margin(1e-12));
  CHECK(global[0].y == Approx(1.0 / 3.0).margin(1e-12));
}

TEST_CASE("A global track that splits keeps its id on the member that carries it", "[aggregator][merger]") {
  TrackMerger merger;
  const TrackId a = id(0, 1);
  const TrackId b = id(1, 1);
  CHECK(merger.merge(1, {{0, {track(a, 10, 10)}}, {1, {track(b, 10.5, 10)}}}).at(0).track == a);
  // They were two targets after all: 10 apart now. Both b and a were in global a; a also is a, so
  // a keeps a (benefit 2 + 1 = 3) and b falls back to its own id (b keeping a would leave a none).
  const auto split = merger.merge(2, {{0, {track(a, 10, 10)}}, {1, {track(b, 20, 10)}}});
  REQUIRE(split.size() == 2);
  CHECK(split[0].track == a);
  CHECK(split[0].x == 10.0);
  CHECK(split[1].track == b);
  CHECK(split[1].x == 20.0);
}

TEST_CASE("One id reported at two far-apart places still gives unique global ids", "[aggregator][merger]") {
  TrackMerger merger;
  const TrackId a = id(0, 1);
  const auto global = merger.merge(1, {{0, {track(a, 10, 10)}}, {1, {track(a, 60, 60)}}});
  REQUIRE(global.size() == 2);
  // One keeps a, the other gets an id minted by the aggregator (supernode field 0, i.e. < 1 << 48).
  const std::set<TrackId> ids{global[0].track, global[1].track};
  CHECK(ids.size() == 2);
  CHECK(ids.count(a) == 1);
  CHECK(*ids.begin() < (TrackId{1} << 48));
  CHECK(sortedById(global));
}

TEST_CASE("Empty inputs give no tracks and keep the memory", "[aggregator][merger]") {
  TrackMerger merger;
  CHECK(merger.merge(1, {}).empty());
  CHECK(merger.merge(2, {{0, {}}, {1, {}}}).empty());
  const TrackId a = id(0, 1);
  const TrackId b = id(1, 1);
  CHECK(merger.merge(3, {{0, {track(a, 10, 10)}}, {1, {track(b, 10.5, 10)}}}).at(0).track == a);
  CHECK(merger.merge(4, {}).empty());
  // b reappears within memory_ticks (10) of tick 3: still global a.
  CHECK(merger.merge(5, {{1, {track(b, 12, 10)}}}).at(0).track == a);
}

TEST_CASE("The id memory expires after memory_ticks", "[aggregator][merger]") {
  TrackMerger merger(TrackMergerConfig{3.0, 2});
  const TrackId a = id(0, 1);
  const TrackId b = id(1, 1);
  CHECK(merger.merge(1, {{0, {track(a, 10, 10)}}, {1, {track(b, 10.5, 10)}}}).at(0).track == a);
  // Tick 3 is 2 ticks after tick 1: remembered. Tick 6 is 3 after tick 3: forgotten.
  CHECK(merger.merge(3, {{1, {track(b, 12, 10)}}}).at(0).track == a);
  CHECK(merger.merge(6, {{1, {track(b, 15, 10)}}}).at(0).track == b);
}

TEST_CASE("Merging does not depend on the order of inputs or tracks", "[aggregator][merger]") {
  // Random tracks of 4 supernodes over 30 ticks, some of them duplicates of others; the second
  // merger gets every tick's inputs and tracks shuffled.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> position(0.0, 30.0), jitter(-1.0, 1.0);
  TrackMerger ordered, shuffled;
  for (std::int32_t t = 1; t <= 30; ++t) {
    std::vector<SupernodeTracks> inputs;
    for (std::uint32_t s = 0; s < 4; ++s) {
      SupernodeTracks input{s, {}};
      for (std::uint64_t k = 1; k <= 5; ++k) input.tracks.push_back(track(id(s, k), position(random), position(random), jitter(random)));
      inputs.push_back(input);
    }
    // Some duplicates: supernode 1 repeats 2 of supernode 0's tracks, slightly off.
    inputs[1].tracks.push_back(track(id(1, 9), inputs[0].tracks[0].x + 0.3, inputs[0].tracks[0].y));
    inputs[1].tracks.push_back(track(id(0, 2), inputs[0].tracks[1].x - 0.2, inputs[0].tracks[1].y));
    auto permuted = inputs;
    std::shuffle(permuted.begin(), permuted.end(), random);
    for (auto& input : permuted) std::shuffle(input.tracks.begin(), input.tracks.end(), random);
    const auto expected = ordered.merge(t, inputs);
    const auto actual = shuffled.merge(t, permuted);
    REQUIRE(expected == actual);  // bit for bit: same order of every floating-point sum
    CHECK(sortedById(expected));
    std::set<TrackId> ids;
    for (const auto& g : expected) ids.insert(g.track);
    CHECK(ids.size() == expected.size());
  }
}

TEST_CASE("Tracks with non-finite fields are dropped and counted", "[aggregator][merger]") {
  TrackMerger merger;
  const auto global = merger.merge(1, {{0, {track(id(0, 1), NAN, 0), track(id(0, 2), 5, 5)}},
                                       {1, {track(id(1, 1), 5, INFINITY)}}});
  REQUIRE(global.size() == 1);
  CHECK(global[0].track == id(0, 2));
  CHECK(merger.droppedNonFinite() == 2);
}

TEST_CASE("TrackMerger rejects a bad configuration", "[aggregator][merger]") {
  CHECK_THROWS_AS(TrackMerger(TrackMergerConfig{-1.0, 10}), std::invalid_argument);
  CHECK_THROWS_AS(TrackMerger(TrackMergerConfig{NAN, 10}), std::invalid_argument);
  CHECK_THROWS_AS(TrackMerger(TrackMergerConfig{3.0, -1}), std::invalid_argument);
}

TEST_CASE("A merged global track's class fuses its members' class vectors", "[aggregator][merger]") {
  TrackMerger merger;
  auto a = track(id(0, 1), 10, 10);
  auto b = track(id(1, 1), 10.5, 10);
  auto unclassified = track(id(1, 2), 40, 10);
  a.class_probabilities = {0.8, 0.2};
  b.class_probabilities = {0.5, 0.5};
  const auto global = merger.merge(1, {{0, {a}}, {1, {b, unclassified}}});
  REQUIRE(global.size() == 2);
  // The normalised geometric mean (common/class_evidence.hpp): 2 : 1, as sqrt(.4) : sqrt(.1).
  REQUIRE(global[0].class_probabilities.size() == 2);
  CHECK(global[0].class_probabilities[0] == Approx(2.0 / 3.0).epsilon(1e-12));
  // A lone track without class evidence stays without.
  CHECK(global[1].class_probabilities.empty());
}

TEST_CASE("A merged global track's stop probability fuses its members' by the same rule", "[aggregator][merger]") {
  TrackMerger merger;
  auto a = track(id(0, 1), 10, 10);
  auto b = track(id(1, 1), 10.5, 10);
  const auto without = track(id(1, 2), 40, 10);
  a.stop_probability = 0.9;
  b.stop_probability = 0.6;
  const auto global = merger.merge(1, {{0, {a}}, {1, {b, without}}});
  REQUIRE(global.size() == 2);
  // sqrt(.9 x .6) / (sqrt(.9 x .6) + sqrt(.1 x .4)) = .734847 / .934847.
  REQUIRE(global[0].stop_probability);
  CHECK(*global[0].stop_probability == Approx(0.786062).epsilon(1e-6));
  CHECK_FALSE(global[1].stop_probability);  // a lone track of an engine without a stop model
}

// The chain's start state: two tracks that hold one target's reports in turns become one where
// eq. (3) prefers it, and stay apart where they are two targets.
#include <catch2/catch.hpp>

#include <vector>

#include "supernode/mcmcda/start_state.hpp"

namespace wsn::supernode::mcmcda {
namespace {

McmcdaParams straightLineParams() {
  McmcdaParams p;
  p.model.detection_probability = 0.5;
  p.model.measurement_sigma = 0.1;
  p.model.process_noise_sigma = 0.05;
  p.model.initial_velocity_sigma = 1.0;
  p.model.max_speed = 3.0;
  p.model.max_gap = 3;
  return p;
}

/// The window problem of the given reports (tick, x, y), no anchors, newest tick `last`.
WindowProblem problemOf(const McmcdaParams& params, const std::vector<std::array<double, 3>>& reports,
                        std::int32_t last) {
  std::vector<ProblemObservation> observations;
  std::vector<ObservationKey> keys;
  common::SensorId sensor = 0;
  for (const auto& [tick, x, y] : reports) {
    observations.push_back({static_cast<std::int32_t>(tick), x, y, false, {}});
    keys.push_back({static_cast<std::int32_t>(tick), sensor++, x, y});
  }
  const auto n = observations.size();
  return WindowProblem{Problem(params.model, std::move(observations), last), std::move(keys),
                       std::vector<std::int32_t>(n, -1), {}};
}

/// A previous track holding the given elements of `wp`.
LiveTrack trackOf(const WindowProblem& wp, common::TrackId id, const std::vector<std::size_t>& elements) {
  LiveTrack track;
  track.id = id;
  for (const auto i : elements) track.observations.push_back(wp.keys[i]);
  track.states.resize(elements.size());
  return track;
}

}  // namespace

TEST_CASE("two tracks that hold one target's reports in turns start the chain as one") {
  // One target along y = 0 at 1 per tick, its reports of ticks 1, 3, 5 in track 1 and of 2, 4, 6 in
  // track 2, as a delayed network leaves them: one track of six reports saves a birth, a
  // termination, misses and two false-alarm-free gaps, and eq. (3) prefers it by far.
  const McmcdaParams params = straightLineParams();
  WindowProblem wp = problemOf(params, {{1, 0, 0}, {2, 1, 0.05}, {3, 2, 0}, {4, 3, -0.05}, {5, 4, 0}, {6, 5, 0}}, 6);
  wp.anchor_index = {-1, -1};
  const std::vector<LiveTrack> previous = {trackOf(wp, 1, {0, 2, 4}), trackOf(wp, 2, {1, 3, 5})};
  const StartState start = startState(wp, previous, {}, params);
  REQUIRE(start.partition.size() == 1);
  CHECK(start.partition[0] == std::vector<std::int32_t>{0, 1, 2, 3, 4, 5});
  // A late report of tick 3 that no track holds is placed inside the track it fits.
  WindowProblem late = problemOf(params, {{1, 0, 0}, {2, 1, 0}, {3, 2, 0.05}, {4, 3, 0}, {5, 4, 0}}, 5);
  late.anchor_index = {-1};
  const StartState placed = startState(late, {trackOf(late, 1, {0, 1, 3, 4})}, {}, params);
  REQUIRE(placed.partition.size() == 1);
  CHECK(placed.partition[0] == std::vector<std::int32_t>{0, 1, 2, 3, 4});
}

TEST_CASE("two targets' tracks whose ticks interleave stay two") {
  // Target A along y = 0, target B along y = 2.5 (within reach, 3 per tick, of A's reports): their
  // tracks take turns at reports, but a track that zigzags 2.5 between ticks is far less likely
  // than two straight ones, so the start state keeps them apart.
  const McmcdaParams params = straightLineParams();
  WindowProblem wp =
      problemOf(params, {{1, 0, 0}, {2, 1, 2.5}, {3, 2, 0}, {4, 3, 2.5}, {5, 4, 0}, {6, 5, 2.5}}, 6);
  wp.anchor_index = {-1, -1};
  const StartState start = startState(wp, {trackOf(wp, 1, {0, 2, 4}), trackOf(wp, 2, {1, 3, 5})}, {}, params);
  REQUIRE(start.partition.size() == 2);
  CHECK(start.partition[0] == std::vector<std::int32_t>{0, 2, 4});
  CHECK(start.partition[1] == std::vector<std::int32_t>{1, 3, 5});
}

}  // namespace wsn::supernode::mcmcda

// Properties of the MCMCDA sampler beyond exactness: its iterations never allocate, its score
// bookkeeping matches a fresh evaluation, and it is deterministic given the seed.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <numbers>
#include <vector>

#include <catch2/catch.hpp>

#include "common/rng.hpp"
#include "common/sensor_coverage.hpp"
#include "supernode/mcmcda/problem.hpp"
#include "supernode/mcmcda/sampler.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
// ASan and TSan own operator new and malloc, so the program cannot replace them; their allocator
// reports every allocation to a hook instead, which counts the same thing.
// Declared here, as in compiler-rt's <sanitizer/allocator_interface.h>, which GCC does not install.
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*, std::size_t),
                                                         void (*free_hook)(const volatile void*));
namespace {
void countAllocation(const volatile void*, std::size_t) { ++g_allocations; }
void ignoreFree(const volatile void*) {}
[[maybe_unused]] const int g_hooks_installed = __sanitizer_install_malloc_and_free_hooks(countAllocation, ignoreFree);
}  // namespace
#else
// Counts every allocation of this test program, so that a test can assert that a code path
// allocates nothing. (Replacing the global operator new is the standard's own hook for this.)
// GCC cannot see that these replacements pair malloc with free and warns; the pairing is right.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop
#endif

namespace wsn::supernode::mcmcda {
namespace {

/// A busy window: 6 targets over 10 ticks, detected with probability 0.8, plus 3 false alarms a
/// tick, over a 30 x 30 area.
Problem busyProblem() {
  std::vector<ProblemObservation> obs;
  for (std::int32_t t = 1; t <= 10; ++t) {
    common::Stream rng(3, common::Purpose::kSensorNoise, 0, t);
    for (int k = 0; k < 6; ++k) {
      if (!rng.bernoulli(0.8)) continue;
      obs.push_back({t, 5.0 + 4.0 * k + 0.9 * t + 0.1 * rng.normal(), 5.0 + 2.5 * k + 0.5 * t + 0.1 * rng.normal(),
                     false, {}});
    }
    for (int c = 0; c < 3; ++c) obs.push_back({t, rng.uniform(0, 30), rng.uniform(0, 30), false, {}});
  }
  ModelParams p;
  p.false_alarm_density = 3.0 / 900.0;
  return Problem(p, obs, 10);
}

}  // namespace

TEST_CASE("mcmcda sampler iterations do not allocate", "[mcmcda]") {
  const Problem problem = busyProblem();
  Sampler sampler(problem, GENERATE(ProposalSets::kKept, ProposalSets::kRescan));
  common::Stream rng(1, common::Purpose::kTracker, 0, 0);
  sampler.run(2000, rng);  // away from the empty start
  // The counter must see an allocation, or the zero below would prove nothing.
  const long probe = g_allocations.load();
  {
    std::vector<int> allocated(16);
    asm volatile("" : : "g"(allocated.data()) : "memory");  // keeps the allocation from being elided
  }
  REQUIRE(g_allocations.load() > probe);
  const long before = g_allocations.load();
  sampler.run(20000, rng);
  CHECK(g_allocations.load() - before == 0);
  CHECK(sampler.trackCount() >= 4);
}

TEST_CASE("mcmcda sampler's running log posterior equals a fresh evaluation", "[mcmcda]") {
  const Problem problem = busyProblem();
  Sampler sampler(problem);
  common::Stream rng(2, common::Purpose::kTracker, 0, 0);
  for (int round = 0; round < 20; ++round) {
    sampler.run(500, rng);
    const Partition state = sampler.state();
    REQUIRE(validatePartition(problem, state).empty());
    CHECK(sampler.logPosterior() == Approx(logPosterior(problem, state)).margin(1e-9));
  }
  const Partition best = sampler.bestState();
  REQUIRE(validatePartition(problem, best).empty());
  CHECK(sampler.bestLogPosterior() == Approx(logPosterior(problem, best)).margin(1e-9));
}

TEST_CASE("mcmcda sampler is deterministic given the seed", "[mcmcda]") {
  const Problem problem = busyProblem();
  const auto chain = [&](std::uint64_t seed) {
    Sampler sampler(problem);
    common::Stream rng(seed, common::Purpose::kTracker, 0, 0);
    sampler.run(3000, rng);
    return sampler.state();
  };
  CHECK(chain(5) == chain(5));
}

TEST_CASE("mcmcda sampler draws births and merges from exactly the sets a rescan of its state finds", "[mcmcda]") {
  // Kept sets follow what each move changed; the definition on the partition is what they, and
  // the sampler's own rescans, must match after every kind of move, accepted or undone.
  const ProposalSets sets = GENERATE(ProposalSets::kKept, ProposalSets::kRescan);
  const Problem problem = busyProblem();
  Sampler sampler(problem, sets);
  common::Stream rng(7, common::Purpose::kTracker, 0, 0);
  // Every 25 rounds the tracks are cut in two, so that merges are accepted, not only births and
  // deaths. Splits, reductions and switches are rarely accepted near the posterior's mode, but
  // each rejected one has changed the state and undone it, which the sets must follow too.
  const auto fragment = [&] {
    Partition pieces;
    for (const auto& track : sampler.state()) {
      const std::size_t half = track.size() >= 4 ? track.size() / 2 : track.size();
      pieces.emplace_back(track.begin(), track.begin() + static_cast<std::ptrdiff_t>(half));
      if (half < track.size()) pieces.emplace_back(track.begin() + static_cast<std::ptrdiff_t>(half), track.end());
    }
    sampler.setState(pieces);
  };
  int checked_with_pairs = 0;
  for (int round = 0; round < 400; ++round) {
    if (round % 25 == 10) fragment();
    sampler.run(1 + round % 7, rng);
    const Partition state = sampler.state();
    std::vector<std::int32_t> owner(static_cast<std::size_t>(problem.size()), -1);
    std::vector<bool> first(static_cast<std::size_t>(problem.size()), false);
    for (std::size_t k = 0; k < state.size(); ++k) {
      for (const std::int32_t i : state[k]) owner[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(k);
      first[static_cast<std::size_t>(state[k].front())] = true;
    }
    std::vector<std::int32_t> starts;
    for (std::int32_t i = 0; i < problem.size(); ++i) {
      if (owner[static_cast<std::size_t>(i)] >= 0) continue;
      for (const std::int32_t j : problem.successors(i))
        if (owner[static_cast<std::size_t>(j)] < 0) {
          starts.push_back(i);
          break;
        }
    }
    std::vector<std::array<std::int32_t, 2>> pairs;
    for (const auto& track : state)
      for (const std::int32_t j : problem.successors(track.back()))
        if (first[static_cast<std::size_t>(j)]) pairs.push_back({track.back(), j});
    INFO("round " << round);
    REQUIRE(sampler.birthStarts() == starts);
    auto drawn = sampler.mergePairs();
    std::sort(drawn.begin(), drawn.end());
    std::sort(pairs.begin(), pairs.end());
    REQUIRE(drawn == pairs);
    if (!pairs.empty()) ++checked_with_pairs;
  }
  CHECK(checked_with_pairs > 30);  // the merge sets were not all empty
  const auto& stats = sampler.stats();
  for (int move = 0; move < kMoveCount; ++move) {
    INFO(moveName(static_cast<Move>(move)));
    CHECK(stats.proposed[static_cast<std::size_t>(move)] > 50);
  }
  for (const Move move : {Move::kBirth, Move::kDeath, Move::kMerge, Move::kExtension, Move::kUpdate})
    CHECK(stats.accepted[static_cast<std::size_t>(move)] > 0);
}

TEST_CASE("mcmcda sampler's chain is the same whether it keeps its proposal sets or rescans", "[mcmcda]") {
  const Problem problem = busyProblem();
  const auto chain = [&](ProposalSets sets) {
    Sampler sampler(problem, sets);
    common::Stream rng(11, common::Purpose::kTracker, 0, 0);
    std::vector<Partition> states;
    for (int round = 0; round < 30; ++round) {
      sampler.run(200, rng);
      states.push_back(sampler.state());
    }
    return std::pair(states, sampler.stats().accepted);
  };
  const auto kept = chain(ProposalSets::kKept);
  const auto rescanned = chain(ProposalSets::kRescan);
  CHECK(kept.first == rescanned.first);
  CHECK(kept.second == rescanned.second);
  CHECK(kept.first.back().size() >= 4);
}

namespace {

/// Round numbers for the hand-computed scores: pd 0.8, pz 0.1, lambda_b 0.01, lambda_f 0.02,
/// r = 0.5, no process noise, velocity prior sigma 1, d-bar 3.
ModelParams handParams() {
  ModelParams p;
  p.detection_probability = 0.8;
  p.termination_probability = 0.1;
  p.birth_density = 0.01;
  p.false_alarm_density = 0.02;
  p.measurement_sigma = 0.5;
  p.process_noise_sigma = 0.0;
  p.initial_velocity_sigma = 1.0;
  p.max_gap = 3;
  return p;
}

}  // namespace

TEST_CASE("mcmcda track score matches eq. 3 by hand for a two-observation track", "[mcmcda]") {
  const ModelParams p = handParams();
  const Problem problem(p, {{1, 0.0, 0.0, false, {}}, {2, 1.0, 0.0, false, {}}}, 3);
  // Prior at y1: position variance r^2 = 0.25, velocity variance 1. One tick later the predicted
  // position variance is 0.25 + 1 = 1.25, so S = 1.25 + 0.25 = 1.5 per axis, nu = (1, 0).
  const double log_likelihood = -std::log(2.0 * std::numbers::pi * 1.5) - 0.5 * 1.0 / 1.5;
  // Birth at the run's first tick (no earlier tick to have been born unseen at), one
  // continuation, two detections, no miss; then the silence of the one tick to T = 3: the target
  // ended (pz 0.1) or lived on unseen ((1 - pz)(1 - pd) = 0.18), 0.28 in all.
  const double prior = std::log(0.01) + std::log(0.9) + 2.0 * std::log(0.8) + std::log(0.28);
  // Minus what the two observations would be left out of every track: a false alarm (0.02) or a
  // target seen once. The one of tick 1: born then, detected, silent for two ticks (silence 0.1
  // + 0.018 + 0.0324 = 0.1504): 0.01 x 0.8 x 0.1504. The one of tick 2: born at tick 2, or at
  // tick 1 and unseen (weight 1 + 0.18), detected, silent one tick: 0.01 x 1.18 x 0.8 x 0.28.
  const double unassigned = std::log(0.02 + 0.01 * 0.8 * 0.1504) + std::log(0.02 + 0.01 * 1.18 * 0.8 * 0.28);
  CHECK(problem.unassignedLogDensity(0) == Approx(std::log(0.0212032)).epsilon(1e-12));
  CHECK(problem.unassignedLogDensity(1) == Approx(std::log(0.0226432)).epsilon(1e-12));
  const std::vector<std::int32_t> track = {0, 1};
  CHECK(problem.trackScore(track) == Approx(prior - unassigned + log_likelihood).epsilon(1e-12));
}

TEST_CASE("mcmcda birth weight counts the ticks a target may have gone unseen before its first report", "[mcmcda]") {
  const ModelParams p = handParams();
  // r = (1 - pz)(1 - pd) = 0.18: born at the tick itself, or one tick before and unseen, ...
  CHECK(unseenBirthWeight(p, 1) == Approx(1.0).epsilon(1e-12));
  CHECK(unseenBirthWeight(p, 3) == Approx(1.0 + 0.18 + 0.0324).epsilon(1e-12));
  // Long after the run's start: 1 / (1 - r).
  CHECK(unseenBirthWeight(p, 10'000) == Approx(1.0 / 0.82).epsilon(1e-12));
  // The same track two ticks later in the run: its birth weighs 1.2124 against 1, and so does each
  // of its observations' chance of being a target seen once.
  const Problem early(p, {{1, 0.0, 0.0, false, {}}, {2, 1.0, 0.0, false, {}}}, 3);
  const Problem late(p, {{3, 0.0, 0.0, false, {}}, {4, 1.0, 0.0, false, {}}}, 5);
  const std::vector<std::int32_t> track = {0, 1};
  const double unassigned_early =
      std::log(0.02 + 0.01 * 1.0 * 0.8 * 0.1504) + std::log(0.02 + 0.01 * 1.18 * 0.8 * 0.28);
  const double unassigned_late =
      std::log(0.02 + 0.01 * 1.2124 * 0.8 * 0.1504) + std::log(0.02 + 0.01 * 1.218232 * 0.8 * 0.28);
  CHECK(late.trackScore(track) - early.trackScore(track) ==
        Approx(std::log(1.2124) - unassigned_late + unassigned_early).epsilon(1e-12));
}

TEST_CASE("mcmcda keeps two lone reports of a heavy-loss field apart that it joined against two false alarms",
          "[mcmcda]") {
  // The derived model of oh_paper_density at pte = 0.8 (pd 0.025, about 40 ticks between a
  // target's reports) and two reports of different targets 25 units and 8 ticks apart, 3.2 units a
  // tick: a link, and the nearer of the two in seed 10's window at tick 25.
  ModelParams p;
  p.detection_probability = 0.02537;
  p.termination_probability = 0.02874;
  p.birth_density = 2e-5;
  p.false_alarm_density = 1.586e-7;
  p.measurement_sigma = 0.0826;
  p.initial_velocity_sigma = 1.427;
  p.max_speed = 5.95;
  p.max_gap = 10;
  const Problem problem(p, {{17, 49.44, 71.87, false, {}}, {25, 45.46, 46.77, false, {}}}, 25);
  const std::vector<std::int32_t> join = {0, 1};
  const double score = problem.trackScore(join);
  // Against two false alarms, which is all a report left out of every track was, the join wins...
  const double against_false_alarms =
      score + problem.unassignedLogDensity(0) + problem.unassignedLogDensity(1) - 2.0 * std::log(p.false_alarm_density);
  CHECK(against_false_alarms > 0.0);
  // ...but each report is far likelier the only report of a target than a false alarm (a birth
  // at tick 17 or before, weighted by the unseen ticks, against lambda_f), and against two such
  // targets the join loses.
  CHECK(problem.unassignedLogDensity(0) > std::log(p.false_alarm_density) + 2.0);
  CHECK(score < 0.0);
}

TEST_CASE("mcmcda track score of an anchored track matches eq. 3 by hand", "[mcmcda]") {
  const ModelParams p = handParams();
  ProblemObservation anchor{0, 0.0, 0.0, true, {}};
  anchor.prior = TrackState{0, 0.0, 0.0, 1.0, 0.0, {0.25, 0.0, 0.01}};
  // The anchor at tick 0, a miss at tick 1, an observation at tick 2; the window ends at T = 4.
  const Problem problem(p, {anchor, {2, 2.5, 0.0, false, {}}}, 4);
  // Two ticks ahead: P_pp = 0.25 + 4 * 0.01 = 0.29, S = 0.29 + 0.25 = 0.54; nu = 2.5 - 2 = 0.5.
  const double S = 0.54;
  const double log_likelihood = -std::log(2.0 * std::numbers::pi * S) - 0.5 * 0.25 / S;
  // Continued two ticks, one detection, one miss, no birth; then the silence of the two ticks to
  // T: with q = (1 - pz)(1 - pd) = 0.18, silence(k) = pz (1 + q + .. + q^(k-1)) + q^k, so
  // silence(2) = 0.1 + 0.018 + 0.0324 = 0.1504. Left alone the anchor would have had the silence
  // of its four ticks, 0.1 (1 + 0.18 + 0.0324 + 0.005832) + 0.00104976 = 0.12287296, which this
  // replaces. The observation is no longer left out of every track: a false alarm, or a target
  // born at tick 2 or before (1.18), detected, silent two ticks.
  const double silence2 = 0.1504;
  const double silence4 = 0.12287296;
  const double unassigned = std::log(0.02 + 0.01 * 1.18 * 0.8 * silence2);
  const double prior =
      2.0 * std::log(0.9) + std::log(0.8) + std::log(0.2) + std::log(silence2) - std::log(silence4) - unassigned;
  const std::vector<std::int32_t> track = {0, 1};
  CHECK(problem.trackScore(track) == Approx(prior + log_likelihood).epsilon(1e-12));
  CHECK(problem.unassignedLogDensity(0) == 0.0);  // an anchor is never a report left out
  // Reaching T = 2: no silence after the track, the anchor's own is silence(2), and the
  // observation at T seen once has no silence to weigh.
  const Problem reaching(p, {anchor, {2, 2.5, 0.0, false, {}}}, 2);
  const double reaching_prior =
      2.0 * std::log(0.9) + std::log(0.8) + std::log(0.2) - std::log(silence2) - std::log(0.02 + 0.01 * 1.18 * 0.8);
  CHECK(reaching.trackScore(track) == Approx(reaching_prior + log_likelihood).epsilon(1e-12));
}

TEST_CASE("mcmcda silence after a track follows the sensors coverage along its predicted path", "[mcmcda]") {
  ModelParams p = handParams();
  p.detection_probability = 0.2;
  // One sensor of PD 1 covering the disc of radius 1 at (3, 0) in a 10 x 10 region: its share at a
  // point inside is 1 / mean, the region mean being pi / 100.
  common::SensorCoverage sensor;
  sensor.sensor = 1;
  sensor.position = {3.0, 0.0};
  sensor.fov = 2.0 * std::numbers::pi;
  sensor.range = 1.0;
  sensor.detection_probability = 1.0;
  const common::DetectionShare share({sensor}, nullptr, std::numbers::pi / 100.0);
  const Problem problem(p, {{0, 0.0, 0.0, false, {}}}, 4, &share);
  // A target last seen at (0, 0) at tick 0, moving at +1 per tick: at tick 1 it is outside the
  // disc (pd 0 there), from tick 2 on inside it (pd min(1, 0.2 x 100 / pi) = 1). Silent
  // through tick 4: it ended at tick 1 (pz), or at tick 2 after an unseen tick 1 (0.9 pz); it could
  // not have been there at tick 2 unseen. 0.1 + 0.9 x 0.1 = 0.19.
  const TrackState moving{0, 0.0, 0.0, 1.0, 0.0, {}};
  CHECK(problem.silence(0, moving) == Approx(0.19).epsilon(1e-12));
  // At rest at the origin the sensor never sees it: pd 0 every tick, and the silence is certain.
  const TrackState resting{0, 0.0, 0.0, 0.0, 0.0, {}};
  CHECK(problem.silence(0, resting) == Approx(1.0).epsilon(1e-12));
  // Without coverage: the model's pd everywhere, q = 0.9 x 0.8 = 0.72.
  const Problem uniform(p, {{0, 0.0, 0.0, false, {}}}, 4);
  const double q = 0.72;
  CHECK(uniform.silence(0, moving) == Approx(0.1 * (1 + q + q * q + q * q * q) + q * q * q * q).epsilon(1e-12));
}

TEST_CASE("mcmcda problem and sampler reject bad input with what is wrong", "[mcmcda]") {
  const ModelParams p = handParams();
  CHECK_THROWS_WITH(Problem(p, {{2, 0.0, 0.0, false, {}}, {1, 0.0, 0.0, false, {}}}, 2),
                    Catch::Contains("sorted by tick"));
  // An observation after T would have a silence of negative length.
  CHECK_THROWS_WITH(Problem(p, {{1, 0.0, 0.0, false, {}}, {3, 0.0, 0.0, false, {}}}, 2),
                    Catch::Contains("after the last tick"));
  ModelParams bad = p;
  bad.detection_probability = 1.0;
  CHECK_THROWS_WITH(Problem(bad, {}, 1), Catch::Contains("detection probability"));
  bad = p;
  bad.max_gap = 0;
  CHECK_THROWS_WITH(Problem(bad, {}, 1), Catch::Contains("max gap"));

  const Problem problem(p, {{1, 0.0, 0.0, false, {}}, {2, 1.0, 0.0, false, {}}, {2, 9.0, 9.0, false, {}}}, 2);
  Sampler sampler(problem);
  CHECK_THROWS_WITH(sampler.setState({{0, 2}}), Catch::Contains("not a candidate successor"));
  CHECK_THROWS_WITH(sampler.setState({{0}}), Catch::Contains("fewer than two"));
  CHECK(sampler.trackCount() == 0);  // a refused state leaves the chain as it was
  sampler.setState({{0, 1}});
  CHECK(sampler.trackCount() == 1);
}

}  // namespace wsn::supernode::mcmcda

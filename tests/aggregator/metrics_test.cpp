#include "aggregator/metrics.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "tests/aggregator/test_support.hpp"

using wsn::aggregator::MetricsAccumulator;
using wsn::aggregator::MetricsSummary;
using wsn::aggregator::ospaDistance;
using wsn::common::MetricsConfig;
using wsn::common::TargetState;
using wsn::common::TrackEstimate;
using wsn::common::Vec2;

using wsn::aggregator::test::target;
using wsn::aggregator::test::track;

namespace {

MetricsConfig config(double c = 5.0, double p = 2.0) {
  MetricsConfig m;
  m.ospa_c = c;
  m.ospa_p = p;
  return m;
}

}  // namespace

TEST_CASE("ospaDistance matches hand-computed values", "[aggregator][metrics][ospa]") {
  // One pair 5 apart (3-4-5), c = 10, p = 2: (5^2 / 1)^(1/2) = 5.
  CHECK(ospaDistance({{0, 0}}, {{3, 4}}, 10.0, 2.0) == Approx(5.0).margin(1e-12));
  // m = 1, n = 2, c = 5: the pair costs 1^p, the extra point c^p.
  //   p = 2: ((1 + 25) / 2)^(1/2) = sqrt(13) = 3.605551
  //   p = 1: (1 + 5) / 2 = 3
  CHECK(ospaDistance({{0, 0}, {10, 0}}, {{0, 1}}, 5.0, 2.0) == Approx(std::sqrt(13.0)).margin(1e-12));
  CHECK(ospaDistance({{0, 0}, {10, 0}}, {{0, 1}}, 5.0, 1.0) == Approx(3.0).margin(1e-12));
  // Symmetric in its arguments.
  CHECK(ospaDistance({{0, 1}}, {{0, 0}, {10, 0}}, 5.0, 2.0) == Approx(std::sqrt(13.0)).margin(1e-12));
  // The optimal assignment, not the listed order: (0,0)-(0.1,0) and (2,0)-(2.1,0), each 0.1:
  // ((0.01 + 0.01) / 2)^(1/2) = 0.1 (the listed order would give 2.1 and 1.9).
  CHECK(ospaDistance({{0, 0}, {2, 0}}, {{2.1, 0}, {0.1, 0}}, 5.0, 2.0) == Approx(0.1).margin(1e-12));
}

TEST_CASE("ospaDistance handles empty sets", "[aggregator][metrics][ospa]") {
  CHECK(ospaDistance({}, {}, 5.0, 2.0) == 0.0);
  // One set empty: ((n c^p) / n)^(1/p) = c, whatever n and p.
  CHECK(ospaDistance({{1, 2}, {3, 4}, {5, 6}}, {}, 5.0, 2.0) == Approx(5.0).margin(1e-12));
  CHECK(ospaDistance({}, {{1, 2}}, 7.5, 1.0) == Approx(7.5).margin(1e-12));
  CHECK(ospaDistance({}, {{1, 2}}, 7.5, 3.0) == Approx(7.5).margin(1e-12));
}

TEST_CASE("ospaDistance saturates at the cut-off c", "[aggregator][metrics][ospa]") {
  // The pair is 5 apart but c = 2 caps it: (2^2 / 1)^(1/2) = 2.
  CHECK(ospaDistance({{0, 0}}, {{3, 4}}, 2.0, 2.0) == Approx(2.0).margin(1e-12));
  // However far the estimates are, OSPA never exceeds c.
  CHECK(ospaDistance({{0, 0}, {1, 1}}, {{500, 0}, {0, 900}, {30, 30}}, 4.0, 2.0) == Approx(4.0).margin(1e-12));
  // Partial saturation: pairs at 1 and 10 with c = 5, p = 2: ((1 + 25) / 2)^(1/2) = sqrt(13).
  CHECK(ospaDistance({{0, 0}, {0, 20}}, {{1, 0}, {10, 20}}, 5.0, 2.0) == Approx(std::sqrt(13.0)).margin(1e-12));
}

TEST_CASE("ospaDistance follows the order p", "[aggregator][metrics][ospa]") {
  // Two pairs at distances 3 and 4 (c = 10): ((3^p + 4^p) / 2)^(1/p)
  //   p = 1: 3.5;  p = 2: sqrt(12.5) = 3.535534;  p = 3: 45.5^(1/3) = 3.569...
  const std::vector<Vec2> x{{0, 0}, {0, 10}};
  const std::vector<Vec2> y{{3, 0}, {0, 14}};
  CHECK(ospaDistance(x, y, 10.0, 1.0) == Approx(3.5).margin(1e-12));
  CHECK(ospaDistance(x, y, 10.0, 2.0) == Approx(std::sqrt(12.5)).margin(1e-12));
  CHECK(ospaDistance(x, y, 10.0, 3.0) == Approx(std::cbrt(45.5)).margin(1e-12));
}

TEST_CASE("eps_K is Oh eq. 9: total count error over total true count", "[aggregator][metrics][eps_k]") {
  MetricsAccumulator metrics(config());
  // K*_t = 2, 2, 1 and K_t = 1, 3, 0:
  //   sum |K_t - K*_t| = 1 + 1 + 1 = 3, sum K*_t = 5 -> eps_K = 3 / 5 = 0.6.
  // (A mean of per-tick ratios would give (1/2 + 1/2 + 1) / 3 = 0.667: not the paper's.)
  metrics.add(1, {target(1, 0, 0), target(2, 50, 50)}, {track(10, 0, 0)});
  metrics.add(2, {target(1, 1, 0), target(2, 51, 50)}, {track(10, 1, 0), track(11, 51, 50), track(12, 80, 80)});
  metrics.add(3, {target(1, 2, 0)}, {});
  const MetricsSummary s = metrics.finish();
  CHECK(s.ticks_scored == 3);
  CHECK(s.sum_k_true == 5);
  CHECK(s.sum_k == 4);
  CHECK(s.sum_abs_k_error == 3);
  CHECK(s.eps_k_defined);
  CHECK(s.eps_k == Approx(0.6).margin(1e-12));
  CHECK(s.mean_k_true == Approx(5.0 / 3.0).margin(1e-12));
  CHECK(s.mean_k == Approx(4.0 / 3.0).margin(1e-12));
  // Distinct global ids: 10, 11, 12.
  CHECK(s.track_ids == 3);
}

TEST_CASE("add returns the tick's K, K* and OSPA and the running eps_K and OSPA mean", "[aggregator][metrics][eps_k]") {
  // The ticks of the eq. 9 case above, c = 5, p = 2.
  //   tick 1: K* = 2, K = 1: target 2 unmatched -> OSPA = sqrt((0 + 25) / 2) = 3.535534;
  //           running eps_K = 1 / 2, mean OSPA = 3.535534.
  //   tick 2: K* = 2, K = 3: track 12 extra -> OSPA = sqrt(25 / 3) = 2.886751;
  //           running eps_K = 2 / 4 = 0.5, mean OSPA = (3.535534 + 2.886751) / 2.
  //   tick 3: K* = 1, K = 0 -> OSPA = c = 5; running eps_K = 3 / 5 = 0.6, the final value.
  MetricsAccumulator metrics(config());
  const auto t1 = metrics.add(1, {target(1, 0, 0), target(2, 50, 50)}, {track(10, 0, 0)});
  CHECK(t1.k_true == 2);
  CHECK(t1.k == 1);
  CHECK(t1.ospa == Approx(std::sqrt(12.5)).margin(1e-12));
  CHECK(t1.eps_k_running == Approx(0.5).margin(1e-12));
  CHECK(t1.ospa_mean_running == Approx(std::sqrt(12.5)).margin(1e-12));
  const auto t2 =
      metrics.add(2, {target(1, 1, 0), target(2, 51, 50)}, {track(10, 1, 0), track(11, 51, 50), track(12, 80, 80)});
  CHECK(t2.k == 3);
  CHECK(t2.ospa == Approx(std::sqrt(25.0 / 3.0)).margin(1e-12));
  CHECK(t2.eps_k_running == Approx(0.5).margin(1e-12));
  CHECK(t2.ospa_mean_running == Approx((std::sqrt(12.5) + std::sqrt(25.0 / 3.0)) / 2.0).margin(1e-12));
  const auto t3 = metrics.add(3, {target(1, 2, 0)}, {});
  CHECK(t3.ospa == Approx(5.0).margin(1e-12));
  CHECK(t3.eps_k_running == Approx(metrics.finish().eps_k).margin(1e-12));
  CHECK(t3.ospa_mean_running == Approx(metrics.finish().ospa_mean).margin(1e-12));
}

TEST_CASE("the running eps_K is 0 while no target has existed", "[aggregator][metrics][eps_k]") {
  MetricsAccumulator metrics(config());
  const auto t1 = metrics.add(1, {}, {track(1, 0, 0)});
  CHECK(t1.k_true == 0);
  CHECK(t1.k == 1);
  CHECK(t1.eps_k_running == 0.0);
  CHECK(t1.ospa_mean_running == Approx(5.0).margin(1e-12));
}

TEST_CASE("eps_K without any target is reported as 0 and undefined", "[aggregator][metrics][eps_k]") {
  MetricsAccumulator metrics(config());
  metrics.add(1, {}, {track(1, 0, 0), track(2, 5, 5)});
  metrics.add(2, {}, {});
  const MetricsSummary s = metrics.finish();
  // sum K*_t = 0: eq. 9 divides by zero. Reported: 0, flagged undefined, the 2 false tracks kept.
  CHECK_FALSE(s.eps_k_defined);
  CHECK(s.eps_k == 0.0);
  CHECK(s.sum_abs_k_error == 2);
  CHECK_FALSE(s.eps_x_defined);
  CHECK(s.eps_x == 0.0);
}

TEST_CASE("eps_X is Oh eq. 10: pooled squared error over all matches", "[aggregator][metrics][eps_x]") {
  MetricsAccumulator metrics(config());
  // Tick 1: error (3,4) -> 25; tick 2: error (0,1) -> 1. eps_X^2 = (25 + 1) / 2 = 13,
  // eps_X = sqrt(13) = 3.605551 (a mean of per-tick errors would give (5 + 1) / 2 = 3).
  metrics.add(1, {target(1, 0, 0)}, {track(7, 3, 4)});
  metrics.add(2, {target(1, 0, 0)}, {track(7, 0, 1)});
  const MetricsSummary s = metrics.finish();
  CHECK(s.sum_matches == 2);
  CHECK(s.sum_squared_position_error == Approx(26.0).margin(1e-12));
  CHECK(s.eps_x_defined);
  CHECK(s.eps_x == Approx(std::sqrt(13.0)).margin(1e-12));
}

TEST_CASE("eps_X forms exactly M_t = min(K_t, K*_t) matches, without a gate", "[aggregator][metrics][eps_x]") {
  SECTION("more targets than tracks") {
    MetricsAccumulator metrics(config());
    // M = min(1, 2) = 1; the track at (1,0) matches target 1 at (0,0) (cost 1 vs 81): eps_X = 1.
    metrics.add(1, {target(1, 0, 0), target(2, 10, 0)}, {track(5, 1, 0)});
    const MetricsSummary s = metrics.finish();
    CHECK(s.sum_matches == 1);
    CHECK(s.eps_x == Approx(1.0).margin(1e-12));
  }
  SECTION("a far-off track still counts") {
    MetricsAccumulator metrics(config());
    // M = 1, no gate: error (100,100) -> sqrt(20000) = 141.421356.
    metrics.add(1, {target(1, 0, 0)}, {track(5, 100, 100)});
    metrics.add(2, {target(1, 0, 0)}, {});  // M = 0 at tick 2: contributes nothing.
    const MetricsSummary s = metrics.finish();
    CHECK(s.sum_matches == 1);
    CHECK(s.eps_x == Approx(std::sqrt(20000.0)).margin(1e-9));
  }
}

TEST_CASE("eps_X gated counts only the matches closer than the gate", "[aggregator][metrics][eps_x]") {
  MetricsConfig m = config();
  m.eps_x_gate = 3.0;
  MetricsAccumulator metrics(m);
  // Tick 1: error (1,0) -> 1; tick 2: error (0,2) -> 4; tick 3: error (3,4) -> 25, |5| >= 3 left
  // out of the gated sums. eps_X = sqrt((1 + 4 + 25) / 3) = sqrt(10) = 3.162278;
  // eps_X gated = sqrt((1 + 4) / 2) = sqrt(2.5) = 1.581139.
  metrics.add(1, {target(1, 0, 0)}, {track(7, 1, 0)});
  metrics.add(2, {target(1, 0, 0)}, {track(7, 0, 2)});
  metrics.add(3, {target(1, 0, 0)}, {track(7, 3, 4)});
  const MetricsSummary s = metrics.finish();
  CHECK(s.sum_matches == 3);
  CHECK(s.eps_x == Approx(std::sqrt(10.0)).margin(1e-12));
  CHECK(s.sum_matches_gated == 2);
  CHECK(s.sum_squared_position_error_gated == Approx(5.0).margin(1e-12));
  CHECK(s.eps_x_gated_defined);
  CHECK(s.eps_x_gated == Approx(std::sqrt(2.5)).margin(1e-12));
  CHECK(s.eps_x_gate == 3.0);

  // A match exactly at the gate is not closer than it: nothing is left, so gated is undefined.
  MetricsAccumulator far(m);
  far.add(1, {target(1, 0, 0)}, {track(7, 3, 0)});
  const MetricsSummary f = far.finish();
  CHECK(f.eps_x == Approx(3.0).margin(1e-12));
  CHECK_FALSE(f.eps_x_gated_defined);
  CHECK(f.eps_x_gated == 0.0);

  m.eps_x_gate = 0.0;
  CHECK_THROWS_AS(MetricsAccumulator(m), std::invalid_argument);
}

TEST_CASE("eps_X matches true and estimated tracks on positions at t-1, t, t+1", "[aggregator][metrics][eps_x]") {
  // Targets 1 and 2 run in parallel along y = 0 and y = 1; track A follows 1, B follows 2, but at
  // tick 2 both estimates stray towards the other target: A at y = 0.6, B at y = 0.4.
  MetricsAccumulator metrics(config(10.0, 2.0));
  metrics.add(1, {target(1, 0, 0), target(2, 0, 1)}, {track(100, 0, 0), track(200, 0, 1)});
  metrics.add(2, {target(1, 1, 0), target(2, 1, 1)}, {track(100, 1, 0.6), track(200, 1, 0.4)});
  metrics.add(3, {target(1, 2, 0), target(2, 2, 1)}, {track(100, 2, 0), track(200, 2, 1)});
  const MetricsSummary s = metrics.finish();
  // Tick 2 alone would swap the pairs: (1-B, 2-A) costs 0.16 + 0.16 = 0.32 < (1-A, 2-B) 0.36 + 0.36.
  // Over t-1, t, t+1 (mean of squared distances):
  //   1-A: (0 + 0.36 + 0) / 3 = 0.12, 2-B: 0.12;  1-B: (1 + 0.16 + 1) / 3 = 0.72, 2-A: 0.72
  // so the pairs follow the identities, and tick 2's errors are 0.36 + 0.36 = 0.72.
  // Ticks 1 and 3 (one neighbour each): 1-A (0 + 0.36) / 2 = 0.18 vs 1-B (1 + 0.16) / 2 = 0.58:
  // identities again, error 0. eps_X^2 = 0.72 / 6 matches = 0.12, eps_X = 0.346410
  // (tick-only matching would have given sqrt(0.32 / 6) = 0.2309).
  CHECK(s.sum_matches == 6);
  CHECK(s.sum_squared_position_error == Approx(0.72).margin(1e-12));
  CHECK(s.eps_x == Approx(std::sqrt(0.12)).margin(1e-12));
}

TEST_CASE("eps_X matching averages over the neighbour ticks where both tracks exist", "[aggregator][metrics][eps_x]") {
  MetricsAccumulator metrics(config(10.0, 2.0));
  // Target 1 sits at (0,0) on ticks 1-2; target 2 is born at tick 2 at (0,2).
  // Track A: (0,0) at tick 1, (0,1) at tick 2. Track B is born at tick 2 at (0,0.9).
  metrics.add(1, {target(1, 0, 0)}, {track(100, 0, 0)});
  metrics.add(2, {target(1, 0, 0), target(2, 0, 2)}, {track(100, 0, 1), track(200, 0, 0.9)});
  const MetricsSummary s = metrics.finish();
  // Tick 1: one pair, error 0 (tick 2 as neighbour changes no choice).
  // Tick 2: tick 1 is the only neighbour and only 1-A exists at both ticks; other pairs use tick 2 alone:
  //   1-A: (0 + 1) / 2 = 0.5;  1-B: 0.81;  2-A: 1;  2-B: 1.21.
  //   (1-A, 2-B) = 0.5 + 1.21 = 1.71 < (1-B, 2-A) = 0.81 + 1 = 1.81 -> identities.
  //   (Tick 2 alone, or a sum instead of the mean, would cost 1-A 1 and swap: 2.21 > 1.81.)
  //   Errors at tick 2: 1 + 1.21 = 2.21.
  // eps_X^2 = (0 + 2.21) / 3 matches.
  CHECK(s.sum_matches == 3);
  CHECK(s.sum_squared_position_error == Approx(2.21).margin(1e-12));
  CHECK(s.eps_x == Approx(std::sqrt(2.21 / 3.0)).margin(1e-12));
}

TEST_CASE("OSPA is scored per tick and averaged", "[aggregator][metrics][ospa]") {
  MetricsAccumulator metrics(config(5.0, 2.0));
  // Tick 1: targets (0,0), (10,0), one track (0,1): sqrt(13) = 3.605551 (see above).
  // Tick 2: nothing at all: 0. Tick 3: a track but no target: c = 5.
  metrics.add(1, {target(1, 0, 0), target(2, 10, 0)}, {track(3, 0, 1)});
  metrics.add(2, {}, {});
  metrics.add(3, {}, {track(3, 4, 4)});
  const MetricsSummary s = metrics.finish();
  REQUIRE(s.ospa_per_tick.size() == 3);
  CHECK(s.ospa_per_tick[0] == Approx(std::sqrt(13.0)).margin(1e-12));
  CHECK(s.ospa_per_tick[1] == 0.0);
  CHECK(s.ospa_per_tick[2] == Approx(5.0).margin(1e-12));
  // Mean: (3.605551 + 0 + 5) / 3 = 2.868517.
  CHECK(s.ospa_mean == Approx((std::sqrt(13.0) + 5.0) / 3.0).margin(1e-12));
  CHECK(s.first_tick == 1);
  CHECK(s.last_tick == 3);
}

TEST_CASE("A perfect tracker scores eps_K = eps_X = OSPA = 0", "[aggregator][metrics][property]") {
  // Random births, deaths and motion; the tracks are the truth states under other ids.
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> position(0.0, 100.0), velocity(-2.0, 2.0), unit(0.0, 1.0);
  std::vector<TargetState> alive;
  int next_id = 0;
  MetricsAccumulator metrics(config());
  std::int64_t total_targets = 0;
  for (int t = 1; t <= 60; ++t) {
    std::erase_if(alive, [&](const TargetState&) { return unit(random) < 0.05; });
    while (unit(random) < 0.3) alive.push_back({next_id++, position(random), position(random), velocity(random), velocity(random)});
    for (auto& s : alive) {
      s.x += s.vx;
      s.y += s.vy;
    }
    std::vector<TrackEstimate> tracks;
    for (const auto& s : alive) tracks.push_back({static_cast<std::uint64_t>(1000 + s.id), s.x, s.y, s.vx, s.vy, {}, 0, {}, {}});
    std::reverse(tracks.begin(), tracks.end());  // order must not matter
    total_targets += static_cast<std::int64_t>(alive.size());
    metrics.add(t, alive, tracks);
  }
  const MetricsSummary s = metrics.finish();
  REQUIRE(total_targets > 0);
  CHECK(s.eps_k_defined);
  CHECK(s.eps_x_defined);
  CHECK(s.eps_k == 0.0);
  CHECK(s.eps_x == 0.0);
  CHECK(s.ospa_mean == 0.0);
  for (double d : s.ospa_per_tick) CHECK(d == 0.0);
  CHECK(s.sum_matches == total_targets);
  CHECK(s.track_ids == next_id);
}

TEST_CASE("MetricsAccumulator does not depend on the order of its inputs", "[aggregator][metrics]") {
  const std::vector<TargetState> truth{target(1, 0, 0), target(2, 5, 5), target(3, 9, 1)};
  const std::vector<TrackEstimate> tracks{track(10, 0.5, 0), track(11, 5, 4), track(12, 20, 20), track(13, 9, 1.5)};
  MetricsAccumulator forward(config()), backward(config());
  for (int t = 1; t <= 3; ++t) {
    forward.add(t, truth, tracks);
    backward.add(t, {truth.rbegin(), truth.rend()}, {tracks.rbegin(), tracks.rend()});
  }
  CHECK(forward.finish() == backward.finish());
}

TEST_CASE("MetricsAccumulator rejects bad settings, repeated ticks and ignores non-finite tracks", "[aggregator][metrics]") {
  CHECK_THROWS_AS(MetricsAccumulator(config(0.0, 2.0)), std::invalid_argument);
  CHECK_THROWS_AS(MetricsAccumulator(config(5.0, 0.5)), std::invalid_argument);
  CHECK_THROWS_AS(MetricsAccumulator(config(NAN, 2.0)), std::invalid_argument);
  MetricsAccumulator metrics(config());
  metrics.add(1, {target(1, 0, 0)}, {track(1, 0, 0), track(2, NAN, 0)});
  CHECK_THROWS_AS(metrics.add(1, {}, {}), std::invalid_argument);
  const MetricsSummary s = metrics.finish();
  // The NaN track is not a track: K_1 = 1 = K*_1.
  CHECK(s.tracks_ignored_nonfinite == 1);
  CHECK(s.sum_abs_k_error == 0);
  CHECK(s.track_ids == 1);
}

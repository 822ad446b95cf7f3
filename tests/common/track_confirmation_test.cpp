// Confirmation and deletion rules derived from clutter and detection statistics, against
// hand-computed values.
#include <catch2/catch.hpp>

#include <cmath>

#include "common/track_confirmation.hpp"

using namespace wsn::common;

TEST_CASE("a chain of false reports multiplies the expected clutter of each gate") {
  // lambda_f = 0.001 over 10^4: 10 false reports start chains per tick; the first gate of area
  // 50 holds 0.05 of a false report, each later one of area 2 holds 0.002.
  CHECK(falseTrackRate(1, 1e-3, 1e4, 50.0, 2.0) == Approx(10.0));
  CHECK(falseTrackRate(2, 1e-3, 1e4, 50.0, 2.0) == Approx(0.5));
  CHECK(falseTrackRate(3, 1e-3, 1e4, 50.0, 2.0) == Approx(1e-3));
  CHECK(falseTrackRate(4, 1e-3, 1e4, 50.0, 2.0) == Approx(2e-6));
}

TEST_CASE("without clutter a single report is decisive") {
  const auto none = [](std::int32_t n) { return falseTrackRate(n, 0.0, 1e4, 50.0, 2.0); };
  const auto wait07 = [](std::int32_t n) { return ticksForReports(n, 0.7); };
  CHECK(leastCostConfirmation(none, 4.0, 0.1, wait07, 1, 50) == 1);
  CHECK(leastCostConfirmation(none, 4.0, 0.1, wait07, 2, 50) == 2);  // an engine whose tracks need two
}

TEST_CASE("the confirmation weighs clutter tracks against the wait of every target") {
  // Births 0.1 per tick at pd 0.5: each extra report asked for costs 0.2 target-ticks per tick.
  // False tracks of the chain above, kept 4 ticks: n = 2 costs 0.5 x 4 + 0.2 = 2.2, n = 3 costs
  // 0.004 + 0.4 = 0.404, n = 4 costs 8e-6 + 0.6: n = 3 is cheapest.
  const auto chain = [](std::int32_t n) { return falseTrackRate(n, 1e-3, 1e4, 50.0, 2.0); };
  const auto wait05 = [](std::int32_t n) { return ticksForReports(n, 0.5); };
  CHECK(leastCostConfirmation(chain, 4.0, 0.1, wait05, 1, 50) == 3);
  // Ten times the births make waiting dearer: n = 2 costs 2 + 2 = 4, n = 3 costs 0.004 + 4.
  CHECK(leastCostConfirmation(chain, 4.0, 1.0, wait05, 1, 50) == 2);
}

TEST_CASE("a run of misses is rare once its probability is below the tolerance") {
  // 0.3^3 = 0.027 > 0.01 >= 0.3^4 = 0.0081.
  CHECK(rareMissRun(0.7, 0.01, 50) == 4);
  // 0.5^6 = 0.0156, 0.5^7 = 0.0078.
  CHECK(rareMissRun(0.5, 0.01, 50) == 7);
  CHECK(rareMissRun(0.5, 0.01, 5) == 5);  // capped
  CHECK(rareMissRun(1.0, 0.01, 50) == 1);
  CHECK(rareMissRun(0.0, 0.01, 50) == 50);
}

TEST_CASE("a run of misses at the live edge counts a late report as not yet arrived, not as missed") {
  // One pd at every lag is rareMissRun: 0.3^4 = 0.0081.
  CHECK(rareLiveEdgeMissRun({0.7}, 0.01, 50) == rareMissRun(0.7, 0.01, 50));
  CHECK(rareLiveEdgeMissRun({0.5, 0.5, 0.5}, 0.01, 50) == 7);
  // Arrived by lag 0, 1, 2: 0.3, 0.6, 0.9. Runs: 0.7, 0.7 x 0.4 = 0.28, 0.28 x 0.1 = 0.028,
  // then 0.028 x 0.1 = 0.0028 <= 0.01 at k = 4. Judged by the in-window pd alone (0.9) it would
  // be k = 2 (0.1^2 = 0.01), which deletes a track whose newest two reports are only late.
  CHECK(rareLiveEdgeMissRun({0.3, 0.6, 0.9}, 0.01, 50) == 4);
  CHECK(rareMissRun(0.9, 0.01, 50) == 2);
  // Judged on time at every lag (0.3) it would be 13: 0.7^12 = 0.0138, 0.7^13 = 0.0097.
  CHECK(rareMissRun(0.3, 0.01, 50) == 13);
  CHECK(rareLiveEdgeMissRun({0.3, 0.6, 0.9}, 0.01, 3) == 3);  // capped
  CHECK(rareLiveEdgeMissRun({}, 0.01, 9) == 9);
  CHECK(rareLiveEdgeMissRun({1.0}, 0.01, 50) == 1);
}

TEST_CASE("the chi-square gate of an isotropic innovation is an ellipse of area pi g s2") {
  CHECK(gateArea(9.21, 0.5) == Approx(M_PI * 4.605));
}

TEST_CASE("a run of consecutive reports takes longer to come than as many reports") {
  // p = 0.5: a run of 2 takes (1 - 0.25) / (0.5 x 0.25) = 6 trials, 5 after the first; 2
  // reports in any order take 1 / 0.5 = 2 ticks after the first.
  CHECK(ticksForConsecutiveReports(2, 0.5) == Approx(5.0));
  CHECK(ticksForReports(2, 0.5) == Approx(2.0));
  // A run of 3: (1 - 0.125) / (0.5 x 0.125) = 14 trials.
  CHECK(ticksForConsecutiveReports(3, 0.5) == Approx(13.0));
  // Certain reports: n - 1 ticks either way.
  CHECK(ticksForConsecutiveReports(3, 1.0) == Approx(2.0));
}

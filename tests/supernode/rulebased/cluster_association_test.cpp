#include "supernode/rulebased/cluster_association.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

namespace wsn::supernode::rulebased {
namespace {

// Clusters of four sensors at Ds = 25 m have r = sqrt(4) 25 / 2 = 25 m (eq. 21); a merged
// cluster of eight has r = sqrt(8) 25 / 2 = 35.36 m. Indices are 0-based: the paper's cluster n
// is index n - 1.
constexpr double kR4 = 25.0;
constexpr double kR8 = 35.355339059327378;

ClusterSummary at(double x, double y, double r = kR4) { return {{x, y}, r}; }

std::vector<bool> bits(std::initializer_list<int> values) {
  std::vector<bool> out;
  for (int v : values) out.push_back(v != 0);
  return out;
}

TEST_CASE("eq. 20 and 22 are the squared centroid distance plus radius difference, and the gap between discs",
          "[rulebased]") {
  // s = 30^2 + 40^2 + (35.36 - 25)^2 = 2500 + 107.3; D = 50 - (25 + 35.36) = -10.36 (overlap).
  CHECK(matchDistance(at(30, 40, kR8), at(0, 0)) == Approx(2500.0 + (kR8 - kR4) * (kR8 - kR4)));
  CHECK(pairDistance(at(30, 40, kR8), at(0, 0)) == Approx(50.0 - kR4 - kR8));
}

TEST_CASE("eq. 22-24 list each cluster's closest later cluster, sorted by gap, ties by the first index",
          "[rulebased]") {
  // The six clusters of Fig. 6 at k - 1. Gaps D: (1,2) 60 - 50 = 10; (2,4) 240 - 50 = 190;
  // (3,6) 300 - 50 = 250 (cluster 4 is 424 away); (4,5) 10; (5,6) 306.6 - 50 = 256.6.
  const std::vector<ClusterSummary> previous = {at(100, 100), at(160, 100), at(100, 400),
                                                at(400, 100), at(460, 100), at(400, 400)};
  const auto pairs = closestPairs(previous);
  REQUIRE(pairs.size() == 5);
  CHECK(pairs[0] == ClosestPair{0, 1, 10.0});  // ties with (4,5): the lower e comes first
  CHECK(pairs[1] == ClosestPair{3, 4, 10.0});
  CHECK((pairs[2].e == 1 && pairs[2].d == 3));
  CHECK(pairs[2].distance == Approx(190.0));
  CHECK((pairs[3].e == 2 && pairs[3].d == 5));
  CHECK(pairs[3].distance == Approx(250.0));
  CHECK((pairs[4].e == 4 && pairs[4].d == 5));
  CHECK(pairs[4].distance == Approx(std::hypot(60.0, 300.0) - 50.0));
}

TEST_CASE("Fig. 5(a)/6: two pairs of clusters merge", "[rulebased]") {
  const std::vector<ClusterSummary> previous = {at(100, 100), at(160, 100), at(100, 400),
                                                at(400, 100), at(460, 100), at(400, 400)};
  // At k: 1' = clusters 1 + 2 (nearer 1), 2' = 3, 3' = clusters 4 + 5 (nearer 5), 4' = 6.
  const std::vector<ClusterSummary> current = {at(125, 100, kR8), at(100, 402), at(435, 100, kR8), at(400, 402)};
  const auto ind = mergeSplitIndicators(previous, current);
  CHECK(ind.nearest == std::vector<int>{0, 2, 4, 5});
  // Fig. 6(a): Mc(1) = Mc(3) = Mc(5) = Mc(6) = 1, Mc(2) = Mc(4) = 0.
  CHECK(ind.match_before == bits({1, 0, 1, 0, 1, 1}));
  // Fig. 6(b): m = 6 - 4 = 2 pairs, (1,2) and (4,5), each with indicators 1 and 0, merge;
  // Mg(1) = Mg(2) = Mg(4) = Mg(5) = 1 and every match indicator is 1 (eq. 25-26).
  CHECK(ind.merge == bits({1, 1, 0, 1, 1, 0}));
  CHECK(ind.match == bits({1, 1, 1, 1, 1, 1}));
  REQUIRE(ind.merged.size() == 2);
  CHECK((ind.merged[0].e == 0 && ind.merged[0].d == 1));
  CHECK((ind.merged[1].e == 3 && ind.merged[1].d == 4));
}

TEST_CASE("Fig. 5(b)/7: one merged pair splits while the other stays merged", "[rulebased]") {
  // At k - 1 the pairs (1,2) (gap 40 - 50 = -10) and (4,5) (gap 45 - 50 = -5) are merged and
  // keep their identities by extrapolation.
  const std::vector<ClusterSummary> previous = {at(100, 100), at(140, 100), at(100, 400),
                                                at(400, 100), at(445, 100), at(400, 400)};
  // At k: 1' -> 2 and 2' -> 1 (the split), 3' -> 3, 4' = 4 + 5 (nearer 5: 15 vs 30 m), 5' -> 6.
  const std::vector<ClusterSummary> current = {at(145, 100), at(95, 100), at(100, 402), at(430, 100, kR8),
                                               at(400, 402)};
  const auto ind = mergeSplitIndicators(previous, current);
  CHECK(ind.nearest == std::vector<int>{1, 0, 2, 4, 5});
  // Fig. 7(a): only cluster 4 has no match.
  CHECK(ind.match_before == bits({1, 1, 1, 0, 1, 1}));
  // Fig. 7(b): m = 1. The closest pair (1,2) has indicators 1 and 1 and is skipped; the next,
  // (4,5), has 0 and 1 and merges.
  CHECK(ind.merge == bits({0, 0, 0, 1, 1, 0}));
  CHECK(ind.match == bits({1, 1, 1, 1, 1, 1}));
  REQUIRE(ind.merged.size() == 1);
  CHECK((ind.merged[0].e == 3 && ind.merged[0].d == 4));
}

TEST_CASE("Fig. 5(c)/8: one merged pair splits while another pair merges", "[rulebased]") {
  // At k - 1: (4,5) merged and closest (gap -10); (1,2) second closest (gap 5).
  const std::vector<ClusterSummary> previous = {at(100, 100), at(155, 100), at(100, 400),
                                                at(400, 100), at(440, 100), at(400, 400)};
  // At k: 1' = 1 + 2 (nearer 1), 2' -> 3, 3' -> 4, 4' -> 5 (the split), 5' -> 6.
  const std::vector<ClusterSummary> current = {at(120, 100, kR8), at(100, 402), at(398, 100), at(442, 100),
                                               at(400, 402)};
  const auto ind = mergeSplitIndicators(previous, current);
  CHECK(ind.nearest == std::vector<int>{0, 2, 3, 4, 5});
  // Fig. 8(a): cluster 2 has no match.
  CHECK(ind.match_before == bits({1, 0, 1, 1, 1, 1}));
  // Fig. 8(b): (4,5) comes first but both match; (1,2) has 1 and 0 and merges.
  CHECK(ind.merge == bits({1, 1, 0, 0, 0, 0}));
  CHECK(ind.match == bits({1, 1, 1, 1, 1, 1}));
}

TEST_CASE("three clusters merging into one take two pairs, the second through an already merged cluster",
          "[rulebased]") {
  // 2014 scenario 2: clusters 1, 2, 3 become one cluster nearest 2. m = 3 - 1 = 2. Pairs:
  // (1,2) gap 10, (2,3) gap 12. (1,2): 0 and 1 -> merge, Mc(1) = 1; (2,3): 1 and 0 -> merge.
  const std::vector<ClusterSummary> previous = {at(100, 100), at(160, 100), at(222, 100)};
  const std::vector<ClusterSummary> current = {at(160, 100, 43.3)};
  const auto ind = mergeSplitIndicators(previous, current);
  CHECK(ind.merge == bits({1, 1, 1}));
  CHECK(ind.merged.size() == 2);
}

TEST_CASE("a pair farther apart than the merge gap never merges", "[rulebased]") {
  // Target 2 vanished 250 m from target 1: one cluster left, m = 1, but the only pair has a gap
  // of 250 - 50 = 200 > 25, so nothing merges and cluster 2 keeps Mc = 0 (it coasts alone).
  const std::vector<ClusterSummary> previous = {at(100, 100), at(350, 100)};
  const std::vector<ClusterSummary> current = {at(102, 100)};
  const auto paper = mergeSplitIndicators(previous, current);
  CHECK(paper.merge == bits({1, 1}));  // the paper's rule alone would merge them
  const auto gated = mergeSplitIndicators(previous, current, 25.0);
  CHECK(gated.merge == bits({0, 0}));
  CHECK(gated.match == bits({1, 0}));
}

TEST_CASE("nothing merges when there are at least as many clusters as before", "[rulebased]") {
  const std::vector<ClusterSummary> previous = {at(100, 100), at(140, 100)};
  const std::vector<ClusterSummary> current = {at(101, 100), at(141, 100), at(600, 600)};
  const auto ind = mergeSplitIndicators(previous, current);
  CHECK(ind.merge == bits({0, 0}));
  CHECK(ind.nearest == std::vector<int>{0, 1, 1});
  CHECK(nearestPrevious(at(0, 0), {}) == -1);
}

}  // namespace
}  // namespace wsn::supernode::rulebased

// Cluster-to-cluster association under merging and splitting (An et al. 2014 §4.2.1): the match
// and merge indicators of eq. (19)-(26) and Rules 1-3, as pure functions over cluster summaries.
#pragma once

#include <limits>
#include <span>
#include <vector>

#include "common/geometry.hpp"

namespace wsn::supernode::rulebased {

/// What the rules know of a cluster (eq. 19): its centroid and averaged radius (eq. 21).
struct ClusterSummary {
  common::Vec2 centroid;
  double radius = 0.0;
};

/// Eq. (20): s = |c_a,k - c_d,k-1|^2 + (r_a,k - r_d,k-1)^2, the match distance of a cluster at
/// k to a cluster at k - 1 (also eq. 27 between a cluster and a track).
double matchDistance(const ClusterSummary& current, const ClusterSummary& previous);

/// Eq. (22): D_e,d = |c_e - c_d| - (r_e + r_d), the gap between two clusters at k - 1 (negative
/// when their discs overlap).
double pairDistance(const ClusterSummary& e, const ClusterSummary& d);

/// Index of the cluster of `previous` nearest to `current` by eq. (20); ties go to the lower
/// index; -1 when `previous` is empty.
int nearestPrevious(const ClusterSummary& current, std::span<const ClusterSummary> previous);

/// One entry of X (eq. 24): cluster e's closest later cluster d' (eq. 23) and D_e,d'.
struct ClosestPair {
  int e = 0;
  int d = 0;
  double distance = 0.0;
  friend bool operator==(const ClosestPair&, const ClosestPair&) = default;
};

/// Eq. (22)-(24): for e = 0 .. M-2 the d' > e minimising D_e,d (ties: lower d), sorted by D
/// ascending (ties: lower e).
std::vector<ClosestPair> closestPairs(std::span<const ClusterSummary> previous);

/// The indicators of Algorithm 4.2.1(b), lines 2-21.
struct MergeSplitIndicators {
  std::vector<int> nearest;           ///< per cluster a at k: d' of eq. (20)
  std::vector<bool> match_before;     ///< Mc per cluster at k - 1 before Rule 1 (Fig. 6a, 7a, 8a)
  std::vector<bool> match;            ///< Mc after Rule 1 (eq. 26; Fig. 6b, 7b, 8b)
  std::vector<bool> merge;            ///< Mg (eq. 25)
  std::vector<ClosestPair> merged;    ///< the pairs Rule 1 merged, in the order found
};

/// Rule 1 on clusters at k - 1 (`previous`) and k (`current`): Mc from eq. (20); then the first
/// m = M_k-1 - M_k pairs of X (eq. 24) whose match indicators are 1 and 0 get Mg = 1 and Mc = 1
/// (eq. 25-26), the indicators being updated as pairs are taken (so three clusters can merge
/// into one through two pairs). Beyond the paper, for three or more clusters merging into one: after
/// X come the pairs X leaves out, by gap (X holds only each cluster's closest later one), and the
/// pairs are scanned again while merges are due and the previous scan found one (a pair skipped
/// with indicators 0 and 0 qualifies once one of its clusters merged). And a pair whose gap D exceeds
/// `max_merge_gap` is never merged (two clusters whose discs are far apart cannot have become
/// one; this keeps a target that vanishes next to another from dragging it into a merge).
/// With m <= 0 nothing merges.
MergeSplitIndicators mergeSplitIndicators(std::span<const ClusterSummary> previous,
                                          std::span<const ClusterSummary> current,
                                          double max_merge_gap = std::numeric_limits<double>::infinity());

}  // namespace wsn::supernode::rulebased

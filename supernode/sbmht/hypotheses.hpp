// Hypothesis management of the sbmht engine (Blackman & Popoli ch. 16, docs/ONERA.md §3): clusters of
// leaves that exclude one another (one tree, or a report two trees took), the k best global hypotheses
// of each cluster and the leaves' posteriors over them, hypothesis pruning, N-scan pruning (with
// algorithm 1's branch per road section) and the merging of duplicate leaves.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "supernode/sbmht/leaf.hpp"

namespace wsn::supernode::sbmht {

/// Sets each leaf's probability P(T) over the k best global hypotheses of its cluster and marks the
/// leaves of each cluster's best hypothesis (Leaf::best). A global hypothesis holds one leaf or none
/// per tree, no report taken twice; its score is the sum of its leaves' scores. Returns the number of
/// clusters whose search hit its node budget (the k best found so far were used).
std::uint64_t weighHypotheses(std::vector<Leaf>& leaves, std::size_t k);

/// Hypothesis pruning: drops the leaves outside the best hypothesis whose P(T) is below 1e-3.
void pruneUnlikelyLeaves(std::vector<Leaf>& leaves);

/// How N-scan pruning decides which branches of a tree stay.
struct NScanRule {
  std::int32_t n_scan = 3;  ///< N: branches must agree with the reference leaf through tick - N
  /// Algorithm 1: also keep the best branch on each other road section, up to road_sections_kept
  /// sections a tree.
  bool roads = false;
  std::int32_t road_sections_kept = 3;
};

/// N-scan pruning at the end of `tick`: each tree of `leaves` (in leafOrder) keeps the branches that
/// took the same reports as its reference leaf (the one in the best hypothesis, else the most
/// probable) through tick - N, and with roads the best branch per other road section.
void pruneNScan(std::vector<Leaf>& leaves, std::int32_t tick, const NScanRule& rule);

/// Of leaves that took reports at each of their last n_scan ticks, and the same ones, keeps the
/// best-scoring one.
void mergeDuplicates(std::vector<Leaf>& leaves, std::int32_t n_scan);

}  // namespace wsn::supernode::sbmht

#include "supernode/rulebased/cluster_association.hpp"

#include <algorithm>

namespace wsn::supernode::rulebased {

double matchDistance(const ClusterSummary& current, const ClusterSummary& previous) {
  const double dr = current.radius - previous.radius;
  return common::squaredDistance(current.centroid, previous.centroid) + dr * dr;
}

double pairDistance(const ClusterSummary& e, const ClusterSummary& d) {
  return common::distance(e.centroid, d.centroid) - (e.radius + d.radius);
}

int nearestPrevious(const ClusterSummary& current, std::span<const ClusterSummary> previous) {
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t d = 0; d < previous.size(); ++d) {
    const double s = matchDistance(current, previous[d]);
    if (best < 0 || s < best_distance) {
      best = static_cast<int>(d);
      best_distance = s;
    }
  }
  return best;
}

std::vector<ClosestPair> closestPairs(std::span<const ClusterSummary> previous) {
  std::vector<ClosestPair> pairs;
  const int n = static_cast<int>(previous.size());
  for (int e = 0; e + 1 < n; ++e) {
    ClosestPair best{e, e + 1, pairDistance(previous[e], previous[e + 1])};
    for (int d = e + 2; d < n; ++d) {
      const double distance = pairDistance(previous[e], previous[d]);
      if (distance < best.distance) best = {e, d, distance};
    }
    pairs.push_back(best);
  }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const ClosestPair& a, const ClosestPair& b) { return a.distance < b.distance; });
  return pairs;
}

MergeSplitIndicators mergeSplitIndicators(std::span<const ClusterSummary> previous,
                                          std::span<const ClusterSummary> current, double max_merge_gap) {
  MergeSplitIndicators out;
  out.match.assign(previous.size(), false);
  out.merge.assign(previous.size(), false);
  for (const auto& cluster : current) {
    const int d = nearestPrevious(cluster, previous);
    out.nearest.push_back(d);
    if (d >= 0) out.match[static_cast<std::size_t>(d)] = true;
  }
  out.match_before = out.match;

  const std::ptrdiff_t merges_due =
      static_cast<std::ptrdiff_t>(previous.size()) - static_cast<std::ptrdiff_t>(current.size());
  std::ptrdiff_t merged = 0;
  // The paper's X (eq. 24) first, then every other pair by gap: X holds only each cluster's closest
  // later cluster, so when three clusters merge into one the pair that joins the third can be
  // missing from it.
  auto pairs = closestPairs(previous);
  std::vector<ClosestPair> others;
  for (int e = 0; e < static_cast<int>(previous.size()); ++e)
    for (int d = e + 1; d < static_cast<int>(previous.size()); ++d)
      if (std::none_of(pairs.begin(), pairs.end(), [&](const ClosestPair& p) { return p.e == e && p.d == d; }))
        others.push_back({e, d, pairDistance(previous[static_cast<std::size_t>(e)], previous[static_cast<std::size_t>(d)])});
  std::stable_sort(others.begin(), others.end(),
                   [](const ClosestPair& a, const ClosestPair& b) { return a.distance < b.distance; });
  pairs.insert(pairs.end(), others.begin(), others.end());
  std::vector<bool> taken(pairs.size(), false);
  // One scan of X is the paper's loop (lines 14-21). When three or more clusters merge into one, the
  // pair of the two that the merged cluster did not choose (indicators 0 and 0) can come first and
  // be skipped; it qualifies once one of its clusters merged, so the pairs are scanned again while
  // merges are still due and the last scan found one. Where one scan of X suffices (Fig. 6-8) the
  // result is the paper's.
  for (bool progress = true; progress && merged < merges_due;) {
    progress = false;
    for (std::size_t n = 0; n < pairs.size() && merged < merges_due; ++n) {
      const auto& pair = pairs[n];
      if (taken[n] || pair.distance > max_merge_gap) continue;
      const auto e = static_cast<std::size_t>(pair.e);
      const auto d = static_cast<std::size_t>(pair.d);
      if (out.match[e] == out.match[d]) continue;  // Rule 1: match indicators 1 and 0
      out.merge[e] = out.merge[d] = true;           // eq. (25)
      out.match[e] = out.match[d] = true;           // eq. (26)
      out.merged.push_back(pair);
      taken[n] = true;
      ++merged;
      progress = true;
    }
  }
  return out;
}

}  // namespace wsn::supernode::rulebased

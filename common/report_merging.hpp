// Same-tick merging of reports that lie close together: for sensor models that report every
// detecting sensor (Oh et al. §VIII's magnetometers: "we did not aggregate sensor readings as in
// Eqn. (6)"), so that an engine assuming at most one report per target and tick (MCMCDA, GNN) sees
// one per target. Pure and deterministic: the same reports in the same order give the same result.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numeric>
#include <span>
#include <vector>

#include "common/messages.hpp"

namespace wsn::common {

/// Clusters `items` (reports of one tick, each with x, y and power_level) around their strongest
/// members, as Oh eq. (6) elects the local maximum: in order of decreasing power level (ties: the
/// earlier item), an item within `radius` of an item already chosen joins the nearest such one (a
/// tie: the earlier), else it starts a cluster of its own. Unlike single linkage this never chains
/// two targets' reports into one cluster through the reports between them. Returns each item's
/// cluster, numbered in the order of the items that start them.
template <typename Item>
std::vector<std::size_t> strongestFirstClusters(std::span<const Item> items, double radius) {
  std::vector<std::size_t> order(items.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return items[a].power_level > items[b].power_level; });
  // A radius derived as a distance (reachFromStrongest) must join the pair it was measured on:
  // squaring a square root can land one ulp below, so the test allows a relative 1e-9.
  const double r2 = radius * radius * (1.0 + 1e-9);
  std::vector<std::size_t> seeds;  // item index of each cluster's first (strongest) member
  std::vector<std::size_t> cluster(items.size(), 0);
  for (const std::size_t i : order) {
    std::size_t nearest = seeds.size();
    double nearest_d2 = r2;
    for (std::size_t c = 0; c < seeds.size(); ++c) {
      const double dx = items[i].x - items[seeds[c]].x;
      const double dy = items[i].y - items[seeds[c]].y;
      const double d2 = dx * dx + dy * dy;
      if (d2 <= nearest_d2 && (nearest == seeds.size() || d2 < nearest_d2)) {
        nearest = c;
        nearest_d2 = d2;
      }
    }
    if (nearest == seeds.size()) seeds.push_back(i);
    cluster[i] = nearest;
  }
  // Number the clusters in the order of their seeds in `items`.
  std::vector<std::size_t> by_position(seeds.size());
  std::iota(by_position.begin(), by_position.end(), std::size_t{0});
  std::sort(by_position.begin(), by_position.end(), [&](std::size_t a, std::size_t b) { return seeds[a] < seeds[b]; });
  std::vector<std::size_t> number(seeds.size());
  for (std::size_t k = 0; k < by_position.size(); ++k) number[by_position[k]] = k;
  for (auto& c : cluster) c = number[c];
  return cluster;
}

/// One report per cluster of strongestFirstClusters over `items` (reports or observations of one
/// tick in a canonical order): at the centre of mass of its members weighted by power level (at
/// least 1 each), as eq. (6) weighs readings; from its strongest member's sensor, with that power
/// level; labelled with the target most of its members name (a tie: the smaller id; false alarms
/// count as a label of their own). An observation keeps its members' earliest delivery. radius <= 0
/// returns the items unchanged. Only positions are merged: a report of another kind (a bearing, a
/// radar plot) lies at its sensor, not at its target, so it is not a point to average; it follows
/// the merged ones unchanged.
template <typename Item>
std::vector<Item> mergeNearby(std::span<const Item> items, double radius) {
  if (!(radius > 0.0) || items.size() < 2) return {items.begin(), items.end()};
  const auto at_target = [](const Item& item) { return item.measurement.kind() == MeasurementKind::position; };
  if (!std::all_of(items.begin(), items.end(), at_target)) {
    std::vector<Item> positions, others;
    for (const Item& item : items) (at_target(item) ? positions : others).push_back(item);
    std::vector<Item> merged = mergeNearby(std::span<const Item>(positions), radius);
    merged.insert(merged.end(), others.begin(), others.end());
    return merged;
  }
  const std::vector<std::size_t> cluster = strongestFirstClusters(items, radius);
  const std::size_t count = *std::max_element(cluster.begin(), cluster.end()) + 1;
  std::vector<std::vector<std::size_t>> members(count);
  for (std::size_t i = 0; i < items.size(); ++i) members[cluster[i]].push_back(i);
  std::vector<Item> merged;
  merged.reserve(count);
  for (const auto& group : members) {
    std::size_t strongest = group.front();
    for (const std::size_t i : group)
      if (items[i].power_level > items[strongest].power_level) strongest = i;
    Item out = items[strongest];
    if (group.size() > 1) {
      double x = 0.0, y = 0.0, weight = 0.0;
      std::map<TargetId, std::size_t> votes;
      for (const std::size_t i : group) {
        const Item& item = items[i];
        const double w = std::max(1.0, static_cast<double>(item.power_level));
        x += w * item.x;
        y += w * item.y;
        weight += w;
        ++votes[item.target];
        if constexpr (requires { item.tick_delivered; })
          out.tick_delivered = std::min(out.tick_delivered, item.tick_delivered);
      }
      out.x = x / weight;
      out.y = y / weight;
      out.measurement = {};  // a centre of mass: the engine's own noise model applies
      std::size_t best = 0;
      for (const auto& [target, n] : votes)
        if (n > best) {  // map order: a tie keeps the smaller id
          best = n;
          out.target = target;
        }
    }
    merged.push_back(std::move(out));
  }
  return merged;
}

/// The radius that joins `reports` (one target's, of one tick) to their strongest one under
/// strongestFirstClusters: the largest distance from the strongest report (the first of the
/// strongest) to another. 0 for one report.
template <typename Item>
double reachFromStrongest(std::span<const Item> reports) {
  if (reports.empty()) return 0.0;
  std::size_t strongest = 0;
  for (std::size_t i = 1; i < reports.size(); ++i)
    if (reports[i].power_level > reports[strongest].power_level) strongest = i;
  double reach2 = 0.0;
  for (const Item& r : reports) {
    const double dx = r.x - reports[strongest].x;
    const double dy = r.y - reports[strongest].y;
    reach2 = std::max(reach2, dx * dx + dy * dy);
  }
  return std::sqrt(reach2);
}

}  // namespace wsn::common

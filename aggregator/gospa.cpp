#include "aggregator/gospa.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/assignment.hpp"
#include "common/near_pairs.hpp"
#include "common/output.hpp"

namespace wsn::aggregator {

GospaResult gospaDistance(const std::vector<common::Vec2>& truth, const std::vector<common::Vec2>& tracks, double c,
                          double p) {
  if (!(c > 0.0) || !std::isfinite(c))
    throw std::invalid_argument("gospa: c must be finite and > 0, got " + common::fixed6(c));
  if (!(p >= 1.0) || !std::isfinite(p))
    throw std::invalid_argument("gospa: p must be finite and >= 1, got " + common::fixed6(p));

  const std::size_t m = truth.size();
  const std::size_t n = tracks.size();
  // A pair at d >= c costs no less than its two misses (c^p / 2 each), so GOSPA's matching is
  // the partial assignment with c^p per unassigned truth.
  const double cp = std::pow(c, p);
  std::vector<common::AssignmentPair> pairs;
  common::forEachPairWithin(truth, tracks, c, [&](std::uint32_t i, std::uint32_t j) {
    pairs.push_back({i, j, std::pow(common::distance(truth[i], tracks[j]), p)});
  });
  const auto assignment = common::solveSparseAssignmentWithMissCost(m, n, pairs, cp);

  GospaResult r;
  for (std::size_t i = 0; i < m; ++i) {
    if (assignment[i] < 0) continue;
    const double d = common::distance(truth[i], tracks[static_cast<std::size_t>(assignment[i])]);
    if (d < c) {
      ++r.assigned;
      r.localisation += std::pow(d, p);
    }
  }
  r.missed_targets = static_cast<std::int64_t>(m) - r.assigned;
  r.false_tracks = static_cast<std::int64_t>(n) - r.assigned;
  r.missed = cp / 2.0 * static_cast<double>(r.missed_targets);
  r.false_targets = cp / 2.0 * static_cast<double>(r.false_tracks);
  r.distance = std::pow(r.localisation + r.missed + r.false_targets, 1.0 / p);
  return r;
}

GospaMean meanGospa(const std::vector<GospaResult>& per_tick) {
  GospaMean mean;
  mean.ticks = static_cast<std::int64_t>(per_tick.size());
  if (per_tick.empty()) return mean;
  for (const auto& r : per_tick) {
    mean.distance += r.distance;
    mean.localisation += r.localisation;
    mean.missed += r.missed;
    mean.false_targets += r.false_targets;
    mean.missed_targets += static_cast<double>(r.missed_targets);
    mean.false_tracks += static_cast<double>(r.false_tracks);
  }
  const double ticks = static_cast<double>(per_tick.size());
  mean.distance /= ticks;
  mean.localisation /= ticks;
  mean.missed /= ticks;
  mean.false_targets /= ticks;
  mean.missed_targets /= ticks;
  mean.false_tracks /= ticks;
  return mean;
}

}  // namespace wsn::aggregator

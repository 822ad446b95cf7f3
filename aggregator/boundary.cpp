#include "aggregator/boundary.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/near_pairs.hpp"
#include "common/output.hpp"

namespace wsn::aggregator {

BoundaryClassifier::BoundaryClassifier(std::vector<common::Vec2> supernodes, double band)
    : supernodes_(std::move(supernodes)), band_(band) {
  if (!(band_ >= 0.0) || !std::isfinite(band_))
    throw std::invalid_argument("boundary: band must be finite and >= 0, got " + common::fixed6(band_));
  for (std::size_t i = 0; i < supernodes_.size(); ++i)
    for (std::size_t j = i + 1; j < supernodes_.size(); ++j)
      if (supernodes_[i] == supernodes_[j])
        throw std::invalid_argument("boundary: supernodes " + std::to_string(i) + " and " + std::to_string(j) +
                                    " are at the same place");
}

double BoundaryClassifier::bisectorDistance(common::Vec2 p) const {
  if (supernodes_.size() < 2) return std::numeric_limits<double>::infinity();
  // Squared distances pick nearest and second-nearest; strict < keeps the lower index on ties.
  std::size_t a = 0, b = 1;
  double da = common::squaredDistance(p, supernodes_[0]);
  double db = common::squaredDistance(p, supernodes_[1]);
  if (db < da) {
    std::swap(a, b);
    std::swap(da, db);
  }
  for (std::size_t i = 2; i < supernodes_.size(); ++i) {
    const double d = common::squaredDistance(p, supernodes_[i]);
    if (d < da) {
      b = a;
      db = da;
      a = i;
      da = d;
    } else if (d < db) {
      b = i;
      db = d;
    }
  }
  return (db - da) / (2.0 * common::distance(supernodes_[a], supernodes_[b]));
}

BoundaryAccumulator::BoundaryAccumulator(std::vector<common::Vec2> supernodes, double band, double mot_threshold)
    : classifier_(std::move(supernodes), band), threshold_(mot_threshold) {
  if (!(threshold_ > 0.0) || !std::isfinite(threshold_))
    throw std::invalid_argument("boundary: mot_threshold must be finite and > 0, got " + common::fixed6(threshold_));
}

BoundaryCounts& BoundaryAccumulator::side(const common::TargetState& target) {
  return classifier_.atBoundary({target.x, target.y}) ? boundary_ : interior_;
}

void BoundaryAccumulator::add(const std::vector<common::TargetState>& truth, const ClearMotTick& events) {
  std::map<common::TargetId, const common::TargetState*> by_id;
  for (const auto& target : truth) by_id.emplace(target.id, &target);
  const auto targetOf = [&](common::TargetId id) -> const common::TargetState& {
    const auto it = by_id.find(id);
    if (it == by_id.end())
      throw std::invalid_argument("boundary: CLEAR-MOT event for target " + std::to_string(id) + " not in the truth");
    return *it->second;
  };

  for (const auto& target : truth) ++side(target).target_ticks;
  for (const auto id : events.id_switches) ++side(targetOf(id)).id_switches;
  for (const auto id : events.fragmentations) ++side(targetOf(id)).fragmentations;

  // Only matched targets are candidates: an unmatched target within T of an unmatched track
  // cannot occur (the matching is of maximum size), and a far-off false track is no duplicate.
  // The nearest (lower id on a tie) is a minimum, so any order of the candidates finds it; only
  // those within T of the track are looked at (a city-scale tick has ~10^3 of each).
  std::vector<const common::TargetState*> matched;
  std::vector<common::Vec2> matched_at;
  for (const auto& match : events.matches) {
    matched.push_back(&targetOf(match.target));
    matched_at.push_back({matched.back()->x, matched.back()->y});
  }
  std::vector<common::Vec2> false_at;
  for (const auto& track : events.false_positives) false_at.push_back({track.x, track.y});
  std::vector<const common::TargetState*> nearest(false_at.size(), nullptr);
  std::vector<double> nearest_distance(false_at.size(), threshold_);
  common::forEachPairWithin(false_at, matched_at, threshold_, [&](std::uint32_t f, std::uint32_t m) {
    const common::TargetState& target = *matched[m];
    const double d = common::distance(matched_at[m], false_at[f]);
    if (d < nearest_distance[f] || (d == nearest_distance[f] && nearest[f] != nullptr && target.id < nearest[f]->id)) {
      nearest[f] = &target;
      nearest_distance[f] = d;
    }
  });
  for (const common::TargetState* target : nearest)
    if (target != nullptr) ++side(*target).duplicate_track_ticks;
}

BoundarySummary BoundaryAccumulator::summary() const {
  BoundarySummary s;
  s.band = classifier_.band();
  s.supernodes = static_cast<std::int64_t>(classifier_.supernodes());
  s.mot_threshold = threshold_;
  s.boundary = boundary_;
  s.interior = interior_;
  return s;
}

}  // namespace wsn::aggregator

#include "aggregator/clear_mot.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/assignment.hpp"
#include "common/near_pairs.hpp"
#include "common/geometry.hpp"
#include "common/output.hpp"

namespace wsn::aggregator {
namespace {

double positionDistance(const common::TargetState& o, const common::TrackEstimate& h) {
  return common::distance({o.x, o.y}, {h.x, h.y});
}

}  // namespace

ClearMotAccumulator::ClearMotAccumulator(double match_threshold) : threshold_(match_threshold) {
  if (!(threshold_ > 0.0) || !std::isfinite(threshold_))
    throw std::invalid_argument("clear_mot: match_threshold must be finite and > 0, got " +
                                common::fixed6(threshold_));
}

ClearMotTick ClearMotAccumulator::add(std::int32_t tick, const std::vector<common::TargetState>& truth,
                                      const std::vector<common::TrackEstimate>& tracks_in) {
  if (any_tick_ && tick <= last_tick_)
    throw std::invalid_argument("clear_mot: tick " + std::to_string(tick) + " added after tick " +
                                std::to_string(last_tick_));
  any_tick_ = true;
  last_tick_ = tick;

  std::vector<common::TrackEstimate> tracks;
  tracks.reserve(tracks_in.size());
  for (const auto& h : tracks_in) {
    if (std::isfinite(h.x) && std::isfinite(h.y))
      tracks.push_back(h);
    else
      ++sums_.tracks_ignored_nonfinite;
  }

  const std::size_t rows = truth.size();
  const std::size_t cols = tracks.size();
  std::vector<int> match(rows, -1);  // truth index -> track index
  std::vector<char> track_used(cols, 0);

  // Step 1: keep last tick's correspondences that are still valid.
  for (std::size_t i = 0; i < rows; ++i) {
    const auto prev = previous_.find(truth[i].id);
    if (prev == previous_.end()) continue;
    for (std::size_t j = 0; j < cols; ++j) {
      if (track_used[j] || tracks[j].track != prev->second) continue;
      if (positionDistance(truth[i], tracks[j]) < threshold_) {
        match[i] = static_cast<int>(j);
        track_used[j] = 1;
      }
      break;
    }
  }

  // Step 2: optimal assignment of the rest within the threshold.
  std::vector<std::size_t> free_rows;
  std::vector<std::size_t> free_cols;
  for (std::size_t i = 0; i < rows; ++i)
    if (match[i] < 0) free_rows.push_back(i);
  for (std::size_t j = 0; j < cols; ++j)
    if (!track_used[j]) free_cols.push_back(j);
  if (!free_rows.empty() && !free_cols.empty()) {
    std::vector<common::Vec2> row_at, col_at;
    for (const std::size_t i : free_rows) row_at.push_back({truth[i].x, truth[i].y});
    for (const std::size_t j : free_cols) col_at.push_back({tracks[j].x, tracks[j].y});
    std::vector<common::AssignmentPair> pairs;
    common::forEachPairWithin(row_at, col_at, threshold_, [&](std::uint32_t r, std::uint32_t c) {
      const double d = positionDistance(truth[free_rows[r]], tracks[free_cols[c]]);
      if (d < threshold_) pairs.push_back({r, c, d});
    });
    const auto assignment = common::solveSparseAssignment(free_rows.size(), free_cols.size(), pairs);
    for (std::size_t r = 0; r < free_rows.size(); ++r) {
      if (assignment[r] < 0) continue;
      const std::size_t j = free_cols[static_cast<std::size_t>(assignment[r])];
      match[free_rows[r]] = static_cast<int>(j);
      track_used[j] = 1;
    }
  }

  // Steps 3-4: count, and remember this tick's correspondences as M_{t-1} of the next.
  ClearMotTick events;
  std::map<common::TargetId, common::TrackId> current;
  std::int64_t matched = 0;
  for (std::size_t i = 0; i < rows; ++i) {
    const common::TargetId id = truth[i].id;
    TargetHistory& h = history_[id];
    if (match[i] < 0) {
      ++sums_.misses;
      events.misses.push_back(id);
      if (h.has_last_track) h.in_gap = true;
      continue;
    }
    const auto& track = tracks[static_cast<std::size_t>(match[i])];
    const double d = positionDistance(truth[i], track);
    ++matched;
    sums_.sum_distance += d;
    events.matches.push_back({id, track.track, d});
    if (h.has_last_track && h.last_track != track.track) {
      ++sums_.id_switches;
      events.id_switches.push_back(id);
    }
    if (h.in_gap) {
      ++sums_.fragmentations;
      events.fragmentations.push_back(id);
    }
    h.has_last_track = true;
    h.last_track = track.track;
    h.in_gap = false;
    current[truth[i].id] = track.track;
  }
  previous_ = std::move(current);
  for (std::size_t j = 0; j < cols; ++j)
    if (!track_used[j]) events.false_positives.push_back(tracks[j]);

  ++sums_.ticks;
  sums_.ground_truth += static_cast<std::int64_t>(rows);
  sums_.matches += matched;
  sums_.false_positives += static_cast<std::int64_t>(cols) - matched;
  return events;
}

ClearMotSummary ClearMotAccumulator::summary() const {
  ClearMotSummary s = sums_;
  s.mota_defined = s.ground_truth > 0;
  s.mota = s.mota_defined ? 1.0 - static_cast<double>(s.misses + s.false_positives + s.id_switches) /
                                      static_cast<double>(s.ground_truth)
                          : 0.0;
  s.motp_defined = s.matches > 0;
  s.motp = s.motp_defined ? s.sum_distance / static_cast<double>(s.matches) : 0.0;
  return s;
}

}  // namespace wsn::aggregator

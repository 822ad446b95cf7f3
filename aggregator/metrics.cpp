#include "aggregator/metrics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "common/assignment.hpp"
#include "common/near_pairs.hpp"
#include "common/output.hpp"

namespace wsn::aggregator {
namespace {

using common::TargetState;
using common::TrackEstimate;
using common::Vec2;

bool truthLess(const TargetState& a, const TargetState& b) {
  return std::tie(a.id, a.x, a.y, a.vx, a.vy) < std::tie(b.id, b.x, b.y, b.vx, b.vy);
}

bool trackLess(const TrackEstimate& a, const TrackEstimate& b) {
  return std::tie(a.track, a.x, a.y, a.vx, a.vy) < std::tie(b.track, b.x, b.y, b.vx, b.vy);
}

/// Position of target `id` in a tick's sorted truth, if alive.
const TargetState* findTarget(const std::vector<TargetState>& truth, common::TargetId id) {
  const auto it = std::lower_bound(truth.begin(), truth.end(), id,
                                   [](const TargetState& s, common::TargetId key) { return s.id < key; });
  return it != truth.end() && it->id == id ? &*it : nullptr;
}

/// Track `id` in a tick's sorted tracks (the first, should a tracker repeat an id).
const TrackEstimate* findTrack(const std::vector<TrackEstimate>& tracks, common::TrackId id) {
  const auto it = std::lower_bound(tracks.begin(), tracks.end(), id,
                                   [](const TrackEstimate& s, common::TrackId key) { return s.track < key; });
  return it != tracks.end() && it->track == id ? &*it : nullptr;
}

double squaredError(const TargetState& truth, const TrackEstimate& track) {
  const double dx = track.x - truth.x;
  const double dy = track.y - truth.y;
  return dx * dx + dy * dy;
}

}  // namespace

double ospaDistance(const std::vector<Vec2>& x, const std::vector<Vec2>& y, double c, double p) {
  // Schuhmacher, Vo & Vo 2008, eq. (3), with X the smaller set.
  const auto& small = x.size() <= y.size() ? x : y;
  const auto& large = x.size() <= y.size() ? y : x;
  const std::size_t m = small.size();
  const std::size_t n = large.size();
  if (n == 0) return 0.0;
  // Pairs cost min(d, c)^p; a pair at the cut-off costs what leaving both out does, so the
  // matching is the partial assignment with c^p per unassigned element of the smaller set, and
  // only the pairs closer than c take part.
  const double cp = std::pow(c, p);
  const auto pair_cost = [&](std::size_t i, std::size_t j) { return std::pow(std::min(c, common::distance(small[i], large[j])), p); };
  std::vector<common::AssignmentPair> pairs;
  common::forEachPairWithin(small, large, c, [&](std::uint32_t i, std::uint32_t j) { pairs.push_back({i, j, pair_cost(i, j)}); });
  const auto assignment = common::solveSparseAssignmentWithMissCost(m, n, pairs, cp);
  double sum = 0.0;
  for (std::size_t i = 0; i < m; ++i) sum += assignment[i] < 0 ? cp : pair_cost(i, static_cast<std::size_t>(assignment[i]));
  sum += cp * static_cast<double>(n - m);
  return std::pow(sum / static_cast<double>(n), 1.0 / p);
}

MetricsAccumulator::MetricsAccumulator(const common::MetricsConfig& config) : config_(config) {
  if (!(config_.ospa_c > 0.0) || !std::isfinite(config_.ospa_c))
    throw std::invalid_argument("metrics: ospa_c must be finite and > 0, got " + common::fixed6(config_.ospa_c));
  if (!(config_.ospa_p >= 1.0) || !std::isfinite(config_.ospa_p))
    throw std::invalid_argument("metrics: ospa_p must be finite and >= 1, got " + common::fixed6(config_.ospa_p));
  if (!(config_.eps_x_gate > 0.0) || !std::isfinite(config_.eps_x_gate))
    throw std::invalid_argument("metrics: eps_x_gate must be finite and > 0, got " + common::fixed6(config_.eps_x_gate));
}

MetricsTick MetricsAccumulator::add(std::int32_t tick, const std::vector<TargetState>& truth,
                                    const std::vector<TrackEstimate>& tracks) {
  if (ticks_.count(tick) != 0) throw std::invalid_argument("metrics: tick " + std::to_string(tick) + " added twice");
  TickRecord record;
  record.truth = truth;
  std::sort(record.truth.begin(), record.truth.end(), truthLess);
  for (const auto& track : tracks) {
    if (!common::isFinite(track)) {
      ++ignored_nonfinite_;
      continue;
    }
    record.tracks.push_back(track);
    track_ids_.insert(track.track);
  }
  std::sort(record.tracks.begin(), record.tracks.end(), trackLess);

  std::vector<Vec2> truth_positions, track_positions;
  for (const auto& target : record.truth) truth_positions.push_back({target.x, target.y});
  for (const auto& track : record.tracks) track_positions.push_back({track.x, track.y});
  record.ospa = ospaDistance(truth_positions, track_positions, config_.ospa_c, config_.ospa_p);

  MetricsTick out;
  out.k_true = static_cast<std::int64_t>(record.truth.size());
  out.k = static_cast<std::int64_t>(record.tracks.size());
  out.ospa = record.ospa;
  ticks_.emplace(tick, std::move(record));
  running_abs_k_error_ += std::abs(out.k - out.k_true);
  running_k_true_ += out.k_true;
  running_ospa_ += out.ospa;
  if (running_k_true_ > 0)
    out.eps_k_running = static_cast<double>(running_abs_k_error_) / static_cast<double>(running_k_true_);
  out.ospa_mean_running = running_ospa_ / static_cast<double>(ticks_.size());
  return out;
}

MetricsSummary MetricsAccumulator::finish() const {
  MetricsSummary s;
  s.ospa_c = config_.ospa_c;
  s.ospa_p = config_.ospa_p;
  s.track_ids = static_cast<std::int64_t>(track_ids_.size());
  s.tracks_ignored_nonfinite = ignored_nonfinite_;
  s.ticks_scored = static_cast<std::int64_t>(ticks_.size());
  if (ticks_.empty()) return s;
  s.first_tick = ticks_.begin()->first;
  s.last_tick = ticks_.rbegin()->first;

  double ospa_sum = 0.0;
  for (const auto& [t, record] : ticks_) {
    // Oh eq. (9): K_t and K*_t.
    const auto k = static_cast<std::int64_t>(record.tracks.size());
    const auto k_true = static_cast<std::int64_t>(record.truth.size());
    s.sum_k += k;
    s.sum_k_true += k_true;
    s.sum_abs_k_error += std::abs(k - k_true);
    s.ospa_per_tick.push_back(record.ospa);
    ospa_sum += record.ospa;

    // Oh eq. (10): M_t = min(K_t, K*_t) matches on positions at t - 1, t, t + 1.
    const std::size_t rows = record.truth.size();
    const std::size_t cols = record.tracks.size();
    if (rows == 0 || cols == 0) continue;
    const TickRecord* before = nullptr;
    const TickRecord* after = nullptr;
    if (t > std::numeric_limits<std::int32_t>::min()) {
      const auto it = ticks_.find(t - 1);
      if (it != ticks_.end()) before = &it->second;
    }
    if (t < std::numeric_limits<std::int32_t>::max()) {
      const auto it = ticks_.find(t + 1);
      if (it != ticks_.end()) after = &it->second;
    }
    // Each target's and each track's states at t - 1 and t + 1, looked up once rather than per pair.
    const std::array<const TickRecord*, 2> neighbours{before, after};
    std::vector<std::array<const TargetState*, 2>> target_near(rows, {nullptr, nullptr});
    std::vector<std::array<const TrackEstimate*, 2>> track_near(cols, {nullptr, nullptr});
    for (std::size_t side = 0; side < 2; ++side) {
      if (neighbours[side] == nullptr) continue;
      for (std::size_t j = 0; j < rows; ++j) target_near[j][side] = findTarget(neighbours[side]->truth, record.truth[j].id);
      for (std::size_t i = 0; i < cols; ++i) track_near[i][side] = findTrack(neighbours[side]->tracks, record.tracks[i].track);
    }
    std::vector<double> cost(rows * cols);
    for (std::size_t j = 0; j < rows; ++j)
      for (std::size_t i = 0; i < cols; ++i) {
        double sum = squaredError(record.truth[j], record.tracks[i]);
        int used = 1;
        for (std::size_t side = 0; side < 2; ++side) {
          if (target_near[j][side] == nullptr || track_near[i][side] == nullptr) continue;
          sum += squaredError(*target_near[j][side], *track_near[i][side]);
          ++used;
        }
        cost[j * cols + i] = sum / static_cast<double>(used);
      }
    const auto match = common::solveAssignment(cost, rows, cols);
    for (std::size_t j = 0; j < rows; ++j) {
      if (match[j] < 0) continue;
      const double error2 = squaredError(record.truth[j], record.tracks[static_cast<std::size_t>(match[j])]);
      ++s.sum_matches;
      s.sum_squared_position_error += error2;
      if (error2 < config_.eps_x_gate * config_.eps_x_gate) {
        ++s.sum_matches_gated;
        s.sum_squared_position_error_gated += error2;
      }
    }
  }

  const auto ticks = static_cast<double>(s.ticks_scored);
  s.mean_k = static_cast<double>(s.sum_k) / ticks;
  s.mean_k_true = static_cast<double>(s.sum_k_true) / ticks;
  s.ospa_mean = ospa_sum / ticks;
  s.eps_k_defined = s.sum_k_true > 0;
  if (s.eps_k_defined) s.eps_k = static_cast<double>(s.sum_abs_k_error) / static_cast<double>(s.sum_k_true);
  s.eps_x_defined = s.sum_matches > 0;
  if (s.eps_x_defined) s.eps_x = std::sqrt(s.sum_squared_position_error / static_cast<double>(s.sum_matches));
  s.eps_x_gate = config_.eps_x_gate;
  s.eps_x_gated_defined = s.sum_matches_gated > 0;
  if (s.eps_x_gated_defined)
    s.eps_x_gated = std::sqrt(s.sum_squared_position_error_gated / static_cast<double>(s.sum_matches_gated));
  return s;
}

}  // namespace wsn::aggregator

#include "aggregator/track_merger.hpp"

#include <algorithm>
#include <memory>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>

#include "aggregator/track_fusion.hpp"
#include "common/assignment.hpp"

namespace wsn::aggregator {
namespace {

using common::TrackEstimate;
using common::TrackId;

struct Member {
  std::uint32_t supernode = 0;
  TrackEstimate track;
};

/// One target as seen by one or more supernodes; members in canonical (supernode) order.
struct Cluster {
  std::vector<Member> members;
};

bool canonicalLess(const TrackEstimate& a, const TrackEstimate& b) {
  return std::tie(a.track, a.x, a.y, a.vx, a.vy) < std::tie(b.track, b.x, b.y, b.vx, b.vy);
}

double squaredDistance(const TrackEstimate& a, const TrackEstimate& b) {
  const double dx = a.x - b.x;
  const double dy = a.y - b.y;
  return dx * dx + dy * dy;
}

/// Cost of `track` joining `cluster`: kForbidden outside the gate of any member, 0 when a member
/// carries the same id, else the mean squared distance to the members.
double joinCost(const Cluster& cluster, const TrackEstimate& track, double gate_squared) {
  double sum = 0.0;
  bool same_id = false;
  for (const auto& member : cluster.members) {
    const double d2 = squaredDistance(member.track, track);
    if (!(d2 <= gate_squared)) return common::kForbidden;
    sum += d2;
    same_id = same_id || member.track.track == track.track;
  }
  return same_id ? 0.0 : sum / static_cast<double>(cluster.members.size());
}

/// The cluster's global track: its members' estimates fused (aggregator/track_fusion.hpp), in
/// member order, which is canonical.
TrackEstimate fusedState(const Cluster& cluster, TrackId id) {
  std::vector<const TrackEstimate*> members;
  for (const auto& member : cluster.members) members.push_back(&member.track);
  return fuseTrackEstimates(id, members);
}

}  // namespace

const common::config::FieldTable<TrackMergerConfig>& gatedMergeParamTable() {
  using C = TrackMergerConfig;
  static const common::config::FieldTable<C> table{
      "aggregator.params (gated)",
      {
          common::config::real<C>("gate_distance", &C::gate_distance, common::config::closed(0.0, 1e6), "separations",
                                  "tracks of different supernodes at most this far apart are one target"),
          common::config::integer<C>("memory_ticks", &C::memory_ticks, 0, 1e6, "ticks",
                                     "how long a supernode track's global id is remembered after it was last "
                                     "reported"),
      }};
  return table;
}

AssociationSpec gatedMergeSpec() {
  return {"gated", "one-scan gated merge of the supernodes' tracks of each tick (complete linkage, ids by memory)",
          common::paramSpecs(gatedMergeParamTable()),
          [](const AssociationContext& context) -> std::unique_ptr<TrackAssociator> {
            return std::make_unique<TrackMerger>(common::decodeParams(gatedMergeParamTable(), context.params));
          }};
}

TrackMerger::TrackMerger(TrackMergerConfig config) : config_(config) {
  if (!(config_.gate_distance >= 0.0) || !std::isfinite(config_.gate_distance))
    throw std::invalid_argument("TrackMerger: gate_distance must be finite and >= 0, got " +
                                std::to_string(config_.gate_distance));
  if (config_.memory_ticks < 0)
    throw std::invalid_argument("TrackMerger: memory_ticks must be >= 0, got " + std::to_string(config_.memory_ticks));
}

std::vector<TrackEstimate> TrackMerger::merge(std::int32_t tick, const std::vector<SupernodeTracks>& inputs) {
  // 1. Canonical input: by supernode, each supernode's finite tracks in canonical order.
  std::map<std::uint32_t, std::vector<TrackEstimate>> by_supernode;
  for (const auto& input : inputs) {
    auto& tracks = by_supernode[input.supernode];
    for (const auto& track : input.tracks) {
      if (common::isFinite(track))
        tracks.push_back(track);
      else
        ++dropped_non_finite_;
    }
  }
  for (auto& [supernode, tracks] : by_supernode) std::sort(tracks.begin(), tracks.end(), canonicalLess);

  // 2. Sequential gated assignment of each supernode's tracks to the clusters built so far.
  const double gate_squared = config_.gate_distance * config_.gate_distance;
  std::vector<Cluster> clusters;
  for (const auto& [supernode, tracks] : by_supernode) {
    const std::size_t existing = clusters.size();
    std::vector<int> column_of_track(tracks.size(), -1);
    if (existing > 0 && !tracks.empty()) {
      std::vector<double> cost(tracks.size() * existing);
      for (std::size_t i = 0; i < tracks.size(); ++i)
        for (std::size_t c = 0; c < existing; ++c) cost[i * existing + c] = joinCost(clusters[c], tracks[i], gate_squared);
      column_of_track = common::solveAssignment(cost, tracks.size(), existing);
    }
    for (std::size_t i = 0; i < tracks.size(); ++i) {
      if (column_of_track[i] >= 0)
        clusters[static_cast<std::size_t>(column_of_track[i])].members.push_back({supernode, tracks[i]});
      else
        clusters.push_back({{{supernode, tracks[i]}}});
    }
  }

  // 3. Global ids: optimal assignment of clusters to candidate ids (see the header).
  auto remembered = [&](TrackId member) -> const Memory* {
    const auto it = memory_.find(member);
    if (it == memory_.end() || tick - it->second.last_tick > config_.memory_ticks) return nullptr;
    return &it->second;
  };
  std::set<TrackId> candidate_set;
  for (const auto& cluster : clusters)
    for (const auto& member : cluster.members) {
      candidate_set.insert(member.track.track);
      if (const Memory* memory = remembered(member.track.track)) candidate_set.insert(memory->global);
    }
  const std::vector<TrackId> candidates(candidate_set.begin(), candidate_set.end());
  const std::size_t rows = clusters.size();
  const std::size_t cols = candidates.size();
  std::vector<int> benefit(rows * cols, 0);
  int max_benefit = 0;
  for (std::size_t r = 0; r < rows; ++r)
    for (const auto& member : clusters[r].members) {
      const auto own = std::lower_bound(candidates.begin(), candidates.end(), member.track.track) - candidates.begin();
      benefit[r * cols + static_cast<std::size_t>(own)] += 1;
      if (const Memory* memory = remembered(member.track.track)) {
        const auto prev = std::lower_bound(candidates.begin(), candidates.end(), memory->global) - candidates.begin();
        benefit[r * cols + static_cast<std::size_t>(prev)] += 2;
      }
    }
  for (int b : benefit) max_benefit = std::max(max_benefit, b);
  // cost = (max_benefit + 1 - benefit) * W + rank: W exceeds any sum of ranks, so the total
  // benefit decides first and the smaller ids only break ties. Integers: exact in a double.
  const double weight = static_cast<double>(rows * cols + 1);
  std::vector<double> id_cost(rows * cols, common::kForbidden);
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < cols; ++c)
      if (benefit[r * cols + c] > 0)
        id_cost[r * cols + c] = static_cast<double>(max_benefit + 1 - benefit[r * cols + c]) * weight + static_cast<double>(c);
  const auto id_column = common::solveAssignment(id_cost, rows, cols);

  std::vector<TrackId> global_ids(rows, 0);
  for (std::size_t r = 0; r < rows; ++r)
    if (id_column[r] >= 0) global_ids[r] = candidates[static_cast<std::size_t>(id_column[r])];
  for (std::size_t r = 0; r < rows; ++r) {
    if (id_column[r] >= 0) continue;
    // Fresh aggregator id (supernode field 0), skipping any id in use at this tick.
    TrackId fresh = 0;
    do {
      fresh = next_minted_serial_++;
    } while (candidate_set.count(fresh) != 0);
    global_ids[r] = fresh;
  }

  // Remember which global id each supernode track belongs to; with one id in two clusters the
  // first cluster in canonical order is remembered. Forget what is older than memory_ticks.
  std::set<TrackId> written;
  for (std::size_t r = 0; r < rows; ++r)
    for (const auto& member : clusters[r].members)
      if (written.insert(member.track.track).second) memory_[member.track.track] = {global_ids[r], tick};
  std::erase_if(memory_, [&](const auto& entry) { return tick - entry.second.last_tick > config_.memory_ticks; });

  // 4. Merged states, sorted by global id.
  std::vector<TrackEstimate> merged;
  merged.reserve(rows);
  for (std::size_t r = 0; r < rows; ++r) merged.push_back(fusedState(clusters[r], global_ids[r]));
  std::sort(merged.begin(), merged.end(), canonicalLess);
  return merged;
}

}  // namespace wsn::aggregator

// Track-level association across supernodes (Oh et al., §VI): the supernodes' confirmed tracks of
// one tick become one set of global tracks, duplicates of one target merged, ids kept stable.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "aggregator/association.hpp"
#include "common/messages.hpp"

namespace wsn::aggregator {

/// The registration of the gated merge: name "gated", parameters gate_distance and memory_ticks.
AssociationSpec gatedMergeSpec();

/// Settings of the track merger. Lengths are in region units, i.e. sensor separations (Oh §VII
/// normalises the grid separation to 1).
struct TrackMergerConfig {
  /// Two tracks of different supernodes whose positions are at most this far apart are one
  /// target. Default 3 = 2 Rs with the paper's Rs = 1.5: the neighbour election of the fusion
  /// step (Oh eq. 6) already cannot tell apart targets closer than 2 Rs, so merging tracks that
  /// close loses no resolution the network has, while it comfortably covers the disagreement of
  /// two supernodes' estimates of one target (a fused report errs by about 0.7 separations,
  /// Oh Fig. 3, plus filter lag of a track that just changed hands).
  double gate_distance = 3.0;
  /// How long (ticks) the merger remembers which global id a supernode track belonged to after
  /// it was last reported. Default: the sliding window ws = 10 of Oh §VI, the longest a
  /// supernode can still revise a track it no longer reports.
  std::int32_t memory_ticks = 10;
};

/// The "gated" association's parameters, described once (aggregator.params).
const common::config::FieldTable<TrackMergerConfig>& gatedMergeParamTable();

/// Gated merge of the supernodes' tracks into global tracks (Oh §VI, track-level association;
/// a deterministic single-scan simplification instead of rerunning MCMCDA on the tracks).
///
/// Per tick:
///  1. Canonical input: supernodes in ascending id (entries of one id concatenated), each one's
///     tracks sorted by (id, x, y, vx, vy); tracks with a non-finite field are dropped and counted.
///  2. Sequential gated assignment: the first supernode's tracks open one cluster each; each further
///     supernode's tracks are assigned to the clusters built so far by the optimal assignment of
///     common/assignment.hpp. A track may join a cluster only if it lies within `gate_distance` of
///     every member (complete linkage) and the cluster has no member of the same supernode (one
///     supernode never reports one target twice as far as the merger is concerned). Cost: 0 when
///     a member carries the same track id (a handed-over track keeps its id, the strongest
///     evidence of identity), else the mean squared distance to the members. Unassigned tracks
///     open new clusters.
///  3. Global id of each cluster, an optimal assignment of clusters to candidate ids: for a
///     cluster, candidates are the global ids its members belonged to before (remembered for
///     `memory_ticks`) and the members' own ids. Preference, lexicographically: as many clusters
///     as possible keep a candidate id; then most continuation (2 points per member that was in
///     that global track, 1 if a member's own id equals it); then the smallest ids. A cluster left
///     without a candidate (two far-apart tracks reported under one id) gets a fresh id minted by
///     the aggregator, `serial` with the supernode field 0 — a field no supernode uses, since
///     supernode ids start at (0 + 1) << 48.
///  4. Merged state: the members' estimates fused in canonical order (aggregator/track_fusion.hpp:
///     covariance intersection; one member passes through).
///
/// Output sorted by global id. The result is a pure function of the sequence of merge() calls and
/// does not depend on the order of `inputs` or of the tracks within one supernode.
class TrackMerger final : public TrackAssociator {
 public:
  explicit TrackMerger(TrackMergerConfig config = {});

  /// Merges tick `tick`'s tracks of all supernodes into global tracks, sorted by track id.
  std::vector<common::TrackEstimate> merge(std::int32_t tick, const std::vector<SupernodeTracks>& inputs);

  std::vector<common::TrackEstimate> associate(std::int32_t tick, const std::vector<SupernodeTracks>& inputs) override {
    return merge(tick, inputs);
  }
  std::uint64_t droppedNonFinite() const override { return dropped_non_finite_; }
  const TrackMergerConfig& config() const { return config_; }

 private:
  struct Memory {
    common::TrackId global = 0;
    std::int32_t last_tick = 0;
  };

  TrackMergerConfig config_;
  /// Supernode track id -> global id it belonged to when last reported.
  std::map<common::TrackId, Memory> memory_;
  std::uint64_t next_minted_serial_ = 1;
  std::uint64_t dropped_non_finite_ = 0;
};

}  // namespace wsn::aggregator

// What the scenario's faults did to a run (metrics.json "faults"): for each fault its tick and
// what happened; for a supernode that died, the tracks it left, how many the adopters carried on
// under their ids and how many ticks that took; for a restarted supernode, how many of the
// tracks of its group it took back from the others, and when; for a partition, the handoffs it cut; and for
// every fault εK (Oh eq. 9) and mean OSPA over the ticks before, during and after it.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include "aggregator/association.hpp"
#include "aggregator/metric/metric.hpp"
#include "common/faults.hpp"

namespace wsn::aggregator {

/// One tick of the live stream as the fault report needs it.
struct FaultTickScores {
  double truth_targets = 0;  ///< K*_t
  double tracks = 0;         ///< K_t
  double ospa = 0;
};

class FaultReport {
 public:
  /// `window` is the length of the before / during / after windows of a kill (the tracker's
  /// window: the time its memory takes to fill again); a pause, partition or burst uses its own length.
  FaultReport(common::FaultPlan plan, std::int32_t window, std::int32_t ticks);

  /// A process lost outside the scenario (killed by hand), as a kill at the first tick its
  /// outputs were missing; reported after the scenario's faults, marked "unscheduled".
  void addUnscheduled(const common::FaultSpec& fault) { unscheduled_.push_back(fault); }
  /// The tracks a supernode dying at `tick` left behind (their ids), as handed to the adopters.
  void addOrphans(std::uint32_t dead, std::int32_t tick, const std::vector<common::TrackHandoff>& orphans);
  /// Tick t of the live stream: its scores, every supernode's tracks, and the running total of
  /// handoffs partitions cut.
  void addTick(std::int32_t t, const FaultTickScores& scores, const std::vector<SupernodeTracks>& live,
               std::uint64_t handoffs_lost_partition);

  /// The "faults" block: one object per fault of the scenario, in the scenario's order, then the
  /// unscheduled losses.
  Json json() const;

 private:
  struct Orphans {
    std::set<common::TrackId> ids;
    std::set<common::TrackId> carried;  ///< reported again by a live supernode
    std::int32_t first_carried = 0;     ///< tick of the first one; 0: none yet
  };
  /// A supernode back at a restart, and the tracks the others held the tick before.
  struct TakeBack {
    std::set<common::TrackId> held;   ///< by the other supernodes at restart tick - 1
    std::set<common::TrackId> taken;  ///< of those, reported by the restarted supernode since
    std::int32_t first_taken = 0;     ///< tick of the first one; 0: none yet
  };
  Json window(std::int32_t first, std::int32_t last) const;
  Json faultJson(const common::FaultSpec& f) const;

  common::FaultPlan plan_;
  std::vector<common::FaultSpec> unscheduled_;
  std::int32_t window_;
  std::int32_t ticks_;
  std::vector<FaultTickScores> by_tick_;             ///< index t - 1
  std::vector<std::uint64_t> handoffs_lost_by_tick_;  ///< running total at t, index t - 1
  std::map<std::pair<std::uint32_t, std::int32_t>, Orphans> orphans_;  ///< (supernode, death tick)
  std::map<std::pair<std::uint32_t, std::int32_t>, TakeBack> take_backs_;  ///< (supernode, restart tick)
};

}  // namespace wsn::aggregator

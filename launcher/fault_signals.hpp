// Faults of role processes as the launcher handles them: the scenario's kills and pauses enacted
// with real signals (SIGKILL where a role announces its kill, SIGSTOP where it announces its pause
// and SIGCONT once the pipeline has passed the paused ticks; a role announces a fault only once
// the pipeline finished its tick, so no output depends on when a signal lands), and which
// processes the cluster can lose by hand and go on.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/faults.hpp"
#include "common/scenario_config.hpp"

namespace wsn::launcher {

class FaultSignals {
 public:
  FaultSignals(common::FaultPlan plan, std::int32_t run_ticks) : plan_(std::move(plan)), run_ticks_(run_ticks) {}

  /// Role `role` `index` (process `pid`) announced its fault of `tick`. Throws
  /// std::runtime_error when the scenario has no such fault (a role and the launcher disagree).
  void announced(pid_t pid, const std::string& role, std::uint32_t index, std::int32_t tick);
  /// The aggregator finished `tick`: the pauses that ended by then are continued.
  void progressed(std::int32_t tick);
  /// The fault that made the launcher kill `pid`, when it did: that death is the run's design.
  std::optional<std::string> killedByFault(pid_t pid) const;
  /// Whether the launcher holds `pid` stopped for a pause of the scenario.
  bool pausing(pid_t pid) const { return paused_until_.count(pid) != 0; }
  /// Continues every process still stopped (before the cluster is stopped, so that SIGTERM lands).
  void continueAll();

 private:
  common::FaultPlan plan_;
  std::int32_t run_ticks_;
  std::map<pid_t, std::string> killed_;                 ///< pid -> the fault
  std::map<pid_t, std::int32_t> paused_until_;          ///< pid -> the pause's last tick
};

/// The scenario's restarts as the launcher starts them: a new process for a supernode slot once the
/// faults killed its old one and the sources may be within max_ticks_in_flight ticks of the
/// restart's tick. When it starts changes only the wall time: the producers of what it reads wait
/// for its readers (dds::RestartedReaders).
class RestartSchedule {
 public:
  /// `supernode_slots[j]`: the launcher's slot of supernode j.
  RestartSchedule(const common::FaultPlan& plan, const std::vector<std::size_t>& supernode_slots,
                  std::int32_t max_ticks_in_flight);
  /// The scenario's faults killed the process of `slot`.
  void killed(std::size_t slot) { killed_.insert(slot); }
  /// The slots to start again now that the aggregator finished `tick`, each with its first tick;
  /// each restart is returned once.
  std::vector<std::pair<std::size_t, std::int32_t>> due(std::int32_t tick);

 private:
  std::vector<std::pair<std::size_t, std::int32_t>> pending_;  ///< (slot, first tick), by tick
  std::set<std::size_t> killed_;
  std::int32_t in_flight_;
};

/// Which processes the cluster can lose by hand (SIGKILL outside the scenario's faults) and go on:
/// node tiles, and supernodes while another stays live; the network model and the aggregator are
/// the run's own machinery.
class HandLosses {
 public:
  explicit HandLosses(const common::Scenario& scenario);
  /// Whether losing role `role` `index` now leaves a run that can go on; records the loss when so.
  bool survivable(const std::string& role, std::uint32_t index);

 private:
  common::FaultPlan plan_;
  std::int32_t supernodes_;
  std::int32_t last_tick_;
  std::set<std::uint32_t> supernodes_lost_;
};

}  // namespace wsn::launcher

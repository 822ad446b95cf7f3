// Enacting the scenario's kills and pauses on role processes with real signals: SIGKILL where a
// role announces its kill, SIGSTOP where it announces its pause and SIGCONT once the pipeline has
// passed the paused ticks. The roles announce a fault only once everything they wrote before it
// was acknowledged, so no output depends on when a signal lands.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "common/faults.hpp"

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

}  // namespace wsn::launcher

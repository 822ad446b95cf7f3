#include "launcher/fault_signals.hpp"

#include <algorithm>
#include <csignal>
#include <stdexcept>

namespace wsn::launcher {

void FaultSignals::announced(pid_t pid, const std::string& role, std::uint32_t index, std::int32_t tick) {
  const auto kind = role == "node" ? common::FaultRole::kNode : common::FaultRole::kSupernode;
  const auto fault = role == "node" || role == "supernode"
                         ? plan_.processFaultAt(kind, static_cast<std::int32_t>(index), tick)
                         : std::nullopt;
  if (!fault)
    throw std::runtime_error(role + " " + std::to_string(index) + " announced a fault at tick " + std::to_string(tick) +
                             " that the scenario does not have");
  if (fault->action == common::FaultAction::kKill) {
    if (killed_.emplace(pid, fault->describe()).second) ::kill(pid, SIGKILL);
  } else if (paused_until_.emplace(pid, std::min(fault->lastTick(), run_ticks_)).second) {
    ::kill(pid, SIGSTOP);
  }
}

void FaultSignals::progressed(std::int32_t tick) {
  for (auto it = paused_until_.begin(); it != paused_until_.end();) {
    if (tick < it->second) {
      ++it;
      continue;
    }
    ::kill(it->first, SIGCONT);
    it = paused_until_.erase(it);
  }
}

std::optional<std::string> FaultSignals::killedByFault(pid_t pid) const {
  const auto it = killed_.find(pid);
  if (it == killed_.end()) return std::nullopt;
  return it->second;
}

void FaultSignals::continueAll() {
  for (const auto& [pid, until] : paused_until_) ::kill(pid, SIGCONT);
  paused_until_.clear();
}

HandLosses::HandLosses(const common::Scenario& scenario)
    : plan_(scenario.faults, scenario.run.node_processes, static_cast<std::int32_t>(scenario.supernodes.size())),
      supernodes_(static_cast<std::int32_t>(scenario.supernodes.size())),
      last_tick_(scenario.run.ticks) {}

bool HandLosses::survivable(const std::string& role, std::uint32_t index) {
  if (role == "node") return true;
  if (role != "supernode") return false;
  std::size_t left = 0;
  for (std::int32_t j = 0; j < supernodes_; ++j)
    left += static_cast<std::uint32_t>(j) != index && supernodes_lost_.count(static_cast<std::uint32_t>(j)) == 0 &&
                    plan_.supernodeLive(j, last_tick_)
                ? 1
                : 0;
  if (left == 0) return false;
  supernodes_lost_.insert(index);
  return true;
}

}  // namespace wsn::launcher

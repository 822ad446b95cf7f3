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

RestartSchedule::RestartSchedule(const common::FaultPlan& plan, const std::vector<std::size_t>& supernode_slots,
                                 std::int32_t max_ticks_in_flight)
    : in_flight_(max_ticks_in_flight) {
  for (const auto& f : plan.faults())
    if (f.action == common::FaultAction::kRestart && f.index >= 0 &&
        static_cast<std::size_t>(f.index) < supernode_slots.size())
      pending_.emplace_back(supernode_slots[static_cast<std::size_t>(f.index)], f.tick);
  std::sort(pending_.begin(), pending_.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
}

std::vector<std::pair<std::size_t, std::int32_t>> RestartSchedule::due(std::int32_t tick) {
  std::vector<std::pair<std::size_t, std::int32_t>> out;
  for (auto it = pending_.begin(); it != pending_.end();) {
    const auto [slot, first_tick] = *it;
    if (killed_.count(slot) == 0 || tick < first_tick - 1 - in_flight_) {
      ++it;
      continue;
    }
    killed_.erase(slot);
    out.emplace_back(slot, first_tick);
    it = pending_.erase(it);
  }
  return out;
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

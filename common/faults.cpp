#include "common/faults.hpp"

#include <algorithm>
#include <limits>

#include "common/config/field_table.hpp"
#include "common/rng.hpp"

namespace wsn::common {

namespace {

/// A fault of `action` at `tick`, its other keys at their defaults.
FaultSpec faultAt(FaultAction action, std::int32_t tick) {
  FaultSpec f;
  f.tick = tick;
  f.action = action;
  return f;
}

/// A fault of `action` on process `role` `index` at `tick`.
FaultSpec processFault(FaultAction action, FaultRole role, std::int32_t index, std::int32_t tick) {
  FaultSpec f = faultAt(action, tick);
  f.role = role;
  f.index = index;
  return f;
}

}  // namespace

FaultSpec FaultSpec::kill(FaultRole role, std::int32_t index, std::int32_t tick) {
  return processFault(FaultAction::kKill, role, index, tick);
}

FaultSpec FaultSpec::pause(FaultRole role, std::int32_t index, std::int32_t tick, std::int32_t ticks) {
  FaultSpec f = processFault(FaultAction::kPause, role, index, tick);
  f.ticks = ticks;
  return f;
}

FaultSpec FaultSpec::partition(std::int32_t a, std::int32_t b, std::int32_t tick, std::int32_t ticks) {
  FaultSpec f = faultAt(FaultAction::kPartition, tick);
  f.between = {a, b};
  f.ticks = ticks;
  return f;
}

FaultSpec FaultSpec::burstLoss(double pte, std::int32_t tick, std::int32_t ticks) {
  FaultSpec f = faultAt(FaultAction::kBurstLoss, tick);
  f.pte = pte;
  f.ticks = ticks;
  return f;
}

FaultSpec FaultSpec::restart(FaultRole role, std::int32_t index, std::int32_t tick) {
  return processFault(FaultAction::kRestart, role, index, tick);
}

std::int32_t FaultSpec::lastTick() const {
  if (action == FaultAction::kKill) return std::numeric_limits<std::int32_t>::max();
  if (action == FaultAction::kRestart) return tick;
  return tick + std::max(ticks, 1) - 1;
}

const char* faultActionName(FaultAction action) {
  switch (action) {
    case FaultAction::kKill: return "kill";
    case FaultAction::kPause: return "pause";
    case FaultAction::kPartition: return "partition";
    case FaultAction::kBurstLoss: return "burst_loss";
    case FaultAction::kRestart: return "restart";
  }
  return "?";
}

const char* faultRoleName(FaultRole role) { return role == FaultRole::kNode ? "node" : "supernode"; }

std::string FaultSpec::describe() const {
  const std::string at = " at tick " + std::to_string(tick);
  const std::string span = " for " + std::to_string(ticks) + " ticks";
  switch (action) {
    case FaultAction::kKill:
      return std::string("kill of ") + faultRoleName(role) + " " + std::to_string(index) + at +
             (count > 0 ? " (one of " + std::to_string(count) + " drawn by the seed)" : "");
    case FaultAction::kPause:
      return std::string("pause of ") + faultRoleName(role) + " " + std::to_string(index) + at + span;
    case FaultAction::kPartition:
      return "partition between supernodes " + std::to_string(between.size() > 0 ? between[0] : -1) + " and " +
             std::to_string(between.size() > 1 ? between[1] : -1) + at + span;
    case FaultAction::kBurstLoss: return "burst loss (pte " + config::compactNumber(pte) + ")" + at + span;
    case FaultAction::kRestart:
      return std::string("restart of ") + faultRoleName(role) + " " + std::to_string(index) + at;
  }
  return "fault" + at;
}

std::vector<std::int32_t> drawProcesses(std::uint64_t seed, std::size_t item, std::vector<std::int32_t> eligible,
                                        std::int32_t count) {
  Stream stream(seed, Purpose::kFaultDraw, item, 0);
  const auto n = static_cast<std::size_t>(std::clamp<std::int32_t>(count, 0, static_cast<std::int32_t>(eligible.size())));
  // Partial Fisher-Yates: the first n places hold a uniform draw without replacement.
  for (std::size_t k = 0; k < n; ++k)
    std::swap(eligible[k], eligible[k + static_cast<std::size_t>(stream.below(eligible.size() - k))]);
  eligible.resize(n);
  std::sort(eligible.begin(), eligible.end());
  return eligible;
}

FaultPlan::FaultPlan(std::vector<FaultSpec> faults, std::int32_t tiles, std::int32_t supernodes)
    : faults_(std::move(faults)), tiles_(tiles), supernodes_(supernodes) {
  // Once, not on every liveness query: the last tick each kill or pause holds (a kill until its
  // process's next restart).
  for (const auto& f : faults_) {
    const auto back = f.action == FaultAction::kKill ? restartAfter(f.role, f.index, f.tick) : std::nullopt;
    last_tick_.push_back(back ? *back - 1 : f.lastTick());
    has_restarts_ = has_restarts_ || f.action == FaultAction::kRestart;
  }
}

std::optional<std::int32_t> FaultPlan::restartAfter(FaultRole role, std::int32_t index, std::int32_t tick) const {
  std::optional<std::int32_t> first;
  for (const auto& f : faults_)
    if (f.action == FaultAction::kRestart && f.role == role && f.index == index && f.tick > tick)
      first = std::min(first.value_or(f.tick), f.tick);
  return first;
}

bool FaultPlan::scheduledLive(FaultRole role, std::int32_t index, std::int32_t tick) const {
  for (std::size_t k = 0; k < faults_.size(); ++k) {
    const auto& f = faults_[k];
    if (f.stopsProcess() && f.role == role && f.index == index && tick >= f.tick && tick <= last_tick_[k]) return false;
  }
  return true;
}

bool FaultPlan::live(FaultRole role, std::int32_t index, std::int32_t tick) const {
  if (!scheduledLive(role, index, tick)) return false;
  for (const auto& f : lost_)  // lost by hand: for good
    if (f.role == role && f.index == index && tick >= f.tick) return false;
  return true;
}

void FaultPlan::loseUnscheduled(FaultRole role, std::int32_t index, std::int32_t from_tick) {
  for (const auto& f : lost_)
    if (f.role == role && f.index == index) return;  // lost once, from the first tick seen
  lost_.push_back(FaultSpec::kill(role, index, std::max(from_tick, 1)));
}

bool FaultPlan::tileLive(std::int32_t tile, std::int32_t tick) const { return live(FaultRole::kNode, tile, tick); }

bool FaultPlan::supernodeLive(std::int32_t supernode, std::int32_t tick) const {
  return live(FaultRole::kSupernode, supernode, tick);
}

std::vector<bool> FaultPlan::liveSupernodes(std::int32_t tick) const {
  std::vector<bool> mask(static_cast<std::size_t>(supernodes_));
  for (std::int32_t j = 0; j < supernodes_; ++j) mask[static_cast<std::size_t>(j)] = supernodeLive(j, tick);
  return mask;
}

bool FaultPlan::supernodeReturns(std::int32_t supernode, std::int32_t tick) const {
  return tick > 1 && supernodeLive(supernode, tick) && !supernodeLive(supernode, tick - 1);
}

bool FaultPlan::supernodeDies(std::int32_t supernode, std::int32_t tick) const {
  return tick > 1 && !scheduledLive(FaultRole::kSupernode, supernode, tick) &&
         scheduledLive(FaultRole::kSupernode, supernode, tick - 1) && supernodeLive(supernode, tick - 1);
}

std::vector<std::int32_t> FaultPlan::dyingAt(std::int32_t tick) const {
  std::vector<std::int32_t> out;
  for (std::int32_t j = 0; j < supernodes_; ++j)
    if (supernodeDies(j, tick)) out.push_back(j);
  return out;
}

bool FaultPlan::partitioned(std::int32_t a, std::int32_t b, std::int32_t tick) const {
  for (const auto& f : faults_) {
    if (f.action != FaultAction::kPartition || f.between.size() != 2 || tick < f.tick || tick > f.lastTick()) continue;
    if ((f.between[0] == a && f.between[1] == b) || (f.between[0] == b && f.between[1] == a)) return true;
  }
  return false;
}

std::optional<double> FaultPlan::burstPte(std::int32_t tick) const {
  std::optional<double> pte;
  for (const auto& f : faults_)
    if (f.action == FaultAction::kBurstLoss && tick >= f.tick && tick <= f.lastTick()) pte = std::max(pte.value_or(0.0), f.pte);
  return pte;
}

bool FaultPlan::settles(std::int32_t supernode, std::int32_t tick, std::int32_t window_size,
                        std::int32_t run_ticks) const {
  const std::int32_t until = std::min(tick + std::max(window_size, 1) - 1, run_ticks);
  for (std::int32_t u = tick; u <= until; ++u)
    if (!supernodeLive(supernode, u)) return false;
  return true;
}

std::int32_t FaultPlan::liveTileCount(std::int32_t tick) const {
  std::int32_t n = 0;
  for (std::int32_t i = 0; i < tiles_; ++i) n += tileLive(i, tick) ? 1 : 0;
  return n;
}

std::vector<std::uint32_t> FaultPlan::liveTiles(std::int32_t tick) const {
  std::vector<std::uint32_t> out;
  for (std::int32_t i = 0; i < tiles_; ++i)
    if (tileLive(i, tick)) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

std::vector<std::uint32_t> FaultPlan::liveSupernodeIndices(std::int32_t tick) const {
  std::vector<std::uint32_t> out;
  for (std::int32_t j = 0; j < supernodes_; ++j)
    if (supernodeLive(j, tick)) out.push_back(static_cast<std::uint32_t>(j));
  return out;
}

std::optional<FaultSpec> FaultPlan::processFaultAt(FaultRole role, std::int32_t index, std::int32_t tick) const {
  for (const auto& f : faults_)
    if (f.stopsProcess() && f.role == role && f.index == index && f.tick == tick) return f;
  return std::nullopt;
}

std::vector<std::uint32_t> FaultPlan::restartsAt(std::int32_t tick) const {
  std::vector<std::uint32_t> out;
  for (const auto& f : faults_)
    if (f.action == FaultAction::kRestart && f.role == FaultRole::kSupernode && f.tick == tick)
      out.push_back(static_cast<std::uint32_t>(f.index));
  std::sort(out.begin(), out.end());
  return out;
}

std::int32_t FaultPlan::incarnation(FaultRole role, std::int32_t index, std::int32_t tick) const {
  std::int32_t first = 1;
  for (const auto& f : faults_)
    if (f.action == FaultAction::kRestart && f.role == role && f.index == index && f.tick <= tick)
      first = std::max(first, f.tick);
  return first;
}

std::optional<std::int32_t> FaultPlan::killEnds(const FaultSpec& kill) const {
  if (kill.action != FaultAction::kKill) return std::nullopt;
  return restartAfter(kill.role, kill.index, kill.tick);
}

}  // namespace wsn::common

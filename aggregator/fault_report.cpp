#include "aggregator/fault_report.hpp"

#include <algorithm>
#include <cmath>

namespace wsn::aggregator {

FaultReport::FaultReport(common::FaultPlan plan, std::int32_t window, std::int32_t ticks)
    : plan_(std::move(plan)), window_(std::max(window, 1)), ticks_(ticks) {}

void FaultReport::addOrphans(std::uint32_t dead, std::int32_t tick, const std::vector<common::TrackHandoff>& orphans) {
  auto& entry = orphans_[{dead, tick}];
  for (const auto& orphan : orphans) entry.ids.insert(orphan.track);
}

void FaultReport::addTick(std::int32_t t, const FaultTickScores& scores, const std::vector<SupernodeTracks>& live,
                          std::uint64_t handoffs_lost_partition) {
  by_tick_.resize(static_cast<std::size_t>(std::max<std::int32_t>(t, 1)));
  by_tick_[static_cast<std::size_t>(t - 1)] = scores;
  handoffs_lost_by_tick_.resize(by_tick_.size(), 0);
  handoffs_lost_by_tick_[static_cast<std::size_t>(t - 1)] = handoffs_lost_partition;
  for (const auto& f : plan_.faults()) {
    if (f.action != common::FaultAction::kRestart || t < f.tick - 1) continue;
    const auto back = static_cast<std::uint32_t>(f.index);
    auto& take_back = take_backs_[{back, f.tick}];
    for (const auto& supernode : live)
      for (const auto& track : supernode.tracks) {
        if (t == f.tick - 1 && supernode.supernode != back) take_back.held.insert(track.track);
        if (t >= f.tick && supernode.supernode == back && take_back.held.count(track.track) != 0 &&
            take_back.taken.insert(track.track).second && take_back.first_taken == 0)
          take_back.first_taken = t;
      }
  }
  for (auto& [key, orphans] : orphans_) {
    if (t < key.second) continue;
    for (const auto& supernode : live)
      for (const auto& track : supernode.tracks)
        if (orphans.ids.count(track.track) != 0 && orphans.carried.insert(track.track).second &&
            orphans.first_carried == 0)
          orphans.first_carried = t;
  }
}

Json FaultReport::window(std::int32_t first, std::int32_t last) const {
  first = std::max(first, 1);
  last = std::min({last, ticks_, static_cast<std::int32_t>(by_tick_.size())});
  Json out{{"first_tick", first}, {"last_tick", last}};
  double abs_k_error = 0, k_true = 0, ospa = 0;
  std::int32_t n = 0;
  for (std::int32_t t = first; t <= last; ++t) {
    const auto& s = by_tick_[static_cast<std::size_t>(t - 1)];
    abs_k_error += std::abs(s.tracks - s.truth_targets);
    k_true += s.truth_targets;
    ospa += s.ospa;
    ++n;
  }
  // Undefined values are null, as metrics.json writes an undefined metric.
  out["eps_k"] = k_true > 0 ? Json(abs_k_error / k_true) : Json(nullptr);
  out["ospa_mean"] = n > 0 ? Json(ospa / n) : Json(nullptr);
  return out;
}

Json FaultReport::faultJson(const common::FaultSpec& f) const {
  Json out{{"tick", f.tick}, {"action", common::faultActionName(f.action)}, {"what", f.describe()}};
  // A kill or restart has no end: its "during" is one window, the transient of the trackers it
  // moves tracks between.
  const bool open_ended = f.action == common::FaultAction::kKill || f.action == common::FaultAction::kRestart;
  const std::int32_t last = open_ended ? f.tick + window_ - 1 : f.lastTick();
  const std::int32_t span = last - f.tick + 1;
  if (f.stopsProcess() || f.action == common::FaultAction::kRestart) {
    out["role"] = common::faultRoleName(f.role);
    out["index"] = f.index;
  }
  if (f.action == common::FaultAction::kRestart) {
    const auto it = take_backs_.find({static_cast<std::uint32_t>(f.index), f.tick});
    const TakeBack none;
    const TakeBack& b = it == take_backs_.end() ? none : it->second;
    // The tracks the restarted supernode reports under ids the others held the tick before: its
    // group handed back to it, and the ticks from the restart to the first of them.
    out["tracks_taken_back"] = b.taken.size();
    out["takeback_ticks"] = b.first_taken > 0 ? Json(b.first_taken - f.tick) : Json(nullptr);
  }
  if (f.action == common::FaultAction::kPause || f.action == common::FaultAction::kPartition ||
      f.action == common::FaultAction::kBurstLoss)
    out["ticks"] = f.ticks;
  if (f.action == common::FaultAction::kBurstLoss) out["pte"] = f.pte;
  if (f.role == common::FaultRole::kSupernode &&
      (f.action == common::FaultAction::kKill || f.action == common::FaultAction::kPause)) {
    const auto it = orphans_.find({static_cast<std::uint32_t>(f.index), f.tick});
    const Orphans none;
    const Orphans& o = it == orphans_.end() ? none : it->second;
    out["tracks_left"] = o.ids.size();
    out["tracks_carried_on"] = o.carried.size();
    out["tracks_lost"] = o.ids.size() - o.carried.size();
    // Ticks from the death to the first of its tracks reported again by an adopter, under its id.
    out["rehome_ticks"] = o.first_carried > 0 ? Json(o.first_carried - f.tick) : Json(nullptr);
  }
  if (f.action == common::FaultAction::kPartition && !handoffs_lost_by_tick_.empty()) {
    const auto at = [&](std::int32_t t) {
      t = std::min(t, static_cast<std::int32_t>(handoffs_lost_by_tick_.size()));
      return t < 1 ? std::uint64_t{0} : handoffs_lost_by_tick_[static_cast<std::size_t>(t - 1)];
    };
    out["handoffs_lost"] = at(last + 1) - at(f.tick);
  }
  out["before"] = window(f.tick - span, f.tick - 1);
  out["during"] = window(f.tick, last);
  out["after"] = window(last + 1, last + span);
  return out;
}

Json FaultReport::json() const {
  Json out = Json::array();
  for (const auto& f : plan_.faults()) out.push_back(faultJson(f));
  for (const auto& f : unscheduled_) {
    Json entry = faultJson(f);
    // Lost outside the scenario: the tick is the first whose outputs the aggregator missed.
    entry["unscheduled"] = true;
    const std::string who = std::string(common::faultRoleName(f.role)) + " " + std::to_string(f.index);
    entry["what"] = f.role == common::FaultRole::kSupernode
                        ? who + " lost outside the scenario (killed by hand), its tracks missing from tick " +
                              std::to_string(f.tick)
                        : who + " lost outside the scenario (killed by hand), announced at tick " + std::to_string(f.tick) +
                              " of the aggregator";
    out.push_back(std::move(entry));
  }
  return out;
}

}  // namespace wsn::aggregator

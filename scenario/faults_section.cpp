#include "scenario/faults_section.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/faults.hpp"
#include "common/scenario_schema.hpp"

namespace wsn::scenario {
namespace {

namespace config = common::config;
using common::FaultAction;
using common::FaultRole;
using common::FaultSpec;
using config::Entry;
using config::Reader;
using config::Section;

/// The keys each action needs besides `tick` and `action`, and why; every other key is refused.
struct ActionKeys {
  std::vector<std::string> needed;
  std::string why;
};

const ActionKeys& keysOf(FaultAction action) {
  static const std::map<FaultAction, ActionKeys> keys = {
      {FaultAction::kKill, {{"role", "index"}, "which process dies; or `count` in place of `index`, drawn by the seed"}},
      {FaultAction::kPause, {{"role", "index", "ticks"}, "which process stops, and for how long"}},
      {FaultAction::kPartition, {{"between", "ticks"}, "which two supernodes lose their handoffs, and for how long"}},
      {FaultAction::kBurstLoss, {{"pte", "ticks"}, "the loss rate, and for how long"}},
      {FaultAction::kRestart, {{"role", "index"}, "which killed supernode comes back"}},
  };
  return keys.at(action);
}

/// The keys an item of `action` needs: a kill takes `count` in place of `index` when it has one.
std::vector<std::string> neededKeys(FaultAction action, bool drawn) {
  auto needed = keysOf(action).needed;
  if (action == FaultAction::kKill && drawn) std::replace(needed.begin(), needed.end(), std::string("index"), std::string("count"));
  return needed;
}

/// The keys of one item: those its action needs, and no other.
void keysFitAction(const Reader& r, const Section& item, const FaultSpec& f) {
  const ActionKeys keys{neededKeys(f.action, item.find("count") != nullptr), keysOf(f.action).why};
  const std::string action = common::faultActionName(f.action);
  if (f.action == FaultAction::kKill && item.find("count") != nullptr && item.find("index") != nullptr)
    r.fail(Reader::lineOf(*item.find("count")), "'" + item.path + "' has both 'index' and 'count'; a kill names its "
                                                  "process (`index`) or has `count` of them drawn by the seed");
  for (const auto& key : keys.needed)
    if (item.find(key) == nullptr)
      r.fail(item.line, "'" + item.path + "' (" + action + ") needs '" + key + "' (" + keys.why + ")");
  for (const auto& [key, entry] : item.entries) {
    if (key == "tick" || key == "action") continue;
    bool needed = false;
    for (const auto& k : keys.needed) needed = needed || k == key;
    if (!needed)
      r.fail(Reader::lineOf(entry), "'" + item.pathOf(key) + "' is not a key of a " + action + " fault; it takes " +
                                        config::join(keys.needed));
  }
}

/// partition.between: [[supernode, A], [supernode, B]], two different supernodes of the scenario.
std::vector<std::int32_t> readBetween(const Reader& r, const Entry& entry, const std::string& path,
                                      std::int32_t supernodes) {
  const int line = Reader::lineOf(entry);
  const std::string shape = "[[supernode, A], [supernode, B]]";
  if (!entry.value.IsSequence() || entry.value.size() != 2)
    r.fail(line, "'" + path + "' must be " + shape + ", got " + config::describe(entry.value));
  std::vector<std::int32_t> out;
  for (std::size_t k = 0; k < 2; ++k) {
    const YAML::Node& pair = entry.value[k];
    const std::string at = path + "[" + std::to_string(k) + "]";
    const int pair_line = Reader::lineOf(pair) > 0 ? Reader::lineOf(pair) : line;
    if (!pair.IsSequence() || pair.size() != 2 || !pair[0].IsScalar() || pair[0].Scalar() != "supernode")
      r.fail(pair_line, "'" + at + "' must be [supernode, INDEX] (a partition cuts the handoffs between two "
                                   "supernodes), got " + config::describe(pair));
    const Entry index{pair[0], pair[1]};
    out.push_back(static_cast<std::int32_t>(
        r.integerValue(index, at + "[1]", config::IntRange{0, std::max<std::int64_t>(0, supernodes - 1)})));
  }
  if (out[0] == out[1]) r.fail(line, "'" + path + "' names supernode " + std::to_string(out[0]) + " twice; expected two different supernodes");
  return out;
}

/// The item of the file a fault came from: its position in the list and its line.
struct Origin {
  std::size_t item = 0;
  int line = 0;
  std::string name() const { return "faults[" + std::to_string(item) + "]"; }
};

/// A kill with `count`: that many processes of its role, drawn from the seed among those no other
/// item names, each a kill of its own in the list (in place of the item, in index order).
std::vector<Origin> expandDrawnKills(const Reader& r, common::Scenario& s, const std::vector<int>& lines,
                                     const std::set<std::size_t>& drawn) {
  std::vector<FaultSpec> expanded;
  std::vector<Origin> origins;
  std::set<std::pair<FaultRole, std::int32_t>> named;  // by another item, or drawn already
  for (std::size_t k = 0; k < s.faults.size(); ++k)
    if (drawn.count(k) == 0 && (s.faults[k].stopsProcess() || s.faults[k].action == FaultAction::kRestart))
      named.emplace(s.faults[k].role, s.faults[k].index);
  for (std::size_t k = 0; k < s.faults.size(); ++k) {
    const auto& f = s.faults[k];
    if (drawn.count(k) == 0) {
      expanded.push_back(f);
      origins.push_back({k, lines[k]});
      continue;
    }
    const std::int32_t processes = f.role == FaultRole::kNode ? s.run.node_processes
                                                              : static_cast<std::int32_t>(s.supernodes.size());
    std::vector<std::int32_t> eligible;
    for (std::int32_t i = 0; i < processes; ++i)
      if (named.count({f.role, i}) == 0) eligible.push_back(i);
    if (f.count > static_cast<std::int32_t>(eligible.size()))
      r.fail(lines[k], "'faults[" + std::to_string(k) + "].count' is " + std::to_string(f.count) + "; only " +
                           std::to_string(eligible.size()) + " " + common::faultRoleName(f.role) +
                           (f.role == FaultRole::kNode ? " tiles" : "s") + " are free of the list's other faults to draw from");
    for (const std::int32_t index : common::drawProcesses(s.run.seed, k, eligible, f.count)) {
      FaultSpec one = f;
      one.index = index;
      named.emplace(f.role, index);
      expanded.push_back(one);
      origins.push_back({k, lines[k]});
    }
  }
  s.faults = std::move(expanded);
  return origins;
}

/// One process cannot be hit by two faults at once, nor by anything after a kill that no restart
/// undid.
void processFaultsApart(const Reader& r, const std::vector<FaultSpec>& faults, const std::vector<Origin>& origins,
                        const common::FaultPlan& plan) {
  // A kill holds until its process's restart, if one comes.
  const auto last = [&](const FaultSpec& x) { return plan.killEnds(x) ? *plan.killEnds(x) - 1 : x.lastTick(); };
  for (std::size_t a = 0; a < faults.size(); ++a)
    for (std::size_t b = 0; b < a; ++b) {
      const auto& f = faults[a];
      const auto& g = faults[b];
      if (!f.stopsProcess() || !g.stopsProcess() || f.role != g.role || f.index != g.index) continue;
      if (f.tick <= last(g) && g.tick <= last(f))
        r.fail(origins[a].line, origins[a].name() + " (" + f.describe() + ") overlaps " + origins[b].name() + " (" +
                                    g.describe() + "); a process can be hit by one kill or pause at a time");
    }
}

/// A restart brings back a supernode that a kill took: the supernode is dead at the tick before.
void restartsFollowKills(const Reader& r, const std::vector<FaultSpec>& faults, const std::vector<Origin>& origins,
                         const common::FaultPlan& plan) {
  for (std::size_t k = 0; k < faults.size(); ++k) {
    const auto& f = faults[k];
    if (f.action != FaultAction::kRestart) continue;
    bool killed = false;
    for (const auto& g : faults)
      killed = killed || (g.action == FaultAction::kKill && g.count == 0 && g.role == f.role && g.index == f.index &&
                          g.tick < f.tick && plan.killEnds(g) == f.tick);
    if (!killed)
      r.fail(origins[k].line, origins[k].name() + " (" + f.describe() + ") has no kill of supernode " +
                           std::to_string(f.index) + " before it that it undoes; a restart brings back a supernode "
                           "that an earlier `kill` of the list took (and no restart since)");
  }
}

/// Some supernode owns the tracking groups at every tick: the live set changes only where a fault
/// begins or ends, so those ticks are the ones to check.
void someSupernodeLive(const Reader& r, const common::Scenario& s, const std::vector<Origin>& origins) {
  const common::FaultPlan plan(s.faults, s.run.node_processes, static_cast<std::int32_t>(s.supernodes.size()));
  for (std::size_t k = 0; k < s.faults.size(); ++k) {
    const std::int32_t tick = s.faults[k].tick;
    if (tick > s.run.ticks) continue;
    bool any = false;
    for (bool live : plan.liveSupernodes(tick)) any = any || live;
    if (!any)
      r.fail(origins[k].line, origins[k].name() + " (" + s.faults[k].describe() +
                           ") leaves no live supernode at tick " + std::to_string(tick) +
                           "; at least one must be live at every tick to take the tracking groups");
  }
}

}  // namespace

void readFaults(const Reader& r, const Section& top, common::Scenario& s) {
  const Entry* e = top.find("faults");
  if (e == nullptr || e->value.IsNull()) return;
  if (!e->value.IsSequence())
    r.fail(Reader::lineOf(*e), "'faults' must be a list of {tick, action, ...}, got " + config::describe(e->value));
  const auto supernodes = static_cast<std::int32_t>(s.supernodes.size());
  std::vector<int> lines;
  std::set<std::size_t> drawn;  // kills with `count` (which may be 0: none)
  config::forEachItem(r, *e, "faults", "{tick, action, ...}", [&](const YAML::Node& node, int line, auto& path) {
    const Section item = r.item(node, line, path, common::schema::fault());
    r.require(item, {"tick", "action"}, "when, and what happens");
    FaultSpec f;
    r.fields(item, common::schema::fault(), f);
    keysFitAction(r, item, f);
    if (item.find("count") != nullptr) drawn.insert(s.faults.size());
    if (f.tick > s.run.ticks)
      r.fail(Reader::lineOf(*item.find("tick")), "'" + item.pathOf("tick") + "' is " + std::to_string(f.tick) +
                                                     ", after the run's last tick " + std::to_string(s.run.ticks) +
                                                     " (run.ticks)");
    if (f.action == FaultAction::kRestart && f.role != FaultRole::kSupernode)
      r.fail(Reader::lineOf(*item.find("role")), "'" + item.pathOf("role") +
                                                     "' is node; only a supernode restarts (a node tile's kill is for "
                                                     "good, and a pause brings a tile back)");
    if (item.find("count") == nullptr && (f.stopsProcess() || f.action == FaultAction::kRestart)) {
      const std::int32_t count = f.role == FaultRole::kNode ? s.run.node_processes : supernodes;
      if (f.index >= count)
        r.fail(Reader::lineOf(*item.find("index")),
               "'" + item.pathOf("index") + "' is " + std::to_string(f.index) + "; the run has " + std::to_string(count) +
                   (f.role == FaultRole::kNode ? " node tiles (run.node_processes)" : " supernodes") + ", 0 to " +
                   std::to_string(count - 1));
    }
    if (f.action == FaultAction::kPartition) f.between = readBetween(r, *item.find("between"), item.pathOf("between"), supernodes);
    s.faults.push_back(std::move(f));
    lines.push_back(line);
  });
  // A drawn kill takes only processes no other item names, so the rules between items hold for it
  // by construction; checked after the draw, each spec names the item it came from.
  const auto origins = expandDrawnKills(r, s, lines, drawn);
  const common::FaultPlan plan(s.faults, s.run.node_processes, supernodes);
  processFaultsApart(r, s.faults, origins, plan);
  restartsFollowKills(r, s.faults, origins, plan);
  someSupernodeLive(r, s, origins);
}

}  // namespace wsn::scenario

namespace wsn::scenario {

std::string faultsYaml(const std::vector<common::FaultSpec>& faults) {
  if (faults.empty()) return "";
  std::string out = "faults:\n";
  const auto& table = common::schema::fault();
  for (std::size_t k = 0; k < faults.size(); ++k) {
    const auto& f = faults[k];
    std::string item = "tick: " + table.find("tick")->yamlValue(f) + ", action: " + table.find("action")->yamlValue(f);
    // A drawn kill is written as the item it came from, once, with what the seed drew.
    std::string drawn;
    if (f.count > 0) {
      for (std::int32_t n = 0; n < f.count && k + static_cast<std::size_t>(n) < faults.size(); ++n)
        drawn += (n == 0 ? "" : ", ") + std::to_string(faults[k + static_cast<std::size_t>(n)].index);
      k += static_cast<std::size_t>(f.count - 1);
      drawn = "  # drawn from run.seed: " + std::string(common::faultRoleName(f.role)) + " " + drawn;
    }
    for (const auto& key : neededKeys(f.action, f.count > 0)) {
      const std::string value = key == "between" ? "[[supernode, " + std::to_string(f.between.at(0)) + "], [supernode, " +
                                                       std::to_string(f.between.at(1)) + "]]"
                                                 : table.find(key)->yamlValue(f);
      item += ", " + key + ": " + value;
    }
    out += "  - {" + item + "}" + drawn + "\n";
  }
  return out;
}

}  // namespace wsn::scenario

#include "launcher/cluster.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <mutex>
#include <optional>
#include <sstream>
#include <stop_token>
#include <thread>

#include "aggregator/role.hpp"
#include "common/dds/cyclone_config.hpp"
#include "common/faults.hpp"
#include "common/printable.hpp"
#include "common/dds/entity.hpp"
#include "common/dds/process_main.hpp"
#include "common/dds/role_runtime.hpp"
#include "common/dds/security.hpp"
#include "launcher/hosts.hpp"
#include "launcher/fault_signals.hpp"
#include "launcher/stopped_processes.hpp"
#include "launcher/run_description.hpp"
#include "launcher/run_summary.hpp"
#include "launcher/status_observer.hpp"
#include "network_model/role.hpp"
#include "node/role.hpp"
#include "supernode/role.hpp"
#include "wsntrack.h"

namespace wsn::launcher {
namespace {

using Clock = std::chrono::steady_clock;

/// How long a stopped process (SIGTERM) or role thread (stop request) may take to end by itself.
constexpr auto kStopGrace = std::chrono::seconds(3);

// The signal that asked the run to stop (SIGINT, SIGTERM), 0 while none has.
std::atomic<int> g_interrupt_signal{0};
extern "C" void onInterrupt(int signal_number) { g_interrupt_signal.store(signal_number); }

/// The failure text of a run stopped by a signal, and the result's record of it.
void markInterrupted(ClusterResult& result) {
  result.interrupted_by = g_interrupt_signal.load();
  result.failure = std::string("interrupted by ") + (result.interrupted_by == SIGINT ? "SIGINT" : "SIGTERM") +
                   " before the last tick; the run directory is incomplete";
}

/// One process of the cluster (or, in-process, one role thread): a role instance, or a group of
/// `count` consecutive supernodes; its host and its participant index there.
struct RoleSlot {
  std::string role;
  std::uint32_t index = 0;  ///< the first index of a group
  std::size_t host = 0;     ///< into HostPlan::hosts(); 0, the launcher's, on a single-host run
  int participant_index = 0;
  std::uint32_t count = 1;
  bool holds(std::uint32_t i) const { return i >= index && i < index + count; }
  /// "supernode 3", or "supernode 0-3" for a group.
  std::string name() const { return role + " " + indices("-"); }
  /// The stem of its log file: "supernode-3", "supernode-0-3".
  std::string logStem() const { return role + "-" + indices("-"); }

 private:
  std::string indices(const char* dash) const {
    return std::to_string(index) + (count > 1 ? dash + std::to_string(index + count - 1) : "");
  }
};

/// Every process of the cluster, numbered per host; `next_index[h]` ends as host h's count. With
/// `group_supernodes`, consecutive supernodes on one host share a process (supernodeProcesses),
/// except those the scenario's faults kill or pause: the launcher enacts those on the process.
std::vector<RoleSlot> clusterSlots(const common::Scenario& scenario, const HostPlan& hosts,
                                   std::vector<int>* next_index = nullptr, bool group_supernodes = true) {
  std::vector<RoleSlot> slots;
  std::vector<int> next(std::max<std::size_t>(hosts.hosts().size(), 1), 0);
  const auto add = [&](const std::string& role, std::uint32_t index) {
    const std::size_t host = hosts.hostOf(role, index);
    slots.push_back({role, index, host, next[host]++});
  };
  for (std::int32_t i = 0; i < scenario.run.node_processes; ++i) add("node", static_cast<std::uint32_t>(i));
  add("network", 0);
  const auto supernodes = static_cast<std::int32_t>(scenario.supernodes.size());
  const std::int32_t group_size =
      group_supernodes ? (supernodes + supernodeProcesses(scenario) - 1) / supernodeProcesses(scenario) : 1;
  std::set<std::int32_t> alone;
  for (const auto& fault : scenario.faults)
    if (fault.stopsProcess() && fault.role == common::FaultRole::kSupernode) alone.insert(fault.index);
  for (std::int32_t j = 0; j < supernodes; ++j) {
    auto* group = slots.back().role == "supernode" ? &slots.back() : nullptr;
    const auto index = static_cast<std::uint32_t>(j);
    if (group != nullptr && static_cast<std::int32_t>(group->count) < group_size && !alone.contains(j) &&
        !alone.contains(static_cast<std::int32_t>(group->index)) && hosts.hostOf("supernode", index) == group->host)
      ++group->count;
    else
      add("supernode", index);
  }
  add("aggregator", 0);
  if (next_index != nullptr) *next_index = next;
  return slots;
}

dds::RoleContext contextFor(const RoleSlot& slot, const ClusterOptions& options, std::stop_token stop) {
  dds::RoleContext context;
  context.role = slot.role;
  context.index = slot.index;
  context.run_id = options.identity.run_id;
  context.domain = static_cast<dds_domainid_t>(options.identity.domain);
  context.run_dir = options.run_dir;
  context.scenario = options.scenario;
  context.shape = {options.scenario.run.node_processes, static_cast<std::int32_t>(options.scenario.supernodes.size())};
  context.stall_timeout = std::chrono::milliseconds(static_cast<long>(options.stall_timeout_s * 1000));
  context.tick_interval = std::chrono::microseconds(std::llround(options.tick_interval_s * 1e6));
  context.stop = std::move(stop);
  context.status_key = options.status_key;
  return context;
}

const std::map<std::string, std::function<void(const dds::RoleContext&)>>& roleRunners() {
  static const std::map<std::string, std::function<void(const dds::RoleContext&)>> runners = {
      {"node", node::runNodeRole},
      {"network", network_model::runNetworkRole},
      {"supernode", supernode::runSupernodeRole},
      {"aggregator", aggregator::runAggregatorRole},
  };
  return runners;
}

/// Shows the aggregator's tick on stderr: in place on a terminal, every 10 % otherwise.
class ProgressDisplay {
 public:
  ProgressDisplay(std::int32_t ticks, bool enabled) : ticks_(ticks), enabled_(enabled), tty_(::isatty(2) != 0) {}
  void update(std::int32_t tick) {
    if (!enabled_ || tick <= shown_) return;
    shown_ = tick;
    if (tty_) {
      std::fprintf(stderr, "\r  tick %d/%d", tick, ticks_);
      std::fflush(stderr);
    } else if (tick == ticks_ || tick * 10 / ticks_ > (last_line_ * 10) / ticks_) {
      std::fprintf(stderr, "  tick %d/%d\n", tick, ticks_);
      last_line_ = tick;
    }
  }
  void finish() {
    if (enabled_ && tty_ && shown_ > 0) std::fprintf(stderr, "\n");
  }

 private:
  std::int32_t ticks_;
  bool enabled_;
  bool tty_;
  std::int32_t shown_ = 0;
  std::int32_t last_line_ = 0;
};

std::string tailOf(const std::string& path, std::size_t lines) {
  std::ifstream in(path);
  std::vector<std::string> all;
  for (std::string line; std::getline(in, line);) all.push_back(line);
  std::ostringstream out;
  for (std::size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) out << "    " << all[i] << "\n";
  return out.str();
}

/// Records when the aggregator was first seen past tick 1.
void noteFirstTick(ClusterResult& result, std::int32_t tick, Clock::time_point started) {
  if (tick >= 1 && result.first_tick_s == 0.0) result.first_tick_s = std::chrono::duration<double>(Clock::now() - started).count();
}

/// A started role process. A process on another host holds the read end of a pipe as its standard
/// input (its lifeline, --stdin-lifeline): `lifeline` is the write end, which the launcher keeps open
/// while the process runs and which the kernel closes when the launcher dies. Every process reads
/// the run's status key from the first line of that pipe (--status-key-on-stdin): a pipe only the
/// launcher writes, unlike the command line (/proc/PID/cmdline) or a file.
struct Spawned {
  pid_t pid = -1;
  int lifeline = -1;
};

/// Starts the process of `slot`; `first_tick` above 1 starts the one a `restart` brings back.
Spawned spawn(const RoleSlot& slot, const ClusterOptions& options, const std::string& log_path, std::int32_t first_tick = 1) {
  const std::string program = options.bin_dir + "/wsntrack-" + slot.role;
  std::vector<std::string> args = {program,
                                   "--run-dir", options.run_dir,
                                   "--run-id", [&] { std::ostringstream h; h << std::hex << options.identity.run_id; return h.str(); }(),
                                   "--domain", std::to_string(options.identity.domain),
                                   "--participant-index", std::to_string(slot.participant_index),
                                   "--tiles", std::to_string(options.scenario.run.node_processes),
                                   "--stall-timeout", std::to_string(options.stall_timeout_s),
                                   "--tick-interval", std::to_string(options.tick_interval_s)};
  if (slot.role == "node" || slot.role == "supernode") {
    args.push_back("--index");
    args.push_back(std::to_string(slot.index));
  }
  if (slot.count > 1) {
    args.push_back("--count");
    args.push_back(std::to_string(slot.count));
  }
  if (first_tick > 1) {
    args.push_back("--first-tick");
    args.push_back(std::to_string(first_tick));
  }
  const bool remote = options.hosts.startsRemotely(slot.role, slot.index);
  args.push_back("--status-key-on-stdin");
  if (remote) {
    // The launcher cannot signal a process behind ssh: the role enacts the scenario's faults itself
    // and ends when its standard input does.
    for (const char* flag : {"--faults-in-role", "--stdin-lifeline"}) args.push_back(flag);
    args.push_back("--cyclone-config");
    args.push_back(hostConfigFile(options.run_dir, options.hosts, slot.host));
    const auto& start = options.hosts.hosts().at(slot.host).start;
    args.insert(args.begin(), start.begin(), start.end());
  }
  int lifeline[2] = {-1, -1};
  if (::pipe2(lifeline, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe failed: ") + std::strerror(errno));
  const pid_t launcher = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    for (const int fd : lifeline)
      if (fd >= 0) ::close(fd);
    throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  }
  if (pid == 0) {
    // A role must not outlive its launcher (killed with -9, say): the kernel sends SIGTERM when
    // the parent dies; the getppid check closes the race of a parent that died before prctl.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != launcher) ::_exit(1);
    const int fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::close(fd);
    }
    ::dup2(lifeline[0], 0);  // dup2 clears close-on-exec on the copy
    // Cyclone opens its sockets without close-on-exec: the launcher's observer's ports must not
    // stay bound for as long as any role lives.
    ::close_range(3, ~0U, 0);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    // A start command (ssh, ip netns exec) is looked up on PATH; a role's program is a path.
    ::execvp(argv[0], argv.data());
    std::fprintf(stderr, "cannot execute %s: %s\n", argv[0], std::strerror(errno));
    ::_exit(127);
  }
  // 65 bytes into an empty pipe: within PIPE_BUF, so the write is whole and does not block; the
  // read end is still open here, so a child that died at once cannot make it raise SIGPIPE.
  const std::string key_line = options.status_key.hex() + "\n";
  const bool written = ::write(lifeline[1], key_line.data(), key_line.size()) == static_cast<ssize_t>(key_line.size());
  ::close(lifeline[0]);
  if (!remote) {
    ::close(lifeline[1]);
    lifeline[1] = -1;
  }
  // A process that did not get its key fails at start (its standard input ended), and says so.
  if (!written) std::fprintf(stderr, "wsntrack run: could not hand %s its status key: %s\n", slot.name().c_str(), std::strerror(errno));
  return {pid, lifeline[1]};
}

/// " (on host h2, started by 'ssh h2', hosts file line 7)" for a process started through a host's
/// start command: its exit status may be the command's own (ssh's 255, a missing namespace's).
std::string startedBy(const RoleSlot& slot, const ClusterOptions& options) {
  if (!options.hosts.startsRemotely(slot.role, slot.index)) return "";
  const Host& host = options.hosts.hosts()[slot.host];
  std::string command;
  for (const auto& word : host.start) command += (command.empty() ? "" : " ") + word;
  return " (on host " + host.name + ", started by '" + command + "', hosts file line " + std::to_string(host.line) + ")";
}

/// The outcome of every slot before it ran: its name, host and log.
std::vector<RoleOutcome> initialOutcomes(const std::vector<RoleSlot>& slots, const ClusterOptions& options) {
  std::vector<RoleOutcome> outcomes(slots.size());
  for (std::size_t i = 0; i < slots.size(); ++i) {
    outcomes[i].name = slots[i].name();
    if (options.hosts.multiHost()) outcomes[i].host = options.hosts.hosts()[slots[i].host].name;
    outcomes[i].log_path = options.run_dir + "/logs/" + slots[i].logStem() + ".log";
  }
  return outcomes;
}

/// The slot of each supernode, in index order.
std::vector<std::size_t> supernodeSlots(const std::vector<RoleSlot>& slots) {
  std::vector<std::size_t> supernode_slots;
  for (std::size_t i = 0; i < slots.size(); ++i)
    if (slots[i].role == "supernode") supernode_slots.insert(supernode_slots.end(), slots[i].count, i);
  return supernode_slots;
}

/// What the roles of a failed process said of their failure in FAILED samples, when they said it:
/// ": why" (a role's own message names it; in a group, each is named), or nothing.
std::string saidWhy(const std::map<std::string, std::string>& failed_messages, const RoleSlot& slot) {
  std::string why;
  for (std::uint32_t k = 0; k < slot.count; ++k)
    if (const auto it = failed_messages.find(slot.role + " " + std::to_string(slot.index + k)); it != failed_messages.end())
      why += (why.empty() ? ": " : "; ") + (slot.count > 1 ? it->first + ": " : "") + it->second;
  return why;
}

/// Whether losing the process of `slot` by hand leaves a run that can go on: every role it holds.
bool survivable(HandLosses& losses, const RoleSlot& slot) {
  for (std::uint32_t k = 0; k < slot.count; ++k)
    if (!losses.survivable(slot.role, slot.index + k)) return false;
  return true;
}

/// The role processes the launcher started and has not reaped yet, with the lifelines of those on
/// other hosts (closed once reaped).
class RunningProcesses {
 public:
  RunningProcesses(const std::vector<RoleSlot>& slots, const ClusterOptions& options) : slots_(slots), options_(options) {}
  void start(std::size_t slot, const std::string& log_path, std::int32_t first_tick) {
    const Spawned spawned = spawn(slots_[slot], options_, log_path, first_tick);
    slot_of_[spawned.pid] = slot;
    if (spawned.lifeline >= 0) lifelines_[spawned.pid] = spawned.lifeline;
  }
  /// The slot of `pid` if it is one of ours, which it then no longer is.
  std::optional<std::size_t> reaped(pid_t pid) {
    const auto it = slot_of_.find(pid);
    if (it == slot_of_.end()) return std::nullopt;
    const std::size_t slot = it->second;
    slot_of_.erase(it);
    if (const auto lifeline = lifelines_.find(pid); lifeline != lifelines_.end()) {
      ::close(lifeline->second);
      lifelines_.erase(lifeline);
    }
    return slot;
  }
  const std::map<pid_t, std::size_t>& bySlot() const { return slot_of_; }
  void signalAll(int signal_number) const {
    for (const auto& [pid, slot] : slot_of_) ::kill(pid, signal_number);
  }
  bool empty() const { return slot_of_.empty(); }

 private:
  const std::vector<RoleSlot>& slots_;
  const ClusterOptions& options_;
  std::map<pid_t, std::size_t> slot_of_;
  std::map<pid_t, int> lifelines_;  ///< pid -> write end of its standard input (other hosts)
};

ClusterResult runProcesses(const ClusterOptions& options) {
  ClusterResult result;
  std::vector<int> launcher_host_count;
  const auto slots = clusterSlots(options.scenario, options.hosts, &launcher_host_count);
  const auto started = Clock::now();
  RunningProcesses processes(slots, options);
  const auto& running = processes.bySlot();  // pid -> slot
  // A role on another host enacts its faults itself (--faults-in-role) and ends with status
  // kExitScheduledDeath where the scenario kills it.
  const auto remote = [&](std::size_t slot) { return options.hosts.startsRemotely(slots[slot].role, slots[slot].index); };
  result.outcomes = initialOutcomes(slots, options);
  StoppedProcesses stopped(Clock::now());
  const common::FaultPlan plan(options.scenario.faults, options.scenario.run.node_processes,
                               static_cast<std::int32_t>(options.scenario.supernodes.size()));
  FaultSignals fault_signals(plan, options.scenario.run.ticks);
  RestartSchedule restarts(plan, supernodeSlots(slots), options.scenario.run.max_ticks_in_flight);
  auto stopAll = [&](int signal_number) { fault_signals.continueAll(); processes.signalAll(signal_number); };
  std::vector<std::size_t> lost_now;  // slots lost by hand since the last announcement
  HandLosses hand_losses(options.scenario);
  std::map<std::string, std::string> failed_messages;  // role name -> its FAILED sample's message
  auto reap = [&](bool block) {
    int status = 0;
    struct rusage usage {};
    pid_t pid;
    while ((pid = ::wait4(-1, &status, block ? 0 : WNOHANG, &usage)) > 0) {
      const auto reaped = processes.reaped(pid);
      if (!reaped) continue;
      const std::size_t slot_index = *reaped;
      auto& outcome = result.outcomes[slot_index];
      outcome.peak_rss_kb = usage.ru_maxrss;  // Linux reports kilobytes
      outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      outcome.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
      const auto fault = fault_signals.killedByFault(pid);
      if (fault && outcome.signal == SIGKILL) {
        outcome.exit_code = 0;  // the death the scenario asked for
        outcome.message = "killed by SIGKILL as the scenario's faults asked (" + *fault + ")";
        restarts.killed(slot_index);
      } else if (remote(slot_index) && outcome.exit_code == dds::kExitScheduledDeath) {
        outcome.exit_code = 0;
        outcome.message = "ended where the scenario's faults kill it";
        restarts.killed(slot_index);
      } else if (outcome.signal == SIGKILL && g_interrupt_signal.load() == 0 && result.failure.empty() &&
                 survivable(hand_losses, slots[slot_index])) {
        // A deployment loses nodes and supernodes: the run goes on without this one.
        outcome.exit_code = 0;
        outcome.message = "killed by SIGKILL outside the scenario's faults; the cluster went on without it";
        lost_now.push_back(slot_index);
      }
      // After an interrupt the roles stop because they were told to (a terminal's Ctrl-C reaches
      // every process of the group): their exit codes say nothing about a fault.
      else if (outcome.exit_code != 0 && result.failure.empty() && g_interrupt_signal.load() == 0)
        result.failure = outcome.name + " " + exitDescription(outcome) + startedBy(slots[slot_index], options) +
                         saidWhy(failed_messages, slots[slot_index]) + "; log " + outcome.log_path + ":\n" + tailOf(outcome.log_path, 8);
      if (block) break;
    }
  };

  try {
    // The observer takes the last participant index of the launcher's host, after its role processes.
    StatusObserver observer(options, launcher_host_count.front());
    for (std::size_t i = 0; i < slots.size(); ++i) processes.start(i, result.outcomes[i].log_path, 1);

    ProgressDisplay progress(options.scenario.run.ticks, options.show_progress);
    std::int32_t tick = 0;
    std::vector<StatusObserver::Faulted> faulted;
    while (!running.empty() && result.failure.empty()) {
      // 50 ms: a process lost by hand is announced within that (plus its tick in flight).
      observer.poll(std::chrono::milliseconds(50), tick, failed_messages, faulted);
      noteFirstTick(result, tick, started);
      for (const auto& f : faulted)
        for (const auto& [pid, slot] : running)
          if (slots[slot].role == f.role && slots[slot].holds(f.index) && !remote(slot))
            fault_signals.announced(pid, f.role, f.index, f.tick);
      faulted.clear();
      fault_signals.progressed(tick);
      for (const auto& [pid, slot] : running) stopped.sample(pid, slots[slot].name(), fault_signals.pausing(pid));
      progress.update(tick);
      reap(false);
      for (const std::size_t lost : lost_now)
        for (std::uint32_t k = 0; k < slots[lost].count; ++k)
          observer.announceLost(slots[lost].role, slots[lost].index + k, result.outcomes[lost].message);
      lost_now.clear();
      for (const auto& [slot, first_tick] : restarts.due(tick)) {
        auto& outcome = result.outcomes[slot];
        outcome.message += ", restarted at tick " + std::to_string(first_tick);
        outcome.log_path = options.run_dir + "/logs/" + slots[slot].logStem() + "-from-" + std::to_string(first_tick) + ".log";
        processes.start(slot, outcome.log_path, first_tick);
      }
      if (g_interrupt_signal.load() != 0) markInterrupted(result);
      if (Clock::now() - options.started > options.timeout)
        result.failure = "timed out after " + std::to_string(options.timeout.count()) + " s";
    }
    progress.finish();
    observer.poll(std::chrono::milliseconds(0), tick, failed_messages, faulted);  // what came after the last poll
    observer.writeRejections();
  } catch (const std::exception& error) {
    if (result.failure.empty()) result.failure = std::string("launcher: ") + error.what();
  }
  // A stopped peer is the likely cause of a stall that another role reported: say so first.
  if (const auto stops = stopped.diagnosis(); !result.failure.empty() && !stops.empty())
    result.failure = stops + "; its peers drop a process stopped longer than its DDS lease (10 s), and the run stalled:\n  " +
                     result.failure;

  // Stop whatever is left: politely first, then for good. Every pid we started is reaped.
  if (!running.empty()) {
    for (const auto& [pid, slot] : running)
      if (result.outcomes[slot].message.empty()) result.outcomes[slot].message = kStoppedByLauncher;
    stopAll(SIGTERM);
    const auto deadline = Clock::now() + kStopGrace;
    while (!running.empty() && Clock::now() < deadline) {
      reap(false);
      if (!running.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    stopAll(SIGKILL);
    while (!running.empty()) reap(true);
  }
  result.wall_s = std::chrono::duration<double>(Clock::now() - started).count();
  result.ok = result.failure.empty();
  return result;
}

ClusterResult runThreads(const ClusterOptions& options) {
  ClusterResult result;
  const auto slots = clusterSlots(options.scenario, options.hosts, nullptr, false);
  const auto started = Clock::now();
  // The first failure stops every role thread: their waits wake at once on the request.
  std::stop_source stop;
  std::atomic<std::size_t> finished{0};
  std::mutex mutex;
  result.outcomes.resize(slots.size());

  std::vector<dds::RoleContext> contexts;
  for (const auto& slot : slots) contexts.push_back(contextFor(slot, options, stop.get_token()));
  std::vector<std::thread> threads;
  auto fail = [&](const std::string& why) {
    std::lock_guard lock(mutex);
    if (result.failure.empty()) result.failure = why;
    stop.request_stop();
  };
  try {
    // One domain (participant index 0) shared by all role threads; the observer joins it too
    // and outlives them.
    StatusObserver observer(options, 0);
    const common::FaultPlan plan(options.scenario.faults, options.scenario.run.node_processes,
                                 static_cast<std::int32_t>(options.scenario.supernodes.size()));
    for (std::size_t i = 0; i < slots.size(); ++i) {
      result.outcomes[i].name = slots[i].name();
      threads.emplace_back([&, i] {
        try {
          // A thread the scenario kills ends there; a restart of it runs the role again from
          // the restart's tick (its producers wait for its readers, as for a process).
          while (true) {
            try {
              roleRunners().at(slots[i].role)(contexts[i]);
              break;
            } catch (const dds::ScheduledDeath& death) {
              // Only a supernode restarts; 0: no restart after this death.
              const std::int32_t back =
                  slots[i].role == "supernode"
                      ? plan.restartAfter(common::FaultRole::kSupernode, static_cast<std::int32_t>(slots[i].index),
                                          contexts[i].first_tick)
                            .value_or(0)
                      : 0;
              std::lock_guard lock(mutex);
              result.outcomes[i].message = std::string("ended as the scenario's faults asked (") + death.what() + ")";
              if (back == 0) break;
              result.outcomes[i].message += ", restarted at tick " + std::to_string(back);
              contexts[i].first_tick = back;
            }
          }
        } catch (const std::exception& error) {
          {
            std::lock_guard lock(mutex);
            result.outcomes[i].exit_code = 1;
            result.outcomes[i].message = error.what();
          }
          fail(slots[i].name() + ": " + error.what());
        }
        ++finished;
      });
    }
    ProgressDisplay progress(options.scenario.run.ticks, options.show_progress);
    std::int32_t tick = 0;
    // A role thread's failure reaches the launcher as its exception, never as a sample.
    std::map<std::string, std::string> failed_messages;
    std::vector<StatusObserver::Faulted> faulted;  // role threads enact their faults themselves
    std::optional<Clock::time_point> stop_seen;
    while (finished.load() < slots.size()) {
      observer.poll(std::chrono::milliseconds(200), tick, failed_messages, faulted);
      noteFirstTick(result, tick, started);
      // A role thread still in set-up (a topology or truth of 10^7 items being built) cannot see
      // the stop request, and a thread cannot be killed: after the same grace a process gets
      // between SIGTERM and SIGKILL, the run is given up with the process (see abandon).
      if (stop.stop_requested() && !stop_seen) stop_seen = Clock::now();
      if (stop_seen && Clock::now() - *stop_seen > kStopGrace && options.abandon) {
        std::lock_guard lock(mutex);
        result.ok = false;
        result.wall_s = std::chrono::duration<double>(Clock::now() - started).count();
        options.abandon(result);
        std::_Exit(runExitStatus(result));  // abandon must not return; if it does, still never join
      }
      progress.update(tick);
      if (g_interrupt_signal.load() != 0 && result.interrupted_by == 0) {
        {
          std::lock_guard lock(mutex);
          markInterrupted(result);
        }
        stop.request_stop();
      }
      if (Clock::now() - options.started > options.timeout) fail("timed out after " + std::to_string(options.timeout.count()) + " s");
    }
    progress.finish();
    for (auto& thread : threads) thread.join();
    observer.poll(std::chrono::milliseconds(0), tick, failed_messages, faulted);  // what came after the last poll
    observer.writeRejections();
  } catch (const std::exception& error) {
    fail(std::string("launcher: ") + error.what());
    for (auto& thread : threads)
      if (thread.joinable()) thread.join();
  }
  struct rusage usage {};
  if (::getrusage(RUSAGE_SELF, &usage) == 0) result.in_process_peak_rss_kb = usage.ru_maxrss;
  result.wall_s = std::chrono::duration<double>(Clock::now() - started).count();
  result.ok = result.failure.empty();
  return result;
}

}  // namespace

int runExitStatus(const ClusterResult& result) {
  if (result.ok) return 0;
  return result.interrupted_by != 0 ? 128 + result.interrupted_by : 1;
}

std::int32_t supernodeProcesses(const common::Scenario& scenario) {
  const auto supernodes = static_cast<std::int32_t>(scenario.supernodes.size());
  const std::int32_t wanted =
      scenario.run.supernode_processes > 0 ? scenario.run.supernode_processes : kDefaultSupernodeProcesses;
  return std::max(1, std::min(wanted, supernodes));
}

/// Cyclone participants on each host: its role processes, and on the launcher's (0) its observer.
/// In-process, one participant index for everything.
std::vector<int> participantsPerHost(const common::Scenario& scenario, bool in_process, const HostPlan& hosts) {
  if (in_process) return {1};
  std::vector<int> per_host;
  clusterSlots(scenario, hosts, &per_host);
  per_host.front() += 1;
  return per_host;
}

int participantCount(const common::Scenario& scenario, bool in_process, const HostPlan& hosts) {
  const auto per_host = participantsPerHost(scenario, in_process, hosts);
  return *std::max_element(per_host.begin(), per_host.end());
}

int launcherHostParticipants(const common::Scenario& scenario, bool in_process, const HostPlan& hosts) {
  return participantsPerHost(scenario, in_process, hosts).front();
}

void installInterruptHandlers() {
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
}

int interruptSignal() { return g_interrupt_signal.load(); }

RunDescription describeRun(const ClusterOptions& options) {
  RunDescription description;
  description.identity = options.identity;
  description.participants = participantCount(options.scenario, options.in_process, options.hosts);
  description.first_viewer_index = launcherHostParticipants(options.scenario, options.in_process, options.hosts);
  description.viewer_slots = dds::kViewerSlots;
  description.scenario = options.scenario.name;
  description.ticks = options.scenario.run.ticks;
  description.processes = static_cast<std::int32_t>(clusterSlots(options.scenario, options.hosts).size());
  description.tick_interval_s = options.tick_interval_s;
  description.in_process = options.in_process;
  description.launcher_pid = ::getpid();
  description.provenance_json = options.provenance_json;
  description.status = kRunRunning;
  return description;
}

ClusterResult runCluster(const ClusterOptions& options) {
  installInterruptHandlers();
  return options.in_process ? runThreads(options) : runProcesses(options);
}

}  // namespace wsn::launcher

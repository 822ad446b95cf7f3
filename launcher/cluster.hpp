// Starting and supervising a whole cluster on this host: every role as its own process (or as
// threads of this process with --in-process), progress from the status topic, and a clean
// stop of every process it started — after a failure as after success.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "common/dds/cyclone_config.hpp"
#include "common/dds/status_auth.hpp"
#include "common/scenario_config.hpp"
#include "launcher/hosts.hpp"
#include "launcher/run_description.hpp"

namespace wsn::launcher {

struct ClusterResult;

struct ClusterOptions {
  std::string run_dir;
  RunIdentity identity;
  common::Scenario scenario;  ///< resolved, overrides applied
  bool in_process = false;
  HostPlan hosts;  ///< --hosts: where each process runs; empty: all on this host, on loopback
  std::string bin_dir;  ///< where the wsntrack-<role> executables are
  std::chrono::seconds timeout{1800};  ///< counted from `started`
  /// When the launcher started: --timeout bounds the whole command, set-up included.
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  double stall_timeout_s = 60.0;
  double tick_interval_s = 0.0;  ///< --tick-interval: real-time pacing of the sources (0: none)
  bool show_progress = true;
  std::string provenance_json;  ///< common::provenanceJson, written into run.json (and so metrics.json)
  /// Signs the launcher's and the roles' status samples (common/dds/status_auth.hpp); reaches a role
  /// process as the first line of its standard input, never through a file or its command line.
  dds::StatusKey status_key = dds::StatusKey::generate();
  /// In-process mode: called (from the supervising thread) when role threads have not ended within
  /// the stop grace after a failure, timeout or signal, with the result so far. Threads cannot be
  /// killed, so it must report, mark the run failed and end the process (_exit): it must not return.
  std::function<void(const ClusterResult&)> abandon;
};

/// RoleOutcome::message of a process the launcher stopped because the run ended (failed, timed out
/// or interrupted) while it still ran: its exit status says nothing about a fault of its own.
inline constexpr const char* kStoppedByLauncher = "stopped by the launcher";

/// How one process (or role thread) ended.
struct RoleOutcome {
  std::string name;      ///< e.g. "node 1"
  int exit_code = 0;     ///< 0 success; for processes killed by a signal, 128 + signal
  std::string message;   ///< why it failed, when known
  std::string log_path;  ///< multi-process mode: its stdout/stderr
  long peak_rss_kb = 0;  ///< multi-process mode: the process's peak resident set (wait4): on another
                         ///< host, that of the process its start command made here (ssh; ip netns
                         ///< exec becomes the role itself)
  int signal = 0;        ///< multi-process mode: the signal that killed the process, 0 when it exited
  std::string host;      ///< the host it ran on, on a run over several hosts (--hosts); else empty
};

struct ClusterResult {
  bool ok = false;
  std::vector<RoleOutcome> outcomes;
  double wall_s = 0.0;  ///< from start of the first process to the exit of the last
  /// From the start of the first process until the launcher saw the aggregator finish tick 1:
  /// the start-up (set-up, discovery) plus one tick through the pipeline. 0 when it never did.
  double first_tick_s = 0.0;
  /// In-process mode: peak resident set of this whole process (every role thread and the
  /// launcher together); 0 in multi-process mode, where each outcome carries its own.
  long in_process_peak_rss_kb = 0;
  std::string failure;  ///< first failure, for the user
  /// The signal (SIGINT, SIGTERM) that stopped the run before its end; 0 when none did.
  int interrupted_by = 0;
};

/// The exit status of `wsntrack run` for a result: 0 when it ran to its end, 128 + the signal for
/// a run stopped by SIGINT (130) or SIGTERM (143), as a shell reports a command killed by it, and 1
/// for any other failure.
int runExitStatus(const ClusterResult& result);

/// Makes SIGINT and SIGTERM a request to stop the run (interruptSignal() then says which) instead of
/// the end of the process; called by runCluster, and by the launcher earlier to cover its set-up.
void installInterruptHandlers();

/// The signal (SIGINT, SIGTERM) that asked the run to stop, 0 while none has.
int interruptSignal();

/// run.json's content for the cluster of `options`, with status running.
RunDescription describeRun(const ClusterOptions& options);

/// Runs the cluster to completion (or failure, timeout, SIGINT) and stops everything it started.
ClusterResult runCluster(const ClusterOptions& options);

/// Most Cyclone participants one run may have: their ports must stay inside its domain's range.
/// The viewer slots after them may reach past it, but only into the next domain's multicast ports
/// (offsets 0..9, unused: multicast is off), never into its unicast ones.
inline constexpr int kMaxParticipants = 119;
static_assert(2 * (kMaxParticipants + dds::kViewerSlots + 1) + 11 < 250 + 10,
              "viewer slots would reach the next domain's unicast ports");

/// Supernode processes when the scenario leaves run.supernode_processes at 0: discovery grows
/// with the participants (every one announces its endpoints to every other), and at 10^6 sensors
/// 64 supernode processes took 12-13 s to start where 16 processes of 4 took 2.3 s (medians of 3,
/// docs/PERFORMANCE.md).
inline constexpr std::int32_t kDefaultSupernodeProcesses = 16;

/// The processes the scenario's supernodes run in: run.supernode_processes, or when 0 one per
/// supernode up to kDefaultSupernodeProcesses; never more than the supernodes.
std::int32_t supernodeProcesses(const common::Scenario& scenario);

/// Number of Cyclone participants of a run: every process plus the launcher's observer; on a run
/// over several hosts, the most on any one host (participant indices and ports count per host).
int participantCount(const common::Scenario& scenario, bool in_process, const HostPlan& hosts = {});

/// Participants on the launcher's own host (its observer included): live viewers there take the
/// indices after them.
int launcherHostParticipants(const common::Scenario& scenario, bool in_process, const HostPlan& hosts = {});

}  // namespace wsn::launcher

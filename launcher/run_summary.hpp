// What `wsntrack run` prints about a run (start line, summary, failure), as pure text from parsed
// run files and results, so that every line is unit-tested.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/scenario_config.hpp"
#include "launcher/cluster.hpp"
#include "launcher/hosts.hpp"
#include "launcher/plot_job.hpp"

namespace wsn::launcher {

/// The headline numbers of a finished run's files; empty where a file or a value is missing
/// (a role that failed to write it, a metric that is undefined and written as null).
struct RunFigures {
  std::optional<double> truth_targets;  ///< metrics.json
  std::optional<double> track_ids;
  std::optional<double> eps_k;
  /// eq. 10 over the matches closer than metrics.eps_x_gate: the ungated eps_x (still in
  /// metrics.json) is ruled by the few far pairs of a miscount, so the summary shows this one.
  std::optional<double> eps_x_gated;
  std::optional<double> ospa_mean;
  std::optional<double> settled_eps_k;      ///< the settled stream (streams.settled.eps_k)
  std::optional<double> settled_ospa_mean;
  std::optional<double> dropped_stale;
  std::optional<double> wall_s;       ///< the tick loop, as the aggregator timed it
  std::optional<double> ticks_per_s;
  std::optional<double> reports_sent;  ///< network.json
  std::optional<double> reports_lost;
  std::optional<double> reports_delayed;
  std::optional<double> reports_unreachable;  ///< no route to any supernode (network.json's unreachable)
  std::optional<double> reports_lost_dead_supernode;  ///< due at a supernode a fault killed (runs with faults)
  /// One line per fault of the scenario (metrics.json's faults): what it was and, for a supernode
  /// that died, how many of its tracks the adopters carried on and after how many ticks.
  std::vector<std::string> faults;
  /// Samples and items the roles refused at the edge (rejected.json's total).
  std::optional<double> samples_rejected;
};

/// The figures of the texts of metrics.json and network.json ("" for a missing file); a text that
/// is not JSON gives no figures rather than an error: the run itself succeeded.
RunFigures parseRunFigures(const std::string& metrics_json, const std::string& network_json);

/// The figures of RUN_DIR/metrics.json and RUN_DIR/network.json.
RunFigures readRunFigures(const std::string& run_dir);

/// "wsntrack: NAME (seed S, T ticks) on N node tiles, ...": the line before the cluster starts.
std::string runStartLine(const common::Scenario& scenario, int domain, bool in_process, const HostPlan& hosts = {});

/// The summary after a run that succeeded: the run directory, the figures, the wall time and peak
/// memory of `result`, and the plots when they were asked for.
std::string runSummary(const std::string& run_dir, const RunFigures& figures, const ClusterResult& result,
                       bool in_process, const std::optional<PlotOutcome>& plots);

/// "SIGKILL" for 9, the usual short names of Linux's signals; "signal N" for any other.
std::string signalName(int signal_number);

/// How a role ended, for people: "killed by SIGKILL" for a death by signal, "exited with code N"
/// otherwise (the exit code itself keeps the shell's 128 + signal for a signal death).
std::string exitDescription(const RoleOutcome& outcome);

/// The report of a run that failed: the first failure, then every process that exited non-zero.
std::string runFailure(const ClusterResult& result);

}  // namespace wsn::launcher

// Preparing a run directory: the resolved scenario, the truth, the Cyclone configuration and
// the isolation settings (run id, domain id) that keep concurrent runs apart.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/scenario.hpp"

namespace wsn::launcher {

/// Where and how a run talks: unique per run.
struct RunIdentity {
  std::uint64_t run_id = 0;
  int domain = 0;
};

/// A fresh run id (time, pid and a counter mixed), never 0.
std::uint64_t newRunId();

/// The domain ids 1 .. dds::kMaxDomainId whose whole Cyclone port block (7400 + 250 d ..
/// + 249) lies outside the kernel's ephemeral port range [ephemeral_first, ephemeral_last]:
/// a port in that range can be taken by any socket the OS numbers itself (another run's, a
/// browser's) between the launcher's check and the roles' bind.
std::vector<int> domainsOutsideEphemeralPorts(int ephemeral_first, int ephemeral_last);

/// The kernel's ephemeral port range (/proc/sys/net/ipv4/ip_local_port_range); Linux's default
/// 32768-60999 when it cannot be read.
std::pair<int, int> ephemeralPortRange();

/// Picks a domain id outside the ephemeral ports whose Cyclone unicast ports for `participants`
/// indices are free on 127.0.0.1, starting from a run-id-dependent position so that
/// concurrent runs spread out.
int pickFreeDomain(std::uint64_t run_id, int participants);

/// Default run directory: runs/<scenario name>-seed<seed>-<UTC timestamp>-<pid>.
std::string defaultRunDirectory(const common::Scenario& scenario);

/// Creates the directory (parents too); it must not exist or be empty unless `overwrite`.
void createRunDirectory(const std::string& path, bool overwrite);

/// Writes scenario.yaml (resolved), truth.csv and cyclonedds.xml for `participants` processes, and
/// sensors.csv (sensor,x,y: true positions) when the layout is random: a grid follows from
/// scenario.yaml alone, and writing it would cost up to 10^7 rows.
void writeRunInputs(const std::string& run_dir, const common::Scenario& scenario, const RunIdentity& identity,
                    int participants);

/// What became of the plots of a run.
struct PlotOutcome {
  enum class Status { kDrawn, kSkipped, kFailed };
  Status status = Status::kSkipped;
  std::string message;  ///< one line: the files written, or why there are none
  double seconds = 0;
};

/// plot_run.py (located by install_layout) run by kPlotPython (the one with python3-matplotlib) on a run
/// directory, output to logs/plot.log. It is started before the cluster and waits on a pipe for the
/// word to go: python's start-up and matplotlib's import, most of the plotting time, overlap the
/// run instead of following it. A missing python, script or matplotlib gives kSkipped, any other
/// failure kFailed: neither undoes a run that succeeded.
class PlotJob {
 public:
  PlotJob(const std::string& plot_script, const std::string& run_dir, const std::string& format);
  PlotJob(const PlotJob&) = delete;
  PlotJob& operator=(const PlotJob&) = delete;
  /// A job never told to go is told to stop, and reaped.
  ~PlotJob();
  /// Lets the script draw (`go`) or tells it to stop, and waits for it.
  PlotOutcome finish(bool go);

 private:
  int pid_ = -1;
  int to_script_ = -1;  ///< write end of the script's stdin
  PlotOutcome outcome_;
  std::string log_;
  std::string files_;
};

/// What a viewer needs to join a running cluster, kept as run.json in the run directory.
struct RunDescription {
  RunIdentity identity;
  int participants = 0;        ///< Cyclone participant indices 0 .. participants - 1 are the cluster's
  int first_viewer_index = 0;  ///< viewers take indices first_viewer_index .. + viewer_slots - 1
  int viewer_slots = 0;
  std::string scenario;        ///< its name
  std::int32_t ticks = 0;
  std::int32_t processes = 0;  ///< role processes (or threads) that report on the status topic
  double tick_interval_s = 0;
  bool in_process = false;
  long long launcher_pid = 0;  ///< the run is live while this wsntrack process is
  std::string provenance_json;  ///< common::provenanceJson of the run; the last line of run.json
};

/// Writes run_dir/run.json atomically (written aside, then renamed).
void writeRunDescription(const std::string& run_dir, const RunDescription& run);

/// Reads run_dir/run.json; throws std::runtime_error saying what is missing or wrong.
RunDescription readRunDescription(const std::string& run_dir);

}  // namespace wsn::launcher

// run.json: what a viewer (wsntrack watch, examples/watch_tracks.c) needs to join a running
// cluster, and whether the run is still going, finished whole, or failed (and why).
#pragma once

#include <cstdint>
#include <string>

namespace wsn::launcher {

/// Where and how a run talks: unique per run.
struct RunIdentity {
  std::uint64_t run_id = 0;
  int domain = 0;
  friend bool operator==(const RunIdentity&, const RunIdentity&) = default;
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
  /// kRunning from before the cluster starts; kComplete only once every role exited 0 and its
  /// outputs exist; kFailed with `reason` otherwise. Empty when read from a run.json written before
  /// the status existed.
  std::string status;
  std::string reason;  ///< why it failed, one line, as the launcher printed it; empty otherwise
  std::string provenance_json;  ///< common::provenanceJson of the run; the last line of run.json
  friend bool operator==(const RunDescription&, const RunDescription&) = default;
};

inline constexpr const char* kRunRunning = "running";
inline constexpr const char* kRunComplete = "complete";
inline constexpr const char* kRunFailed = "failed";

/// The text of run.json: one key per line, so that a shell script can pick a value with sed as
/// well as a JSON parser can; the provenance (when there is one) is the last line.
std::string runDescriptionJson(const RunDescription& run);

/// Reads the text of a run.json; throws std::runtime_error "`path`: what is missing or wrong".
RunDescription parseRunDescription(const std::string& json, const std::string& path);

/// Writes run_dir/run.json atomically (written aside, then renamed).
void writeRunDescription(const std::string& run_dir, const RunDescription& run);

/// Reads run_dir/run.json; throws std::runtime_error saying what is missing or wrong.
RunDescription readRunDescription(const std::string& run_dir);

/// Rewrites run_dir/run.json (atomically) with `status` and `reason` (its first line only), the
/// rest as it was; throws std::runtime_error when run.json cannot be read or written.
void markRun(const std::string& run_dir, const std::string& status, const std::string& reason = "");

}  // namespace wsn::launcher

// The launcher's watch over its own set-up (scenario resolution, the run's inputs): --timeout and
// SIGINT/SIGTERM end it promptly even where the work itself never looks at a stop request.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>
#include <thread>

namespace wsn::launcher {

/// Watches `wsntrack run` from its start until the cluster's own supervision takes over (handOver).
/// Set-up is one long computation in the main thread (Topology, Truth, observation statistics of
/// a 10^7-sensor scenario take minutes) with no point to stop at cooperatively, and nothing in it
/// needs undoing: so on a signal or at the deadline a thread of its own reports it, marks the run
/// failed in run.json when there is one, and ends the process with _exit (128 + the signal, or 1).
class SetupGuard {
 public:
  /// Installs the interrupt handlers (installInterruptHandlers) and starts watching; the deadline
  /// is `started` + `timeout`.
  SetupGuard(std::chrono::steady_clock::time_point started, std::chrono::seconds timeout);
  SetupGuard(const SetupGuard&) = delete;
  SetupGuard& operator=(const SetupGuard&) = delete;
  ~SetupGuard();

  /// What set-up is doing now, for the message ("resolving the scenario").
  void phase(const std::string& what);
  /// From now on run.json exists in `run_dir` and is marked failed when set-up is stopped.
  void runDirectory(const std::string& run_dir);
  bool hasRunDirectory() {
    std::lock_guard lock(mutex_);
    return !run_dir_.empty();
  }
  /// Whether a stop leaves the run's credentials in place (--keep-credentials); it removes them
  /// otherwise, as the finished run would.
  void keepCredentials(bool keep) {
    std::lock_guard lock(mutex_);
    keep_credentials_ = keep;
  }
  /// Held while the launcher writes run.json itself, so that a stop never interleaves with it.
  std::mutex& runJsonMutex() { return mutex_; }
  /// The cluster's supervision takes over signals and the deadline: the guard stops watching.
  void handOver();

 private:
  void watch();
  [[noreturn]] void stopSetUp(int signal_number);

  std::chrono::steady_clock::time_point deadline_;
  std::chrono::seconds timeout_;
  std::mutex mutex_;
  std::string phase_;
  std::string run_dir_;
  bool keep_credentials_ = false;
  std::atomic<bool> done_{false};
  std::thread thread_;
};

}  // namespace wsn::launcher

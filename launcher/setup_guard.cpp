#include "launcher/setup_guard.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>

#include "launcher/cluster.hpp"
#include "launcher/run_credentials.hpp"
#include "launcher/run_description.hpp"
#include "launcher/run_summary.hpp"

namespace wsn::launcher {

SetupGuard::SetupGuard(std::chrono::steady_clock::time_point started, std::chrono::seconds timeout)
    : deadline_(started + timeout), timeout_(timeout) {
  installInterruptHandlers();
  thread_ = std::thread([this] { watch(); });
}

SetupGuard::~SetupGuard() { handOver(); }

void SetupGuard::phase(const std::string& what) {
  std::lock_guard lock(mutex_);
  phase_ = what;
}

void SetupGuard::runDirectory(const std::string& run_dir) {
  std::lock_guard lock(mutex_);
  run_dir_ = run_dir;
}

void SetupGuard::handOver() {
  done_.store(true);
  if (thread_.joinable()) thread_.join();
}

void SetupGuard::watch() {
  // A poll rather than a wait on the signal: the handler may only set a flag, and 50 ms is far
  // below anything a person or a test waits for.
  while (!done_.load()) {
    const int signal_number = interruptSignal();
    if (signal_number != 0 || std::chrono::steady_clock::now() > deadline_) {
      if (done_.load()) return;  // the cluster's supervision has it now
      stopSetUp(signal_number);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

void SetupGuard::stopSetUp(int signal_number) {
  // Taken and never released: the main thread must not write run.json after this.
  mutex_.lock();
  const std::string where = phase_.empty() ? "during set-up" : "during set-up (" + phase_ + ")";
  const std::string why = signal_number != 0 ? "interrupted by " + signalName(signal_number) + " " + where +
                                                   (run_dir_.empty() ? "" : "; the run directory is incomplete")
                                             : "timed out after " + std::to_string(timeout_.count()) + " s " + where;
  std::string note;
  if (!run_dir_.empty()) {
    try {
      markRun(run_dir_, kRunFailed, why);
    } catch (const std::exception& error) {
      note = std::string("wsntrack run: warning: ") + error.what() + "\n";
    }
    try {
      if (!keep_credentials_) removeRunCredentials(run_dir_);
    } catch (const std::exception& error) {
      note += std::string("wsntrack run: warning: ") + error.what() + "\n";
    }
  }
  const int status = signal_number != 0 ? 128 + signal_number : 1;
  std::fprintf(stderr, "%swsntrack run: %s%s (exit status %d)\n", note.c_str(), signal_number != 0 ? "" : "FAILED: ",
               why.c_str(), status);
  std::fflush(stderr);
  std::_Exit(status);
}

}  // namespace wsn::launcher

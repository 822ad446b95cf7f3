// Which role processes the launcher saw stopped (SIGSTOP, a debugger) during a run, and for how
// long. A process stopped past its DDS lease is dropped by its peers and the cluster stalls behind
// it; the run's failure then names it rather than the peer whose wait timed out first.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <map>
#include <string>

namespace wsn::launcher {

/// The state letter of /proc/PID/stat ('R', 'S', 'T' for stopped, ...); '?' when unreadable.
char processState(pid_t pid);

class StoppedProcesses {
 public:
  using Clock = std::chrono::steady_clock;
  explicit StoppedProcesses(Clock::time_point started) : started_(started) {}

  /// Looks at `pid` (role `name`) now; a stop the scenario's faults asked for is `expected` and
  /// not recorded.
  void sample(pid_t pid, const std::string& name, bool expected);
  /// "supernode 1 was stopped (SIGSTOP or a debugger) for about 15.0 s, from 3.1 s into the run";
  /// every such process, or "" when none was stopped for at least `at_least`.
  std::string diagnosis(std::chrono::milliseconds at_least = std::chrono::milliseconds(1000)) const;

 private:
  struct Span {
    std::string name;
    Clock::time_point first;
    Clock::time_point last;
  };
  Clock::time_point started_;
  std::map<pid_t, Span> spans_;  ///< the longest stop seen of each process
  std::map<pid_t, Span> current_;  ///< stops going on
};

}  // namespace wsn::launcher

// A rough estimate of what a scenario costs to run (memory, time), so that `wsntrack validate`
// can warn before a run that this machine cannot finish. Coefficients: docs/ARCHITECTURE.md.
#pragma once

#include <string>
#include <vector>

#include "common/scenario_config.hpp"

namespace wsn::launcher {

struct ResourceEstimate {
  double sensors = 0;        ///< N
  double neighbours = 0;     ///< per sensor within the communication range: pi (range / spacing)^2
  double targets = 0;        ///< scripted + drawn + born over the run
  double target_ticks = 0;   ///< sum over targets of the ticks each lives (an upper bound for born ones)
  double memory_bytes = 0;   ///< peak over the whole run, every process together
  double seconds = 0;        ///< set-up (observation statistics, topology) and the tick loop
};

/// The estimate for a scenario as loaded (before its component parameters are resolved: the
/// resolution itself is what can take the time).
ResourceEstimate estimateResources(const common::Scenario& scenario);

/// "warning: ..." lines when the estimate is far beyond a machine with `ram_bytes` of memory:
/// memory above half of it, or more than 10 minutes of run time. Empty when it fits.
std::vector<std::string> resourceWarnings(const ResourceEstimate& estimate, double ram_bytes);

/// MemTotal of /proc/meminfo in bytes; 0 when it cannot be read.
double totalRamBytes();

}  // namespace wsn::launcher

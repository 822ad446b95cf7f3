// `wsntrack watch RUN_DIR`: a live terminal view of a running cluster (global tracks and per-tick
// metrics), joined over DDS as a viewer — like any other program built from the IDL can.
#pragma once

#include <string>
#include <vector>

namespace wsn::launcher {

/// Exit codes of `wsntrack watch`.
inline constexpr int kWatchFinished = 0;     ///< the run ended (aggregator DONE or last tick shown)
inline constexpr int kWatchFailed = 1;       ///< the run failed, was not running, or timed out
inline constexpr int kWatchUsage = 2;        ///< bad options, or RUN_DIR is not a run directory
inline constexpr int kWatchInterrupted = 130;

/// Runs the `watch` command with its arguments (after the command word); returns the exit code.
int commandWatch(const std::vector<std::string>& args);

}  // namespace wsn::launcher

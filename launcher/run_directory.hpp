// Preparing a run directory: the resolved scenario, the truth, the Cyclone configuration and
// the isolation settings (run id, domain id) that keep concurrent runs apart.
#pragma once

#include <cstdint>
#include <string>

#include "common/scenario.hpp"

namespace wsn::launcher {

/// Where and how a run talks: unique per run.
struct RunIdentity {
  std::uint64_t run_id = 0;
  int domain = 0;
};

/// A fresh run id (time, pid and a counter mixed), never 0.
std::uint64_t newRunId();

/// Picks a domain id whose Cyclone unicast ports for `participants` indices are free on
/// 127.0.0.1, starting from a run-id-dependent position so that concurrent runs spread out.
int pickFreeDomain(std::uint64_t run_id, int participants);

/// Default run directory: runs/<scenario name>-seed<seed>-<UTC timestamp>-<pid>.
std::string defaultRunDirectory(const common::Scenario& scenario);

/// Creates the directory (parents too); it must not exist or be empty unless `overwrite`.
void createRunDirectory(const std::string& path, bool overwrite);

/// Writes scenario.yaml (resolved), truth.csv and cyclonedds.xml for `participants` processes.
void writeRunInputs(const std::string& run_dir, const common::Scenario& scenario, const RunIdentity& identity,
                    int participants);

}  // namespace wsn::launcher

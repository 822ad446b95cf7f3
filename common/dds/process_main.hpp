// The shared main() of every role executable: parses the role's command line, loads the run's
// resolved scenario, creates the loopback-only Cyclone domain and runs the role, turning every
// failure into a clear message and a non-zero exit code.
#pragma once

#include <functional>
#include <string>

#include "common/dds/role_runtime.hpp"

namespace wsn::dds {

/// A role body: runs the role to completion or throws.
using RoleRunner = std::function<void(const RoleContext&)>;

/// Reads the run's resolved scenario.yaml. The role mains pass scenario::loadScenario: the loader
/// reads the sensor models' keys through their registry, so it sits above the roles' libraries
/// and this layer cannot name it.
using ScenarioLoader = common::Scenario (*)(const std::string& path);

/// Exit status of a role process that ended where the scenario's faults kill it, enacting the fault
/// itself (--faults-in-role, for roles the launcher cannot signal: on another host).
inline constexpr int kExitScheduledDeath = 3;

/// Runs one role as a process. `summary` is the --help text's first paragraph.
int runRoleProcess(int argc, char** argv, const std::string& role, const std::string& summary, bool indexed,
                   ScenarioLoader load_scenario, const RoleRunner& runner);

/// Reads the Cyclone configuration template in file `path`.
std::string readConfigFile(const std::string& path);

/// Reads the run's Cyclone configuration template, run_dir/cyclonedds.xml (on a run over several
/// hosts, the launcher's host's).
std::string readConfigTemplate(const std::string& run_dir);

}  // namespace wsn::dds

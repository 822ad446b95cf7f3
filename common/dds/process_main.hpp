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

/// Runs one role as a process. `summary` is the --help text's first paragraph.
int runRoleProcess(int argc, char** argv, const std::string& role, const std::string& summary, bool indexed,
                   ScenarioLoader load_scenario, const RoleRunner& runner);

/// Reads the run's Cyclone configuration template from run_dir/cyclonedds.xml.
std::string readConfigTemplate(const std::string& run_dir);

}  // namespace wsn::dds

// The resolved scenario.yaml of a run: every key written out with its default or derived value,
// so that the roles (and anyone rerunning the run) read exactly the scenario the launcher resolved.
#pragma once

#include <string>

#include "common/scenario_config.hpp"

namespace wsn::scenario {

/// YAML with every field present (defaults filled in), which loads back to an equal scenario.
/// A value the file left out and the loader computed from others is marked `# derived: how`.
std::string resolvedScenarioYaml(const common::Scenario& scenario);

}  // namespace wsn::scenario

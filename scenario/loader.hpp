// Loading a scenario (the structs of common/scenario_config.hpp) from YAML with strict validation
// (DESIGN principle 6). Command-line overrides are in scenario/overrides.hpp, the resolved
// scenario.yaml in scenario/writer.hpp.
#pragma once

#include <string>

#include "common/scenario_config.hpp"
#include "common/scenario_error.hpp"

namespace wsn::scenario {

/// Loads and strictly validates a scenario file: unknown keys, wrong types, out-of-range
/// values and a missing file throw common::ScenarioError naming file, line and what was expected.
common::Scenario loadScenario(const std::string& path);

/// Same, from YAML text; `name_for_errors` stands in for the file name in messages.
common::Scenario parseScenario(const std::string& yaml_text, const std::string& name_for_errors);

}  // namespace wsn::scenario

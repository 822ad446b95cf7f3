// The steps of loading that the loader and the overrides share: a file's text, its one YAML
// document, and that document read into a validated scenario. Internal to wsn_scenario: the
// overrides set values in the document between the second step and the third.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "common/scenario_config.hpp"

namespace wsn::scenario {

/// The whole text of a scenario file; common::ScenarioError "path: cannot open ..." otherwise.
std::string readScenarioFile(const std::string& path);

/// The one YAML document of a scenario text (null when empty); syntax errors as "name:line: ...".
YAML::Node parseScenarioDocument(const std::string& yaml_text, const std::string& name_for_errors);

/// The scenario a document describes, validated key by key and rule by rule.
common::Scenario scenarioFromDocument(const YAML::Node& root, const std::string& name_for_errors);

}  // namespace wsn::scenario

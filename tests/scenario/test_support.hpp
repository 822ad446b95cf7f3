// Parsing a scenario text in the scenario tests: the file name "s.yaml" that every expected
// message names, and the message of the error a text raises.
#pragma once

#include <string>

#include "scenario/loader.hpp"

namespace wsn::scenario::test_support {

using common::Scenario;
using common::ScenarioError;

/// parseScenario with the file name "s.yaml".
inline Scenario parse(const std::string& text) { return parseScenario(text, "s.yaml"); }

/// The message of the ScenarioError that parsing `text` throws ("" when it does not throw).
inline std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const ScenarioError& error) {
    return error.what();
  }
  return "";
}

}  // namespace wsn::scenario::test_support

// Numeric parameters of a pluggable component chosen by name in the scenario (a supernode tracking
// engine, the aggregator's track association): their specifications and the strict check that
// fills in defaults.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/scenario.hpp"

namespace wsn::common {

/// A numeric parameter with its paper default and admissible range.
struct ParamSpec {
  std::string name;
  double default_value = 0.0;
  double min = 0.0;
  double max = 0.0;
  std::string description;
  bool integer = false;  ///< the value must be a whole number (a count)
};

/// Checks `params`, read from the scenario's `section` (e.g. "tracker.params"), against the
/// `specs` of `owner` (e.g. "engine 'mcmcda'") and adds every missing parameter with its default.
/// Throws ScenarioError "source_path:line: ..." for an unknown name, a value out of range or a
/// fraction where a count is expected; names are checked in sorted order, so the first error
/// reported does not depend on the order of keys in the file.
void resolveParams(const std::string& source_path, const std::string& section, const std::string& owner,
                   const std::vector<ParamSpec>& specs, std::map<std::string, EngineParam>& params);

/// params[name] if present, else `fallback`.
double paramOr(const std::map<std::string, EngineParam>& params, const std::string& name, double fallback);

/// Shortest text that reads back to the same double ("0.5", "9.21", "3").
std::string formatNumber(double value);

}  // namespace wsn::common

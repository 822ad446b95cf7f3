// Command-line overrides of a scenario (wsntrack run/validate --set KEY=VALUE, tools/sweep.py):
// set in the file's YAML and validated by the loader, exactly as if the file had been edited.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "common/scenario_config.hpp"
#include "common/scenario_error.hpp"

namespace wsn::scenario {

/// An override that could not be applied, or that made the scenario invalid: what() reads
/// "--set KEY=VALUE: what was expected" (the loader's message without a line number, which would
/// point into no file).
class OverrideError : public common::ScenarioError {
 public:
  using common::ScenarioError::ScenarioError;
};

/// One `--set KEY=VALUE`. KEY is a dotted path into the scenario's YAML, list items as name[i]
/// (`network.pte`, `tracker.params.gate_chi2`, `supernodes[1].x`); VALUE is read as one YAML
/// scalar (`0.4` is a number, `gnn` and `"0.4"` are strings, an empty VALUE is null).
struct ScenarioOverride {
  std::string key;
  std::string value;
  /// How the user wrote it when that was not `--set KEY=VALUE` (`--nodes 5`); messages name it so.
  std::string as_written;
  /// As the user wrote it.
  std::string text() const { return as_written.empty() ? "--set " + key + "=" + value : as_written; }
};

/// Splits "KEY=VALUE" at the first '='; throws OverrideError when there is none or KEY is empty.
ScenarioOverride parseOverride(const std::string& key_equals_value);

/// Checks that belong to another module (the engine registry) and run on every loaded scenario;
/// they may fill in defaults and throw common::ScenarioError "source_path:line: ...".
using ScenarioCheck = std::function<void(common::Scenario&)>;

/// Parses `yaml_text`, sets every override in order in its YAML tree and validates the result
/// with the loader's checks and `check`, exactly as if the file had been edited: values the
/// loader derives from others (sensor_model.beta, the default supernode) follow the overrides.
/// A missing mapping on the way is created (the loader then rejects an unknown name); lists are
/// never extended. Throws common::ScenarioError "name:line: ..." for a problem of the text itself
/// (it reads the same without the overrides) and OverrideError naming the responsible --set
/// otherwise.
common::Scenario applyOverrides(const std::string& yaml_text, const std::string& name_for_errors,
                                const std::vector<ScenarioOverride>& overrides, const ScenarioCheck& check = {});

/// loadScenario() with overrides and further checks: applyOverrides() on the file's text.
common::Scenario loadScenario(const std::string& path, const std::vector<ScenarioOverride>& overrides,
                              const ScenarioCheck& check = {});

}  // namespace wsn::scenario

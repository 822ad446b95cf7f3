// `wsntrack components`: every registered sensor model, tracking engine, track association and
// metric with its parameters, units and meaning; and the check that a scenario's components fit
// together (an engine takes the measurements its sensor model makes).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/scenario_config.hpp"
#include "common/scenario_error.hpp"

namespace wsn::launcher {

/// The listing of every registry, as `wsntrack components` prints it.
std::string componentsText();

/// The catalogue as JSON (`wsntrack components --json`): every scenario key, sensor model, engine,
/// association and metric with units, defaults, ranges and meaning; the metrics.json and
/// network.json quantities sweeps tabulate, with their labels; the columns of each output file; the
/// measurement kinds, target classes, observation fates and the track-id layout (launcher/catalogue.cpp).
std::string componentsJson();

/// The key tables of scenarios/README.md, each between "<!-- table: NAME -->" and
/// "<!-- end table -->" (`wsntrack components --markdown`; a test checks the README against it).
std::string componentsMarkdown();

/// The registered names of one kind of component, one per line, in registry order
/// (`wsntrack components --names KIND`, for scripts such as the golden outputs). KIND is one of
/// componentKinds(); throws std::invalid_argument naming them for any other.
std::string componentNames(const std::string& kind);

/// The kinds componentNames takes: sensor-models, engines, associations, metrics.
std::vector<std::string> componentKinds();

/// The engines and associations only (`wsntrack engines`, kept for scripts that use it).
std::string enginesText();

/// The first measurement kind of `reported` that `accepted` lacks, if any.
std::optional<std::string> unacceptedKind(const std::vector<std::string>& reported,
                                          const std::vector<std::string>& accepted);

/// Throws common::ScenarioError "file:line: ..." when the scenario's tracker engine does not
/// accept every measurement kind of its sensor model (of the scenario's sensors, where the model
/// tells them apart).
void checkComponentsFit(const common::Scenario& scenario);

}  // namespace wsn::launcher

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

#include "supernode/engine.hpp"
#include "supernode/gnn/gnn_engine.hpp"
#include "supernode/mcmcda/mcmcda_engine.hpp"

namespace wsn::supernode {
namespace {

/// Shortest text that reads back to the same double ("0.5", "9.21", "3").
std::string formatNumber(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string where(const common::Scenario& scenario, int line) {
  return scenario.source_path + ":" + std::to_string(line) + ": ";
}

const EngineSpec* findEngine(const std::string& name) {
  const auto& registry = engineRegistry();
  const auto it = std::find_if(registry.begin(), registry.end(), [&](const EngineSpec& e) { return e.name == name; });
  return it == registry.end() ? nullptr : &*it;
}

}  // namespace

const std::vector<EngineSpec>& engineRegistry() {
  static const std::vector<EngineSpec> registry = {
      gnn::engineSpec(),
      mcmcda::engineSpec(),
      // A new engine is a sibling folder plus one line here.
  };
  return registry;
}

void resolveEngineParams(common::Scenario& scenario) {
  auto& tracker = scenario.tracker;
  const EngineSpec* spec = findEngine(tracker.engine);
  if (spec == nullptr) {
    std::string names;
    for (const auto& e : engineRegistry()) names += (names.empty() ? "" : ", ") + e.name;
    throw common::ScenarioError(where(scenario, tracker.engine_line) + "unknown tracker engine '" + tracker.engine +
                                "'; expected one of: " + names);
  }

  // std::map iterates by name, so the first error reported does not depend on file order.
  for (const auto& [name, param] : tracker.params) {
    const auto it = std::find_if(spec->params.begin(), spec->params.end(),
                                 [&](const ParamSpec& p) { return p.name == name; });
    if (it == spec->params.end()) {
      std::string names;
      for (const auto& p : spec->params) names += (names.empty() ? "" : ", ") + p.name;
      throw common::ScenarioError(where(scenario, param.line) + "unknown parameter '" + name + "' for engine '" +
                                  spec->name + "'; expected one of: " + names);
    }
    const double v = param.value;
    if (!(v >= it->min && v <= it->max))  // also rejects NaN
      throw common::ScenarioError(where(scenario, param.line) + "'tracker.params." + name + "' must be in [" +
                                  formatNumber(it->min) + ", " + formatNumber(it->max) + "], got " +
                                  formatNumber(v));
    if (it->integer && v != std::floor(v))
      throw common::ScenarioError(where(scenario, param.line) + "'tracker.params." + name +
                                  "' must be a whole number, got " + formatNumber(v));
  }

  for (const auto& p : spec->params)
    if (!tracker.params.contains(p.name)) tracker.params[p.name] = common::EngineParam{p.default_value, 0};
}

std::unique_ptr<Engine> makeEngine(const EngineContext& context) {
  const EngineSpec* spec = findEngine(context.scenario.tracker.engine);
  if (spec == nullptr)
    throw common::ScenarioError(where(context.scenario, context.scenario.tracker.engine_line) +
                                "unknown tracker engine '" + context.scenario.tracker.engine + "'");
  return spec->create(context);
}

}  // namespace wsn::supernode

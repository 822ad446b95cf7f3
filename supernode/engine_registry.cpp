#include <algorithm>
#include <string>

#include "supernode/engine.hpp"
#include "supernode/gnn/gnn_engine.hpp"
#include "supernode/mcmcda/mcmcda_engine.hpp"
#include "supernode/rulebased/rulebased_engine.hpp"

namespace wsn::supernode {
namespace {

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
      rulebased::engineSpec(),
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

  common::resolveParams(scenario.source_path, "tracker.params", "engine '" + spec->name + "'", spec->params,
                        tracker.params);
  if (spec->check) spec->check(scenario);
}

std::unique_ptr<Engine> makeEngine(const EngineContext& context) {
  const EngineSpec* spec = findEngine(context.scenario.tracker.engine);
  if (spec == nullptr)
    throw common::ScenarioError(where(context.scenario, context.scenario.tracker.engine_line) +
                                "unknown tracker engine '" + context.scenario.tracker.engine + "'");
  return spec->create(context);
}

}  // namespace wsn::supernode

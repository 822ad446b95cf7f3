#include <algorithm>
#include <utility>
#include <stdexcept>
#include <string>
#include <string_view>

#include "common/sensor_layout.hpp"
#include "supernode/engine.hpp"
#include "supernode/gnn/gnn_engine.hpp"
#include "supernode/mcmcda/mcmcda_engine.hpp"
#include "supernode/rulebased/rulebased_engine.hpp"
#include "supernode/sbmht/sbmht_engine.hpp"
#include "supernode/supernode_tracker.hpp"

namespace wsn::supernode {
namespace {

std::string where(const common::Scenario& scenario, int line) {
  return scenario.source_path + ":" + std::to_string(line) + ": ";
}

}  // namespace

const common::Registry<EngineSpec>& engineRegistry() {
  static const common::Registry<EngineSpec> registry("tracker engine", {
      gnn::engineSpec(),
      mcmcda::engineSpec(),
      rulebased::engineSpec(),
      sbmht::engineSpec(),
      // A new engine is a sibling folder plus one line here.
  });
  return registry;
}

void resolveEngineParams(common::Scenario& scenario, const common::StatisticsSource& statistics) {
  auto& tracker = scenario.tracker;
  const EngineSpec& spec =
      engineRegistry().at<common::ScenarioError>(tracker.engine, where(scenario, tracker.engine_line));
  common::resolveParams(scenario.source_path, "tracker.params", "engine '" + spec.name + "'", spec.params,
                        tracker.params, statistics, &scenario.derived);
  if (spec.check) spec.check(scenario);
}

EngineContext engineContext(const common::Scenario& scenario, std::uint32_t supernode) {
  std::vector<common::SensorCoverage> coverage;
  if (scenario.sensor_model.settings) coverage = scenario.sensor_model.settings->coverage(scenario);
  std::shared_ptr<const common::Terrain> terrain;
  if (!scenario.terrain.empty()) terrain = std::make_shared<const common::Terrain>(scenario.terrain);
  const double region_mean = common::meanSensedProbability(coverage, scenario.region, terrain.get());
  if (scenario.supernodes.size() > 1 && !coverage.empty()) {
    // A supernode hears only its tracking group, the sensors the network model routes to it (Oh
    // §V: g(i), the supernode nearest the sensor's true position). Scanning the others would
    // charge its tracks misses for what only they see.
    const common::SensorLayout layout(common::sensorFieldConfig(scenario));
    std::erase_if(coverage, [&](const common::SensorCoverage& sensor) {
      return nearestSupernode(scenario.supernodes, layout.truePosition(sensor.sensor)) != supernode;
    });
  }
  return {scenario.tracker.engine,
          supernode,
          scenario.region,
          scenario.run.seed,
          scenario.dynamics,
          scenario.sensors.spacing,
          scenario.tracker.window_size,
          scenario.tracker.params,
          std::move(coverage),
          std::move(terrain),
          region_mean};
}

std::unique_ptr<Engine> makeEngine(const EngineContext& context) {
  return engineRegistry().at(context.engine).create(context);
}

void requireAccepted(const EngineSpec& engine, const common::Observation& observation) {
  const std::string_view kind = common::measurementKindName(observation.measurement.kind());
  if (std::find(engine.accepts.begin(), engine.accepts.end(), kind) != engine.accepts.end()) return;
  std::string accepted;
  for (const auto& a : engine.accepts) accepted += (accepted.empty() ? "" : ", ") + a;
  throw std::logic_error("engine '" + engine.name + "' was handed a measurement of kind '" + std::string(kind) +
                         "' (sensor " + std::to_string(observation.sensor) + ", tick " +
                         std::to_string(observation.tick_generated) + ") but accepts only: " + accepted +
                         "; the scenario check should have rejected this sensor model for it");
}

std::uint32_t acceptedKindMask(const EngineSpec& engine) {
  std::uint32_t mask = 0;
  for (const auto& name : engine.accepts)
    if (const auto kind = common::measurementKindNamed(name)) mask |= 1u << static_cast<unsigned>(*kind);
  return mask;
}

}  // namespace wsn::supernode

// Helpers shared by the supernode tests: scenarios built by value and noise-free observations.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "common/messages.hpp"
#include "common/scenario_config.hpp"
#include "common/scenario_error.hpp"
#include "supernode/engine.hpp"
#include "supernode/supernode_tracker.hpp"

namespace wsn::supernode::test {

/// A scenario with one supernode at the centre and resolved "gnn" defaults.
inline common::Scenario gnnScenario(std::int32_t window_size = 10) {
  common::Scenario s;
  s.source_path = "test.yaml";
  s.supernodes = {{50.0, 50.0}};
  s.tracker.engine = "gnn";
  s.tracker.window_size = window_size;
  resolveEngineParams(s, wsn::common::kNoStatistics);
  return s;
}

/// The tracker of supernode `index` of `scenario`, its parameters resolved first as the launcher
/// resolves them (a bad engine or parameter throws common::ScenarioError).
inline SupernodeTracker trackerFor(common::Scenario scenario, std::uint32_t index) {
  resolveEngineParams(scenario, wsn::common::kNoStatistics);
  return SupernodeTracker(supernodeConfig(scenario, index));
}

/// Row-major sensor id of the grid cell holding (x, y) on a 100 x 100 grid of spacing 1.
inline common::SensorId sensorAt(double x, double y) {
  return static_cast<common::SensorId>(std::floor(y)) * 100u + static_cast<common::SensorId>(std::floor(x));
}

/// An observation of (x, y) generated at `generated`, delivered at `delivered`.
inline common::Observation observation(std::int32_t generated, std::int32_t delivered, double x, double y,
                                       common::TargetId target = 0) {
  return common::Observation{generated, delivered, sensorAt(x, y), x, y, target};
}

}  // namespace wsn::supernode::test

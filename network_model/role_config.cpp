#include "network_model/role_config.hpp"

namespace wsn::network_model {

TopologyConfig topologyConfig(const common::Scenario& scenario) {
  TopologyConfig config;
  config.supernodes = scenario.supernodes;
  config.communication_range = scenario.network.communication_range;
  return config;
}

RouterConfig routerConfig(const common::Scenario& scenario) {
  RouterConfig config;
  config.pte = scenario.network.pte;
  config.pde = scenario.network.pde;
  config.run_ticks = scenario.run.ticks;
  config.window_size = scenario.tracker.window_size;
  config.seed = scenario.run.seed;
  // A run without faults keeps the empty plan, whatever its shape: nothing in it differs.
  if (!scenario.faults.empty())
    config.faults = common::FaultPlan(scenario.faults, scenario.run.node_processes,
                                      static_cast<std::int32_t>(scenario.supernodes.size()));
  return config;
}

}  // namespace wsn::network_model

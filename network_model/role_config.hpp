// The role edge of the network model: splits a scenario into the configs its algorithms take,
// so that Router and Topology never see the whole scenario. Pure (no DDS), so tests can use it.
#pragma once

#include "common/scenario_config.hpp"
#include "network_model/router.hpp"
#include "network_model/topology.hpp"

namespace wsn::network_model {

/// scenario.supernodes and network.communication_range.
TopologyConfig topologyConfig(const common::Scenario& scenario);

/// network.pte and pde, run.ticks and seed, and tracker.window_size (for the beyond_window count).
RouterConfig routerConfig(const common::Scenario& scenario);

}  // namespace wsn::network_model

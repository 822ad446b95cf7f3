// Reading and writing the scenario's `faults:` list (common/faults.hpp): each item's keys checked against its
// action, its tick against the run, its process against the cluster, and the list as a whole
// against the rule that some supernode is live at every tick. Internal to wsn_scenario.
#pragma once

#include <string>
#include <vector>

#include "common/config/yaml_reader.hpp"
#include "common/scenario_config.hpp"

namespace wsn::scenario {

/// Reads `faults:` into s.faults; needs s.run and s.supernodes read first.
void readFaults(const common::config::Reader& r, const common::config::Section& top, common::Scenario& s);

/// The `faults:` section of the resolved scenario.yaml, each item with the keys of its action
/// only; "" when there are none, so that a scenario without faults reads as before.
std::string faultsYaml(const std::vector<common::FaultSpec>& faults);

}  // namespace wsn::scenario

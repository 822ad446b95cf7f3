// The network-model role: routes every tile's reports to the supernodes with loss and delay.
#pragma once

#include "common/dds/role_runtime.hpp"

namespace wsn::network_model {

/// For ticks 1..T: collects one ReportBatch per tile, applies loss and delay (Oh §V, eq. 7),
/// publishes one DeliveryBatch per supernode, and writes observations.csv and network.json.
void runNetworkRole(const dds::RoleContext& context);

}  // namespace wsn::network_model

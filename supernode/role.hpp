// The supernode role: one tracking group's sliding-window tracker, in lockstep over DDS.
#pragma once

#include "common/dds/role_runtime.hpp"

namespace wsn::supernode {

/// For ticks 1..T: takes its DeliveryBatch of tick t and every other supernode's handoffs of
/// tick t-1, steps the engine, and publishes its TrackBatch and HandoffBatch of tick t.
void runSupernodeRole(const dds::RoleContext& context);

}  // namespace wsn::supernode

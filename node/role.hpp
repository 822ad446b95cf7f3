// The sensor-node role: one tile of sensors per process, in lockstep over DDS.
#pragma once

#include "common/dds/role_runtime.hpp"

namespace wsn::node {

/// Runs tile context.index for ticks 1..T: detect, exchange boundary readings with the other
/// tiles, fuse (Oh eq. 5-6) and publish one ReportBatch per tick. Throws on failure.
void runNodeRole(const dds::RoleContext& context);

}  // namespace wsn::node

// The aggregator role: merges the supernodes' tracks into global tracks and scores the run.
#pragma once

#include "common/dds/role_runtime.hpp"

namespace wsn::aggregator {

/// For ticks 1..T: takes one TrackBatch per supernode, merges them, publishes the
/// GlobalTrackBatch, and writes tracks.csv, tracks_supernode.csv and metrics.json.
void runAggregatorRole(const dds::RoleContext& context);

}  // namespace wsn::aggregator

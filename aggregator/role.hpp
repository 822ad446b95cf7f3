// The aggregator role: associates the supernodes' tracks into global tracks (aggregator.association)
// and scores the run.
#pragma once

#include "common/dds/role_runtime.hpp"

namespace wsn::aggregator {

/// For ticks 1..T: takes one TrackBatch per supernode, associates them, publishes the
/// GlobalTrackBatch, the tick's TickMetrics and its TickDone, and writes tracks.csv, tracks_supernode.csv,
/// metrics_per_tick.csv and, at the end, metrics.json.
void runAggregatorRole(const dds::RoleContext& context);

}  // namespace wsn::aggregator

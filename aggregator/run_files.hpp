// The aggregator's run-directory formats: the rows of tracks.csv and tracks_supernode.csv. Pure, so
// the role only moves data and the formats are unit-tested (metrics.json and metrics_per_tick.csv
// come from the metric registry, aggregator/run_scorer.hpp).
#pragma once

#include <cstdint>
#include <string>

#include "common/messages.hpp"

namespace wsn::aggregator {

/// The header of tracks.csv: tick, then the track columns (id, readable label, state, the upper
/// triangle of the covariance over x, y, vx, vy).
std::string globalTracksCsvHeader();
/// The header of tracks_supernode.csv: tick, supernode, then the track columns.
std::string supernodeTracksCsvHeader();

/// One row of tracks.csv (state with 6 decimals, covariance with 9 significant digits).
std::string globalTrackCsvRow(std::int32_t tick, const common::TrackEstimate& track);
/// One row of tracks_supernode.csv, as supernode `supernode` published the track.
std::string supernodeTrackCsvRow(std::int32_t tick, std::uint32_t supernode, const common::TrackEstimate& track);

}  // namespace wsn::aggregator

// Scores a run from its per-tick (truth, global tracks): the single entry point the aggregator
// uses for every metric of metrics.json and metrics_per_tick.csv (docs/METRICS.md).
//
// Each metric stays in its own module (metrics.hpp: εK, εX, OSPA; gospa.hpp; clear_mot.hpp;
// track_quality.hpp; boundary.hpp); this only feeds them the same tick and lays out the files.
// Tracks with a non-finite field are dropped once, here, so every metric scores the same K_t
// (MetricsAccumulator still counts them in tracks_ignored_nonfinite).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "aggregator/boundary.hpp"
#include "aggregator/clear_mot.hpp"
#include "aggregator/gospa.hpp"
#include "aggregator/metrics.hpp"
#include "aggregator/track_quality.hpp"
#include "common/geometry.hpp"
#include "common/messages.hpp"
#include "common/scenario.hpp"
#include "common/truth.hpp"

namespace wsn::aggregator {

/// The scores of one tick, as metrics_per_tick.csv and the TickMetrics topic carry them.
struct TickScores {
  std::int32_t tick = 0;
  std::int64_t truth_targets = 0;  ///< K*_t
  std::int64_t tracks = 0;  ///< K_t, finite tracks
  double ospa = 0.0;
  GospaResult gospa;  ///< distance and its three parts (units of distance^p)
  double eps_k_running = 0.0;  ///< Oh eq. (9) over the ticks added so far
  double ospa_mean_running = 0.0;
};

/// Everything a run scored, with the settings each metric used.
struct RunScores {
  MetricsSummary metrics;
  double gospa_c = 0.0;
  double gospa_p = 0.0;
  GospaMean gospa;
  double mot_threshold = 0.0;
  ClearMotSummary clear_mot;
  double quality_gate = 0.0;
  TrackQualitySummary track_quality;
  BoundarySummary boundary;
};

/// Feeds every metric tick by tick.
class RunScorer {
 public:
  /// `supernodes` are the scenario's, for the boundary split. Throws std::invalid_argument on
  /// settings a metric rejects (see each module).
  RunScorer(const common::MetricsConfig& config, std::vector<common::Vec2> supernodes);

  /// Scores tick `tick`; ticks must increase strictly (else std::invalid_argument, nothing
  /// recorded). The order of either vector does not matter.
  TickScores add(std::int32_t tick, const std::vector<common::TargetState>& truth,
                 const std::vector<common::TrackEstimate>& tracks);

  /// The run's scores over every tick added.
  RunScores finish() const;

 private:
  common::MetricsConfig config_;
  MetricsAccumulator metrics_;
  ClearMotAccumulator clear_mot_;
  TrackQualityAccumulator quality_;
  BoundaryAccumulator boundary_;
  std::vector<GospaResult> gospa_;
  bool any_tick_ = false;
  std::int32_t last_tick_ = 0;
};

/// The header of metrics_per_tick.csv; a plotting script reads these exact names.
inline constexpr const char* kPerTickCsvHeader =
    "tick,truth_targets,tracks,ospa,gospa,gospa_localisation,gospa_missed,gospa_false";

/// One metrics_per_tick.csv row (reals with 6 decimals), without the newline.
std::string perTickCsvRow(const TickScores& scores);

/// What metrics.json says about the run besides its scores.
struct RunInfo {
  std::string scenario;
  std::uint64_t seed = 0;
  std::int32_t ticks = 0;
  std::string engine;
  std::int32_t truth_targets = 0;
  std::uint64_t observations_dropped_stale = 0;
  std::string association = "gated";  ///< the aggregator's track association (aggregator.association)
  std::string provenance_json;        ///< common::provenanceJson of the run; omitted when empty
};

/// The whole metrics.json text. The "provenance" and "timing" blocks are last and one line each:
/// they are the only parts that differ between equal runs, and the determinism test drops exactly
/// those two lines.
std::string metricsJson(const RunInfo& info, const RunScores& scores, double wall_s, double ticks_per_s);

}  // namespace wsn::aggregator

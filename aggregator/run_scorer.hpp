// Scores one track stream of a run against ground truth with every registered metric
// (aggregator/metric/), and lays out metrics.json and metrics_per_tick.csv (docs/METRICS.md).
//
// A stream is one sequence of track estimates of the run: "live" is what the aggregator publishes
// at each tick; another (a settled, smoothed estimate) gets its own RunScorer with its own name and
// is written under metrics.json's "streams" key, so the same metric code scores both.
// Tracks with a non-finite field are dropped once, here, so every metric scores the same K_t.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "aggregator/metric/metric.hpp"
#include "common/geometry.hpp"
#include "common/messages.hpp"
#include "common/scenario_config.hpp"
#include "common/truth.hpp"

namespace wsn::aggregator {

/// The stream whose scores sit at the top level of metrics.json, as before there were streams.
inline constexpr const char* kLiveStream = "live";
/// The settled (fixed-lag, smoothed) estimate of each tick once it left the supernodes' windows;
/// under metrics.json's "streams" → "settled".
inline constexpr const char* kSettledStream = "settled";

/// The scores of one tick of one stream.
struct TickScores {
  std::int32_t tick = 0;
  std::vector<NamedValue> columns;  ///< metrics_per_tick.csv's cells after "tick", in header order
  std::vector<NamedValue> live_only;  ///< live values that are not columns (running scores)

  /// What the TickMetrics topic carries: every column, then the live-only values.
  std::vector<NamedValue> live() const;
  /// The column or live value called `name`.
  std::optional<double> find(std::string_view name) const;
};

/// Everything one stream of a run scored, metric by metric in registration order.
struct RunScores {
  std::string stream;
  std::vector<std::pair<std::string, MetricReport>> reports;

  /// The summary of the metric called `name` (its metrics.json block); throws std::out_of_range.
  const Json& at(const std::string& name) const;
};

/// Feeds every metric of a registry the same ticks of one stream.
class RunScorer {
 public:
  /// `supernodes` are the scenario's, for the boundary split. Throws std::invalid_argument on
  /// settings a metric rejects, std::logic_error when two metrics claim the same column.
  RunScorer(std::string stream, const common::MetricsConfig& config, const std::vector<common::Vec2>& supernodes,
            const MetricRegistry& metrics = metricRegistry());

  /// Scores tick `tick`; ticks must increase strictly (else std::invalid_argument, nothing
  /// recorded). The order of either vector does not matter.
  TickScores add(std::int32_t tick, const std::vector<common::TargetState>& truth,
                 const std::vector<common::TrackEstimate>& tracks);

  /// The run's scores over every tick added.
  RunScores finish() const;

  const std::string& stream() const { return stream_; }

  /// The header of metrics_per_tick.csv: "tick", then every metric's columns in registration
  /// order (tools/plot_run.py and tools/sweep.py read these names).
  std::string csvHeader() const;
  /// One row under csvHeader() (counts whole, reals with 6 decimals), without the newline.
  std::string csvRow(const TickScores& scores) const;

 private:
  struct Entry {
    std::string name;
    std::unique_ptr<Metric> metric;
    std::size_t columns = 0;
  };

  std::string stream_;
  std::vector<Entry> metrics_;
  std::vector<Column> columns_;
  bool any_tick_ = false;
  std::int32_t last_tick_ = 0;
};

/// What metrics.json says about the run besides its scores.
struct RunInfo {
  std::string scenario;
  std::uint64_t seed = 0;
  std::int32_t ticks = 0;
  std::string engine;
  std::int32_t truth_targets = 0;
  std::uint64_t observations_dropped_stale = 0;
  std::string association = "gated";  ///< the aggregator's track association (aggregator.association)
  std::string provenance_json;        ///< common::provenanceJson of the run (one line); omitted when empty
  Json faults{};                      ///< what the scenario's faults did (FaultReport); null: none, omitted
};

/// The whole metrics.json text. The "live" stream's headline and metric blocks are at the top
/// level; every other stream is under "streams" → name, with the same keys. The "provenance" and
/// "timing" blocks are last and one line each: they are the only parts that differ between equal
/// runs, and the determinism tests drop exactly those two lines.
std::string metricsJson(const RunInfo& info, const std::vector<RunScores>& streams, double wall_s, double ticks_per_s);

/// metricsJson of a run scored on its live stream only.
inline std::string metricsJson(const RunInfo& info, const RunScores& live, double wall_s, double ticks_per_s) {
  return metricsJson(info, std::vector<RunScores>{live}, wall_s, ticks_per_s);
}

}  // namespace wsn::aggregator

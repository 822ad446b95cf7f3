// The metric plugin interface: what each metric of metrics.json, metrics_per_tick.csv and the
// TickMetrics topic implements, and the registry that lists them (docs/METRICS.md, "How to add a metric").
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/geometry.hpp"
#include "common/messages.hpp"
#include "common/registry.hpp"
#include "common/scenario_config.hpp"
#include "common/truth.hpp"

namespace wsn::aggregator {

/// JSON that keeps insertion order: the launcher's summary reads the first occurrence of a key,
/// so the order of metrics.json is part of its interface.
using Json = nlohmann::ordered_json;

/// One tick of one track stream, the same for every metric.
struct MetricTick {
  std::int32_t tick = 0;
  const std::vector<common::TargetState>& truth;
  /// Finite tracks only: dropped once, by RunScorer, so that every metric scores the same K_t.
  const std::vector<common::TrackEstimate>& tracks;
  std::int64_t tracks_dropped_nonfinite = 0;  ///< how many tracks of this tick were dropped
};

/// A number of one tick under its name: a metrics_per_tick.csv cell or a TickMetrics value.
struct NamedValue {
  std::string name;
  double value = 0.0;
};

/// A metrics_per_tick.csv column. Counts are written as whole numbers, reals with 6 decimals.
struct Column {
  std::string name;
  bool whole = false;
};

/// What a metric says about one tick.
struct MetricTickValues {
  std::vector<double> columns;  ///< one per Metric::columns(), in that order
  /// Values published live but not written per tick (running scores); the columns go out live too.
  std::vector<NamedValue> live;
};

/// What a metric says about the whole run.
struct MetricReport {
  Json summary;  ///< the value of metrics.json's key named after the metric
  /// Keys a stream's block starts with, ahead of every metric's summary (today εK, εX and mean
  /// OSPA, which tools/sweep.py and the launcher read at the top level).
  Json headline = Json::object();
};

/// One metric's state over the run of one track stream.
class Metric {
 public:
  virtual ~Metric() = default;

  /// This metric's metrics_per_tick.csv columns, fixed for the run (the header is written first).
  virtual std::vector<Column> columns() const { return {}; }

  /// Scores one tick. RunScorer guarantees strictly increasing ticks.
  virtual MetricTickValues add(const MetricTick& tick) = 0;

  /// The run's scores over every tick added.
  virtual MetricReport finish() const = 0;
};

/// One number of a run's metrics.json that sweeps tabulate and plot, as the catalogue
/// (`wsntrack components --json`) describes it to the Python side and to figures.
struct MetricQuantity {
  std::string name;   ///< a sweep's metric name (eps_k)
  std::string title;  ///< its column title in a sweep's tables (eps_K)
  std::string label;  ///< a figure's axis label ("εK (Oh eq. 9)")
  std::string unit;   ///< "" for a ratio or a count
  /// Keys from the top of a stream's block in metrics.json (the live stream's block is the file
  /// itself; the settled stream's is streams.settled).
  std::vector<std::string> path;
  /// Keys of the flag that says whether the run defines it; empty when it always does.
  std::vector<std::string> defined;
  std::string meaning;
};

/// A registered metric. Its name is its key in metrics.json.
struct MetricSpec {
  std::string name;
  std::string description;
  std::vector<std::string> settings;  ///< the keys of the scenario's `metrics` section it reads
  /// Makes a fresh accumulator; `supernodes` are the scenario's. Throws std::invalid_argument on
  /// settings it rejects, so that a bad scenario fails before the run rather than at its end.
  std::function<std::unique_ptr<Metric>(const common::MetricsConfig& config,
                                        const std::vector<common::Vec2>& supernodes)>
      create;
  std::vector<MetricQuantity> quantities;  ///< what of its block a sweep can tabulate
};

using MetricRegistry = common::Registry<MetricSpec>;

/// Every metric of a run, in the order of metrics.json's blocks and metrics_per_tick.csv's columns
/// (aggregator/metric/registry.cpp).
const MetricRegistry& metricRegistry();

}  // namespace wsn::aggregator

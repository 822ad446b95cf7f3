// The list of every metric of a run. Adding a metric: a new file in this folder that defines
// `MetricSpec fooMetric()`, and its line below (docs/METRICS.md, "How to add a metric").
#include "aggregator/metric/metric.hpp"

namespace wsn::aggregator {

// Each defined in the file of this folder named after it. Declared here rather than in a header
// so that a metric adds nothing outside its own file but its registration line.
MetricSpec ohOspaMetric();
MetricSpec gospaMetric();
MetricSpec clearMotMetric();
MetricSpec trackQualityMetric();
MetricSpec boundaryMetric();
MetricSpec classificationMetric();
MetricSpec stopModeMetric();

const MetricRegistry& metricRegistry() {
  // The order is that of metrics.json's blocks and of metrics_per_tick.csv's columns, which
  // tools/plot_run.py and tools/sweep.py read: append, do not insert.
  static const MetricRegistry registry("metric", {
      ohOspaMetric(),
      gospaMetric(),
      clearMotMetric(),
      trackQualityMetric(),
      boundaryMetric(),
      classificationMetric(),
      stopModeMetric(),
  });
  return registry;
}

}  // namespace wsn::aggregator

// Plugin of CLEAR-MOT (aggregator/clear_mot.hpp): metrics.json's "clear_mot" block.
#include <memory>

#include "aggregator/clear_mot.hpp"
#include "aggregator/metric/metric.hpp"

namespace wsn::aggregator {
namespace {

class ClearMotMetric final : public Metric {
 public:
  explicit ClearMotMetric(double threshold) : threshold_(threshold), clear_mot_(threshold) {}

  MetricTickValues add(const MetricTick& tick) override {
    clear_mot_.add(tick.tick, tick.truth, tick.tracks);
    return {};
  }

  MetricReport finish() const override {
    const ClearMotSummary m = clear_mot_.summary();
    return {Json{{"threshold", threshold_},
                 {"mota", m.mota},
                 {"mota_defined", m.mota_defined},
                 {"motp", m.motp},
                 {"motp_defined", m.motp_defined},
                 {"id_switches", m.id_switches},
                 {"fragmentations", m.fragmentations},
                 {"misses", m.misses},
                 {"false_positives", m.false_positives},
                 {"matches", m.matches},
                 {"ground_truth", m.ground_truth}}};
  }

 private:
  double threshold_;
  ClearMotAccumulator clear_mot_;
};

}  // namespace

MetricSpec clearMotMetric() {
  return {"clear_mot", "CLEAR-MOT: MOTA, MOTP, identity switches, fragmentations, misses, false positives",
          {"mot_threshold"},
          [](const common::MetricsConfig& config, const std::vector<common::Vec2>&) -> std::unique_ptr<Metric> {
            return std::make_unique<ClearMotMetric>(config.mot_threshold);
          }};
}

}  // namespace wsn::aggregator

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
          },
          {{"mota", "MOTA", "MOTA", "", {"clear_mot", "mota"}, {"clear_mot", "mota_defined"},
            "multiple-object tracking accuracy, 1 − (misses + false positives + identity switches) / targets"},
           {"motp", "MOTP", "MOTP", "separations", {"clear_mot", "motp"}, {"clear_mot", "motp_defined"},
            "mean distance of the matched track-target pairs"},
           {"id_switches", "ID switches", "identity switches", "", {"clear_mot", "id_switches"}, {},
            "CLEAR-MOT identity switches"},
           {"fragmentations", "fragmentations", "fragmentations", "", {"clear_mot", "fragmentations"}, {},
            "times a target's track was interrupted"}}};
}

}  // namespace wsn::aggregator

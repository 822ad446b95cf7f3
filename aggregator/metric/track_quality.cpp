// Plugin of the per-target track quality RSE, TLR (of duration and of path length) and <dx>
// (aggregator/track_quality.hpp): metrics.json's "track_quality" block.
#include <memory>

#include "aggregator/metric/metric.hpp"
#include "aggregator/track_quality.hpp"

namespace wsn::aggregator {
namespace {

class TrackQualityMetric final : public Metric {
 public:
  explicit TrackQualityMetric(double gate) : gate_(gate), quality_(gate) {}

  MetricTickValues add(const MetricTick& tick) override {
    quality_.add(tick.truth, tick.tracks);
    return {};
  }

  MetricReport finish() const override {
    const TrackQualitySummary q = quality_.summary();
    Json targets = Json::array();
    for (const TargetQuality& t : q.targets)
      targets.push_back(Json{{"id", t.id},
                             {"ticks_alive", t.ticks_alive},
                             {"ticks_associated", t.ticks_associated},
                             {"errors_defined", t.errors_defined},
                             {"rse_position", t.rse_position},
                             {"rse_velocity", t.rse_velocity},
                             {"tlr", t.tlr},
                             {"path_length", t.path_length},
                             {"path_length_associated", t.path_length_associated},
                             {"tlr_length", t.tlr_length},
                             {"mean_position_error", t.mean_position_error}});
    return {Json{{"gate", gate_},
                 {"means_defined", q.means_defined},
                 {"mean_rse_position", q.mean_rse_position},
                 {"mean_rse_velocity", q.mean_rse_velocity},
                 {"mean_tlr", q.mean_tlr},
                 {"mean_tlr_length", q.mean_tlr_length},
                 {"mean_position_error", q.mean_position_error},
                 {"false_track_ticks", q.false_track_ticks},
                 {"targets", std::move(targets)}}};
  }

 private:
  double gate_;
  TrackQualityAccumulator quality_;
};

}  // namespace

MetricSpec trackQualityMetric() {
  return {"track_quality",
          "per-target RSE of position and velocity, TLR (duration and path length) and <dx>, and their run means",
          {"quality_gate"},
          [](const common::MetricsConfig& config, const std::vector<common::Vec2>&) -> std::unique_ptr<Metric> {
            return std::make_unique<TrackQualityMetric>(config.quality_gate);
          },
          {{"tlr", "TLR", "TLR (Pannetier et al. 2014, §V)", "", {"track_quality", "mean_tlr"},
            {"track_quality", "means_defined"},
            "track length ratio A_j / L_j (associated over alive ticks), averaged over the targets"},
           {"tlr_length", "TLR length", "TLR by path length", "", {"track_quality", "mean_tlr_length"},
            {"track_quality", "means_defined"},
            "track length ratio by path length P^A_j / P_j, averaged over the targets"},
           {"position_error", "<dx>", "⟨dx⟩ (An et al. 2014, §5.2)", "separations", {"track_quality", "mean_position_error"},
            {"track_quality", "means_defined"}, "mean position error of the associated ticks, averaged over the targets"}}};
}

}  // namespace wsn::aggregator

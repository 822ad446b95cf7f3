// Plugin of GOSPA, alpha = 2 (aggregator/gospa.hpp): metrics.json's "gospa" block (means over the
// ticks) and the gospa, gospa_localisation, gospa_missed and gospa_false columns.
#include <memory>

#include "aggregator/gospa.hpp"
#include "aggregator/metric/metric.hpp"

namespace wsn::aggregator {
namespace {

class GospaMetric final : public Metric {
 public:
  explicit GospaMetric(const common::MetricsConfig& config) : c_(config.gospa_c), p_(config.gospa_p) {
    // gospaDistance checks c and p only when called; fail at construction like the others.
    (void)gospaDistance({}, {}, c_, p_);
  }

  std::vector<Column> columns() const override {
    return {{"gospa"}, {"gospa_localisation"}, {"gospa_missed"}, {"gospa_false"}};
  }

  MetricTickValues add(const MetricTick& tick) override {
    std::vector<common::Vec2> truth, tracks;
    truth.reserve(tick.truth.size());
    tracks.reserve(tick.tracks.size());
    for (const auto& target : tick.truth) truth.push_back({target.x, target.y});
    for (const auto& track : tick.tracks) tracks.push_back({track.x, track.y});
    const GospaResult& g = per_tick_.emplace_back(gospaDistance(truth, tracks, c_, p_));
    return {{g.distance, g.localisation, g.missed, g.false_targets}, {}};
  }

  MetricReport finish() const override {
    const GospaMean g = meanGospa(per_tick_);
    return {Json{{"c", c_},
                 {"p", p_},
                 {"alpha", 2},
                 {"ticks", g.ticks},
                 {"mean", g.distance},
                 {"localisation", g.localisation},
                 {"missed", g.missed},
                 {"false", g.false_targets},
                 {"missed_targets", g.missed_targets},
                 {"false_tracks", g.false_tracks}}};
  }

 private:
  double c_;
  double p_;
  std::vector<GospaResult> per_tick_;
};

}  // namespace

MetricSpec gospaMetric() {
  return {"gospa", "GOSPA (alpha = 2) per tick with its localisation, missed and false parts, and their means",
          {"gospa_c", "gospa_p"},
          [](const common::MetricsConfig& config, const std::vector<common::Vec2>&) -> std::unique_ptr<Metric> {
            return std::make_unique<GospaMetric>(config);
          },
          {{"gospa", "GOSPA", "mean GOSPA", "separations", {"gospa", "mean"}, {},
            "GOSPA (alpha = 2) averaged over the ticks"}}};
}

}  // namespace wsn::aggregator

// Plugin of εK (Oh eq. 9), εX (eq. 10) and OSPA (aggregator/metrics.hpp): metrics.json's "metrics"
// block, the headline eps_k, eps_x, eps_x_gated and ospa, and the truth_targets, tracks and ospa columns.
#include <memory>

#include "aggregator/metric/metric.hpp"
#include "aggregator/metrics.hpp"

namespace wsn::aggregator {
namespace {

Json toJson(const MetricsSummary& s) {
  return Json{{"ticks_scored", s.ticks_scored},
              {"first_tick", s.first_tick},
              {"last_tick", s.last_tick},
              {"eps_k", s.eps_k},
              {"eps_k_defined", s.eps_k_defined},
              {"eps_x", s.eps_x},
              {"eps_x_defined", s.eps_x_defined},
              {"eps_x_gated", s.eps_x_gated},
              {"eps_x_gated_defined", s.eps_x_gated_defined},
              {"eps_x_gate", s.eps_x_gate},
              {"mean_k", s.mean_k},
              {"mean_k_true", s.mean_k_true},
              {"sum_k", s.sum_k},
              {"sum_k_true", s.sum_k_true},
              {"sum_abs_k_error", s.sum_abs_k_error},
              {"sum_matches", s.sum_matches},
              {"sum_squared_position_error", s.sum_squared_position_error},
              {"sum_matches_gated", s.sum_matches_gated},
              {"sum_squared_position_error_gated", s.sum_squared_position_error_gated},
              {"ospa_c", s.ospa_c},
              {"ospa_p", s.ospa_p},
              {"ospa_mean", s.ospa_mean},
              {"ospa_per_tick", s.ospa_per_tick},
              {"track_ids", s.track_ids},
              {"tracks_ignored_nonfinite", s.tracks_ignored_nonfinite}};
}

class OhOspaMetric final : public Metric {
 public:
  explicit OhOspaMetric(const common::MetricsConfig& config) : metrics_(config) {}

  std::vector<Column> columns() const override { return {{"truth_targets", true}, {"tracks", true}, {"ospa"}}; }

  MetricTickValues add(const MetricTick& tick) override {
    // The accumulator counts non-finite tracks itself, but RunScorer has already dropped them.
    dropped_nonfinite_ += tick.tracks_dropped_nonfinite;
    const MetricsTick t = metrics_.add(tick.tick, tick.truth, tick.tracks);
    return {{static_cast<double>(t.k_true), static_cast<double>(t.k), t.ospa},
            {{"eps_k_running", t.eps_k_running}, {"ospa_mean_running", t.ospa_mean_running}}};
  }

  MetricReport finish() const override {
    MetricsSummary s = metrics_.finish();
    s.tracks_ignored_nonfinite += dropped_nonfinite_;
    return {toJson(s), Json{{"eps_k", s.eps_k}, {"eps_x", s.eps_x}, {"eps_x_gated", s.eps_x_gated}, {"ospa", s.ospa_mean}}};
  }

 private:
  MetricsAccumulator metrics_;
  std::int64_t dropped_nonfinite_ = 0;
};

}  // namespace

MetricSpec ohOspaMetric() {
  return {"metrics", "Oh et al. eq. 9 (eps_K) and eq. 10 (eps_X, and eps_X gated), OSPA per tick and its mean",
          {"eps_x_gate", "ospa_c", "ospa_p"},
          [](const common::MetricsConfig& config, const std::vector<common::Vec2>&) -> std::unique_ptr<Metric> {
            return std::make_unique<OhOspaMetric>(config);
          },
          {{"eps_k", "eps_K", "εK (Oh eq. 9)", "", {"eps_k"}, {"metrics", "eps_k_defined"},
            "Σ|K*_t − K_t| / Σ K*_t: the error of the number of tracks"},
           {"eps_x", "eps_X", "εX (Oh eq. 10)", "separations", {"eps_x"}, {"metrics", "eps_x_defined"},
            "the rms distance of the matched track-target pairs"},
           {"eps_x_gated", "eps_X gated", "εX gated (Oh eq. 10)", "separations", {"metrics", "eps_x_gated"},
            {"metrics", "eps_x_gated_defined"}, "εX over the matches closer than metrics.eps_x_gate"},
           {"ospa", "OSPA", "mean OSPA", "separations", {"ospa"}, {}, "OSPA (c = metrics.ospa_c, p = metrics.ospa_p) "
            "averaged over the scored ticks"}}};
}

}  // namespace wsn::aggregator

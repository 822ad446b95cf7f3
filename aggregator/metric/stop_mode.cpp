// Plugin of the stop-mode score of a run (ONERA §III-B, eq. 4; docs/ONERA.md §4): over the
// target-track pairs of track_quality's per-tick unique assignment, the mean probability the
// track gives its target being stopped, while the target stands still and while it moves.
#include <array>
#include <cstdint>
#include <map>
#include <memory>

#include "aggregator/metric/metric.hpp"
#include "aggregator/track_quality.hpp"

namespace wsn::aggregator {
namespace {

class StopModeMetric final : public Metric {
 public:
  explicit StopModeMetric(double gate) : gate_(gate) {}

  MetricTickValues add(const MetricTick& tick) override {
    const auto assignment = associateTargetsWithTracks(tick.truth, tick.tracks, gate_);
    for (std::size_t i = 0; i < tick.truth.size(); ++i) {
      if (assignment[i] < 0) continue;
      const common::TargetState& target = tick.truth[i];
      const auto& track = tick.tracks[static_cast<std::size_t>(assignment[i])];
      // A scripted stop sets the velocity to zero exactly; every moving truth has some speed.
      Sums& sums = targets_[target.id][target.vx == 0.0 && target.vy == 0.0 ? kStopped : kMoving];
      if (!track.stop_probability) {
        ++sums.unknown;
        continue;
      }
      ++sums.ticks;
      sums.probability += *track.stop_probability;
    }
    return {};
  }

  MetricReport finish() const override {
    std::array<Sums, 2> run{};
    Json targets = Json::array();
    for (const auto& [id, by_motion] : targets_) {
      for (std::size_t m = 0; m < 2; ++m) run[m] += by_motion[m];
      targets.push_back(Json{{"id", id},
                             {"ticks_stopped", by_motion[kStopped].ticks},
                             {"mean_stop_probability_stopped", mean(by_motion[kStopped])},
                             {"ticks_moving", by_motion[kMoving].ticks},
                             {"mean_stop_probability_moving", mean(by_motion[kMoving])}});
    }
    return {Json{{"gate", gate_},
                 {"ticks_stopped", run[kStopped].ticks},
                 {"mean_stop_probability_stopped", mean(run[kStopped])},
                 {"ticks_moving", run[kMoving].ticks},
                 {"mean_stop_probability_moving", mean(run[kMoving])},
                 {"ticks_without_stop_model", run[kStopped].unknown + run[kMoving].unknown},
                 {"targets", std::move(targets)}}};
  }

 private:
  /// Associated ticks of one kind (target stopped or moving).
  struct Sums {
    std::int64_t ticks = 0;    ///< with a stop probability
    double probability = 0.0;  ///< its sum over those ticks
    std::int64_t unknown = 0;  ///< whose track gives none (its engine has no stop model)
    Sums& operator+=(const Sums& o) {
      ticks += o.ticks;
      probability += o.probability;
      unknown += o.unknown;
      return *this;
    }
  };
  static constexpr std::size_t kStopped = 0;
  static constexpr std::size_t kMoving = 1;

  /// The mean probability; null when no tick had one.
  static Json mean(const Sums& s) {
    if (s.ticks == 0) return Json();
    return s.probability / static_cast<double>(s.ticks);
  }

  double gate_;
  std::map<common::TargetId, std::array<Sums, 2>> targets_;
};

}  // namespace

MetricSpec stopModeMetric() {
  return {"stop_mode",
          "the mean probability a track gives its target being stopped (the IMM's stop model), over "
          "track_quality's unique assignment, while the target stands still and while it moves",
          {"quality_gate"},
          [](const common::MetricsConfig& config, const std::vector<common::Vec2>&) -> std::unique_ptr<Metric> {
            return std::make_unique<StopModeMetric>(config.quality_gate);
          },
          {{"stop_probability_stopped", "P(stop) stopped", "mean stop probability while stopped", "",
            {"stop_mode", "mean_stop_probability_stopped"}, {},
            "the mean probability a track gives its target being stopped, over the ticks it stands still"},
           {"stop_probability_moving", "P(stop) moving", "mean stop probability while moving", "",
            {"stop_mode", "mean_stop_probability_moving"}, {},
            "the mean probability a track gives its target being stopped, over the ticks it moves"}}};
}

}  // namespace wsn::aggregator

// Plugin of the boundary/interior split of tracking errors (aggregator/boundary.hpp):
// metrics.json's "boundary" block.
#include <memory>
#include <utility>

#include "aggregator/boundary.hpp"
#include "aggregator/clear_mot.hpp"
#include "aggregator/metric/metric.hpp"

namespace wsn::aggregator {
namespace {

Json toJson(const BoundaryCounts& c) {
  return Json{{"target_ticks", c.target_ticks},
              {"duplicate_track_ticks", c.duplicate_track_ticks},
              {"id_switches", c.id_switches},
              {"fragmentations", c.fragmentations}};
}

class BoundaryMetric final : public Metric {
 public:
  BoundaryMetric(std::vector<common::Vec2> supernodes, double band, double mot_threshold)
      : clear_mot_(mot_threshold), boundary_(std::move(supernodes), band, mot_threshold) {}

  MetricTickValues add(const MetricTick& tick) override {
    // Its own CLEAR-MOT mapping, identical to the clear_mot metric's (same inputs, deterministic),
    // so that this metric depends on no other; the cost is one more small assignment per tick.
    boundary_.add(tick.truth, clear_mot_.add(tick.tick, tick.truth, tick.tracks));
    return {};
  }

  MetricReport finish() const override {
    const BoundarySummary b = boundary_.summary();
    return {Json{{"band", b.band},
                 {"supernodes", b.supernodes},
                 {"mot_threshold", b.mot_threshold},
                 {"boundary", toJson(b.boundary)},
                 {"interior", toJson(b.interior)}}};
  }

 private:
  ClearMotAccumulator clear_mot_;
  BoundaryAccumulator boundary_;
};

}  // namespace

MetricSpec boundaryMetric() {
  return {"boundary",
          "duplicate tracks, identity switches and fragmentations near a tracking-group boundary and inside",
          {"boundary_band", "mot_threshold"},
          [](const common::MetricsConfig& config, const std::vector<common::Vec2>& supernodes) -> std::unique_ptr<Metric> {
            return std::make_unique<BoundaryMetric>(supernodes, config.boundary_band, config.mot_threshold);
          },
          {{"boundary_duplicates", "boundary dup", "duplicate track-ticks near boundaries", "",
            {"boundary", "boundary", "duplicate_track_ticks"}, {}, "ticks a target near a group boundary had two tracks"},
           {"boundary_id_switches", "boundary IDsw", "identity switches near boundaries", "",
            {"boundary", "boundary", "id_switches"}, {},
            "CLEAR-MOT identity switches of targets near a group boundary"},
           {"boundary_fragmentations", "boundary frag", "fragmentations near boundaries", "",
            {"boundary", "boundary", "fragmentations"}, {}, "fragmentations of targets near a group boundary"}}};
}

}  // namespace wsn::aggregator

// Environmental-noise mitigation before tracking (An et al. 2013 §3.3): the persistence test
// (eq. 9-11), the spatial test (eq. 12-14, generalised to several targets) and the centroid-jump
// gate (eq. 15).
#pragma once

#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include "common/geometry.hpp"
#include "supernode/rulebased/clustering.hpp"

namespace wsn::supernode::rulebased {

/// Step 1, eq. (11): f_i,k-2 f_i,k-1 f_i,k = 1. Keeps a detection only when its sensor also
/// detected at each of the previous `ticks - 1` ticks, which removes every noise shorter than
/// `ticks` ticks (0.3 s with the paper's 3 ticks of 0.1 s).
class PersistenceFilter {
 public:
  /// `ticks` >= 1 (1 keeps everything).
  explicit PersistenceFilter(std::int32_t ticks = 3);
  /// Feeds the unfiltered detections of `tick` (ticks increase; a tick never fed counts as a
  /// tick without detections) and returns those that persisted, in input order.
  std::vector<Detection> apply(std::int32_t tick, std::span<const Detection> detections);

 private:
  std::int32_t ticks_;
  struct Past {
    std::int32_t tick;
    std::vector<common::SensorId> sensors;  // sorted
  };
  std::deque<Past> history_;  // the last ticks_ - 1 ticks fed, oldest first
};

/// Step 2, eq. (13)-(14) generalised to several targets. The paper drops sensor j when more
/// than half of the m survivors lie farther than `radius` (3 Ds) from it, i.e. it keeps j when
/// n_j, the number of survivors within `radius` of j (j included), is at least m / 2. That
/// assumes one target: with two targets of equal clusters every sensor has n_j = m / 2 and a
/// third target would be dropped entirely. The rule here keeps j when
///   n_j >= min(m / 2, min_cluster),
/// a density test: a sensor in a group of at least `min_cluster` survivors is kept whatever the
/// number of targets, and with few survivors (m < 2 min_cluster) it is the paper's rule exactly.
/// Returns the kept detections in input order.
std::vector<Detection> spatialFilter(std::span<const Detection> survivors, double radius, std::int32_t min_cluster);

/// Step 3, eq. (15): a measurement is accepted only when it lies within `max_jump` (3 Ds) of the
/// previous one, |d_c,k-1 - d_c,k| <= max_jump.
inline bool withinJump(common::Vec2 previous, common::Vec2 current, double max_jump) {
  return common::squaredDistance(previous, current) <= max_jump * max_jump;
}

}  // namespace wsn::supernode::rulebased

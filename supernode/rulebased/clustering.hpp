// Clustering of detecting sensors and the weighted centroid of each cluster (An et al. 2014
// §3.2, eq. 5-6 and 10): what turns a tick's raw acoustic detections into target measurements.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "common/geometry.hpp"
#include "common/messages.hpp"

namespace wsn::supernode::rulebased {

/// One detecting sensor as the fusion centre sees it: id, believed position, ws = floor(Ps/cs).
struct Detection {
  common::SensorId sensor = 0;
  common::Vec2 position;
  std::int32_t level = 1;
  friend bool operator==(const Detection&, const Detection&) = default;
};

/// A cluster h_a of connected detecting sensors (eq. 6) with its measurement.
struct Cluster {
  std::vector<Detection> members;  ///< sorted by sensor id
  common::Vec2 centroid;           ///< eq. 10: sum ws x_s / sum ws
  common::Vec2 strongest;          ///< position of the member with the largest ws (2013 §3.2)
  double radius = 0.0;             ///< eq. 21: r = sqrt(N) Ds / 2
  std::int32_t size() const { return static_cast<std::int32_t>(members.size()); }
  /// The sensors the cluster stands for: its members, but a fused report (level 0, Oh eq. 6)
  /// already stands for all the sensors that heard its target, so a cluster holding one counts as
  /// large as `full` (the size rules of births and Noise_find are about raw detections).
  std::int32_t evidence(std::int32_t full) const {
    for (const auto& d : members)
      if (d.level <= 0) return std::max(size(), full);
    return size();
  }
};

/// The weight ws of a detection in eq. (10): its level, or 1 for a report without one (a fused
/// Oh report carries level 0), so that the centroid is always defined.
inline double centroidWeight(const Detection& d) { return d.level > 0 ? static_cast<double>(d.level) : 1.0; }

/// Eq. (21): the averaged radius of a cluster of n sensors at separation Ds.
double clusterRadius(std::int32_t sensors, double sensor_spacing);

/// Eq. (5)-(6): single-linkage clusters of the detections, two sensors being connected when
/// their positions are at most `link_distance` apart. On a grid of spacing Ds, any link distance
/// in [sqrt(2) Ds, 2 Ds) connects exactly the 8 neighbours |i_r - i_b| <= 1, |j_r - j_b| <= 1 of
/// eq. (6); on a random layout it is the documented distance-based equivalent. Clusters are
/// numbered as the paper's routine does, from the sensor nearest the first row and column: by
/// their smallest sensor id (ids are row-major). Duplicate sensor ids are kept once (the first).
std::vector<Cluster> clusterDetections(std::span<const Detection> detections, double link_distance,
                                       double sensor_spacing);

}  // namespace wsn::supernode::rulebased

// Plain C++ forms of what flows between roles. Algorithm libraries speak these; only
// common/dds converts them to and from the IDL types on the wire.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace wsn::common {

/// Identifies a sensor: its index in the layout (row-major for grids).
using SensorId = std::uint32_t;
/// Track identities are global: (supernode + 1) << 48 | per-supernode serial (engines mint them,
/// e.g. gnn::birthTrackId); ids below 1 << 48 are the aggregator's own.
using TrackId = std::uint64_t;
inline constexpr int kTrackOwnerShift = 48;

/// Serials at or above this are birth ids, tick << 24 | sensor (gnn::birthTrackId, used by the GNN
/// and rule-based engines); below it, counters (MCMCDA). Ticks start at 1, so the two never meet.
inline constexpr std::uint64_t kBirthSerialFloor = std::uint64_t{1} << 24;

/// A track id as people read it: "S:N" for serial N of supernode S; "S:tTsK" for a track that
/// supernode S started at tick T from sensor K's report; "gN" for an id the aggregator minted.
/// `wsntrack watch` and the track CSVs show ids this way.
inline std::string trackLabel(TrackId id) {
  const std::uint64_t owner = id >> kTrackOwnerShift;
  const std::uint64_t serial = id & ((std::uint64_t{1} << kTrackOwnerShift) - 1);
  if (owner == 0) return "g" + std::to_string(serial);
  const std::string supernode = std::to_string(owner - 1) + ":";
  if (serial < kBirthSerialFloor) return supernode + std::to_string(serial);
  return supernode + "t" + std::to_string(serial >> 24) + "s" + std::to_string(serial & (kBirthSerialFloor - 1));
}
/// Ground-truth target id; kFalseAlarm marks a report that no target caused.
using TargetId = std::int32_t;
inline constexpr TargetId kFalseAlarm = -1;

/// A reading z >= eta of one sensor at one tick.
struct SensorReading {
  SensorId sensor = 0;
  double z = 0.0;
  friend bool operator==(const SensorReading&, const SensorReading&) = default;
};

/// A fused report (Oh eq. 6) from the local-maximum sensor, in believed coordinates; or a raw
/// acoustic detection (An et al. 2014 eq. 4) at the sensor's believed position with its level.
struct Report {
  std::int32_t tick = 0;
  SensorId sensor = 0;
  double x = 0.0;
  double y = 0.0;
  TargetId target = kFalseAlarm;
  /// Acoustic detection: ws = floor(Ps / cs) >= 1 (An et al. 2014 eq. 4, 10); 0 for a fused report.
  std::int32_t power_level = 0;
  friend bool operator==(const Report&, const Report&) = default;
};

/// A report as a supernode receives it: generated at tick_generated, delivered at
/// tick_delivered >= tick_generated.
struct Observation {
  std::int32_t tick_generated = 0;
  std::int32_t tick_delivered = 0;
  SensorId sensor = 0;
  double x = 0.0;
  double y = 0.0;
  TargetId target = kFalseAlarm;
  std::int32_t power_level = 0;  ///< as in Report
  friend bool operator==(const Observation&, const Observation&) = default;
};

/// A track's estimate at one tick: the state and its covariance.
struct TrackEstimate {
  TrackId track = 0;
  double x = 0.0;
  double y = 0.0;
  double vx = 0.0;
  double vy = 0.0;
  std::array<double, 16> covariance{};  ///< row-major 4x4 over (x, y, vx, vy); zero when unknown
  /// Tick of the track's latest observation (the state above is its filtered state there,
  /// predicted forward); 0 when unknown. Lets the aggregator tell observed from coasted ticks.
  std::int32_t last_seen_tick = 0;
  friend bool operator==(const TrackEstimate&, const TrackEstimate&) = default;
};

/// A track whose state can be used: x, y, vx, vy all finite (consumers drop and count the rest).
inline bool isFinite(const TrackEstimate& t) {
  return std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.vx) && std::isfinite(t.vy);
}

/// Everything a supernode needs to continue a track another supernode started.
struct TrackHandoff {
  TrackId track = 0;
  std::uint32_t to_supernode = 0;
  std::int32_t last_tick = 0;         ///< tick of `state`
  std::array<double, 4> state{};      ///< x, y, vx, vy
  std::array<double, 16> covariance{};  ///< row-major 4x4
  std::int32_t hits = 0;
  std::int32_t misses = 0;
  bool confirmed = false;
  friend bool operator==(const TrackHandoff&, const TrackHandoff&) = default;
};

}  // namespace wsn::common

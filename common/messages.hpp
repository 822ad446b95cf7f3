// Plain C++ forms of what flows between roles. Algorithm libraries speak these; only
// common/dds converts them to and from the IDL types on the wire.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/measurement.hpp"
#include "common/track_id.hpp"

namespace wsn::common {

// SensorId (a sensor's index in the layout) and TrackId (a track's global identity) are declared,
// with the track id's bit layout, in common/track_id.hpp.

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
  /// Where the report lies in the field, which routing, canonical orders and observations.csv
  /// use: the measured position for kind position, the sensor's believed position otherwise.
  double x = 0.0;
  double y = 0.0;
  TargetId target = kFalseAlarm;
  /// Acoustic detection: ws = floor(Ps / cs) >= 1 (An et al. 2014 eq. 4, 10); 0 for a fused report.
  std::int32_t power_level = 0;
  /// What the sensor measured: null (the default) for the position (x, y) with the engine's noise.
  MeasurementRef measurement = {};
  friend bool operator==(const Report&, const Report&) = default;
};

/// A report as a supernode receives it: generated at tick_generated, delivered at
/// tick_delivered >= tick_generated. Position engines read x, y; the others the measurement.
struct Observation {
  std::int32_t tick_generated = 0;
  std::int32_t tick_delivered = 0;
  SensorId sensor = 0;
  double x = 0.0;
  double y = 0.0;
  TargetId target = kFalseAlarm;
  std::int32_t power_level = 0;  ///< as in Report
  MeasurementRef measurement = {};  ///< as in Report
  friend bool operator==(const Observation&, const Observation&) = default;
};

/// True when the report's measurement can be used (common::wellFormed) and agrees with x, y: the
/// values of a position, the sensor's position for the other kinds.
inline bool wellFormed(const Report& r) {
  if (!r.measurement) return true;  // the position (x, y)
  const Measurement& m = *r.measurement;
  if (!wellFormed(m)) return false;
  if (m.kind == MeasurementKind::position) return m.values[0] == r.x && m.values[1] == r.y;
  return m.sensor->x == r.x && m.sensor->y == r.y;
}

/// The observation a supernode receives when `report` is delivered at tick_delivered.
inline Observation observationOf(const Report& report, std::int32_t tick_delivered) {
  return {report.tick,   tick_delivered,     report.sensor,     report.x,
          report.y,      report.target,      report.power_level, report.measurement};
}

/// What `o` measured, in full: its measurement, or the position (x, y) for a plain one.
inline Measurement measurementOf(const Observation& o) {
  return o.measurement ? *o.measurement : Measurement::position(o.x, o.y);
}

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
  /// The track's class vector beta over common/class_evidence.hpp's classes (ONERA eqs. 19-20);
  /// empty when the engine does not classify. At most kMaxClasses entries go on the wire.
  std::vector<double> class_probabilities;
  /// The probability the engine's motion model gives the target being stopped (ONERA's IMM stop
  /// model, eq. 4); none when the engine has no stop model.
  std::optional<double> stop_probability;
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
  std::vector<double> class_probabilities;  ///< the track's beta, as in TrackEstimate; empty: none
  friend bool operator==(const TrackHandoff&, const TrackHandoff&) = default;
};

}  // namespace wsn::common

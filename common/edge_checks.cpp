#include "common/edge_checks.hpp"

#include "common/sensor_layout.hpp"

#include <algorithm>
#include <array>
#include <span>
#include <cmath>
#include <sstream>

namespace wsn::common {
namespace {

bool bounded(double v) { return std::isfinite(v) && std::fabs(v) <= kMaxMagnitude; }

/// Not finite, or beyond any bound, for the values of a measurement.
std::optional<RejectReason> checkValues(std::span<const double> values) {
  for (const double v : values) {
    if (!std::isfinite(v)) return RejectReason::kNotFinite;
    if (std::fabs(v) > kMaxMagnitude) return RejectReason::kOutOfRegion;
  }
  return std::nullopt;
}

std::optional<RejectReason> checkMeasurement(const Measurement& m) {
  for (const auto* values : {&m.values, &m.noise, &m.class_likelihoods})
    if (const auto why = checkValues(*values)) return why;
  if (!std::isfinite(m.clutter_density)) return RejectReason::kNotFinite;
  if (!bounded(m.clutter_density)) return RejectReason::kOutOfRegion;
  if (m.sensor) {
    const std::array<double, 4> pose{m.sensor->x, m.sensor->y, m.sensor->heading, m.sensor->height};
    if (const auto why = checkValues(pose)) return why;
  }
  if (!wellFormed(m)) return RejectReason::kMalformedMeasurement;
  return std::nullopt;
}

/// A report or an observation: a sensor the run has, a finite position within the region and its
/// margin, and a measurement that checkMeasurement accepts.
template <typename Sensed>
std::optional<RejectReason> checkSensed(const Sensed& m, const EdgeBounds& bounds) {
  if (m.sensor >= bounds.sensors) return RejectReason::kSensorOutOfRange;
  if (!std::isfinite(m.x) || !std::isfinite(m.y)) return RejectReason::kNotFinite;
  if (!bounds.region.contains({m.x, m.y})) return RejectReason::kOutOfRegion;
  if (m.measurement) return checkMeasurement(*m.measurement);
  return std::nullopt;
}

}  // namespace

const char* rejectReasonName(RejectReason reason) {
  switch (reason) {
    case RejectReason::kForeignRun: return "foreign_run";
    case RejectReason::kProducerOutOfRange: return "producer_out_of_range";
    case RejectReason::kTickOutOfRange: return "tick_out_of_range";
    case RejectReason::kDuplicate: return "duplicate";
    case RejectReason::kTooLong: return "too_long";
    case RejectReason::kSensorOutOfRange: return "sensor_out_of_range";
    case RejectReason::kNotFinite: return "not_finite";
    case RejectReason::kOutOfRegion: return "out_of_region";
    case RejectReason::kMalformedMeasurement: return "malformed_measurement";
    case RejectReason::kMisaddressed: return "misaddressed";
    case RejectReason::kUnauthenticated: return "unauthenticated";
    case RejectReason::kMalformed: return "malformed";
  }
  return "unknown";
}

EdgeBounds edgeBounds(const Scenario& scenario) {
  const std::uint64_t sensors = sensorCount(scenario.sensors, scenario.region);
  EdgeBounds bounds;
  bounds.margin = std::max(scenario.region.width(), scenario.region.height()) + scenario.sensor_model.sensing_range +
                  6.0 * scenario.localisation.sigma;
  bounds.region = Rect{scenario.region.x_min - bounds.margin, scenario.region.y_min - bounds.margin,
                       scenario.region.x_max + bounds.margin, scenario.region.y_max + bounds.margin};
  bounds.sensors = sensors;
  bounds.ticks = scenario.run.ticks;
  bounds.max_reports = static_cast<std::size_t>(sensors) * kMaxReportsPerSensor;
  return bounds;
}

std::optional<RejectReason> checkBatchHeader(std::uint64_t run_id, std::uint64_t expected_run_id, std::uint32_t producer,
                                             std::uint32_t producers, std::int32_t tick, std::int32_t ticks) {
  if (run_id != expected_run_id) return RejectReason::kForeignRun;
  if (producer >= producers) return RejectReason::kProducerOutOfRange;
  if (tick < 1 || tick > ticks) return RejectReason::kTickOutOfRange;
  return std::nullopt;
}

std::optional<RejectReason> checkReport(const Report& report, const EdgeBounds& bounds) {
  return checkSensed(report, bounds);
}

std::optional<RejectReason> checkObservation(const Observation& observation, const EdgeBounds& bounds) {
  if (observation.tick_generated < 1 || observation.tick_generated > observation.tick_delivered)
    return RejectReason::kTickOutOfRange;
  return checkSensed(observation, bounds);
}

std::optional<RejectReason> checkReading(const SensorReading& reading, const EdgeBounds& bounds) {
  if (reading.sensor >= bounds.sensors) return RejectReason::kSensorOutOfRange;
  return checkValues(std::span<const double>(&reading.z, 1));
}

std::optional<RejectReason> checkTrack(const TrackEstimate& track, const EdgeBounds& bounds) {
  const std::array<double, 4> state{track.x, track.y, track.vx, track.vy};
  if (const auto why = checkValues(state)) return why;
  if (const auto why = checkValues(track.covariance)) return why;
  if (const auto why = checkValues(track.class_probabilities)) return why;
  if (track.stop_probability && !std::isfinite(*track.stop_probability)) return RejectReason::kNotFinite;
  if (!bounds.region.contains({track.x, track.y})) return RejectReason::kOutOfRegion;
  if (track.last_seen_tick < 0 || track.last_seen_tick > bounds.ticks) return RejectReason::kTickOutOfRange;
  return std::nullopt;
}

std::optional<RejectReason> checkHandoff(const TrackHandoff& handoff, const EdgeBounds& bounds, std::uint32_t supernodes) {
  if (handoff.to_supernode >= supernodes) return RejectReason::kMisaddressed;
  if (handoff.last_tick < 1 || handoff.last_tick > bounds.ticks) return RejectReason::kTickOutOfRange;
  if (const auto why = checkValues(handoff.state)) return why;
  if (const auto why = checkValues(handoff.covariance)) return why;
  if (const auto why = checkValues(handoff.class_probabilities)) return why;
  if (!bounds.region.contains({handoff.state[0], handoff.state[1]})) return RejectReason::kOutOfRegion;
  return std::nullopt;
}

void RejectionLog::add(const std::string& topic, RejectReason reason, std::uint64_t count) {
  if (count > 0) counts_[{topic, reason}] += count;
}

std::uint64_t RejectionLog::total() const {
  std::uint64_t n = 0;
  for (const auto& [key, count] : counts_) n += count;
  return n;
}

std::uint64_t RejectionLog::count(const std::string& topic, RejectReason reason) const {
  const auto it = counts_.find({topic, reason});
  return it == counts_.end() ? 0 : it->second;
}

std::string RejectionLog::json(const std::string& role, std::uint32_t index) const {
  std::ostringstream out;
  out << "{\"role\": \"" << role << "\", \"index\": " << index << ", \"rejected\": [";
  bool first = true;
  for (const auto& [key, count] : counts_) {
    out << (first ? "" : ", ") << "{\"topic\": \"" << key.first << "\", \"reason\": \"" << rejectReasonName(key.second)
        << "\", \"count\": " << count << "}";
    first = false;
  }
  out << "]}\n";
  return out.str();
}

void dropRejectedReports(std::vector<Report>& reports, const EdgeBounds& bounds, const std::string& topic,
                         RejectionLog& log) {
  dropRejected(reports, [&](const Report& report) { return checkReport(report, bounds); }, topic, log);
}

}  // namespace wsn::common

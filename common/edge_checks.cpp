#include "common/edge_checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace wsn::common {
namespace {

bool bounded(double v) { return std::isfinite(v) && std::fabs(v) <= kMaxMagnitude; }

/// Not finite, or beyond any bound, for the values of a measurement.
std::optional<RejectReason> checkValues(const std::vector<double>& values) {
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
    if (const auto why = checkValues({m.sensor->x, m.sensor->y, m.sensor->heading, m.sensor->height})) return why;
  }
  if (!wellFormed(m)) return RejectReason::kMalformedMeasurement;
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
  }
  return "unknown";
}

EdgeBounds edgeBounds(const Scenario& scenario, std::uint64_t sensors) {
  EdgeBounds bounds;
  bounds.margin = std::max(scenario.region.width(), scenario.region.height()) + scenario.sensor_model.sensing_range +
                  6.0 * scenario.localisation.sigma;
  bounds.region = Rect{scenario.region.x_min - bounds.margin, scenario.region.y_min - bounds.margin,
                       scenario.region.x_max + bounds.margin, scenario.region.y_max + bounds.margin};
  bounds.sensors = sensors;
  bounds.ticks = scenario.run.ticks;
  bounds.max_reports = static_cast<std::size_t>(sensors);
  return bounds;
}

std::optional<RejectReason> checkReport(const Report& report, const EdgeBounds& bounds) {
  if (report.sensor >= bounds.sensors) return RejectReason::kSensorOutOfRange;
  if (!std::isfinite(report.x) || !std::isfinite(report.y)) return RejectReason::kNotFinite;
  if (!bounds.region.contains({report.x, report.y})) return RejectReason::kOutOfRegion;
  if (report.measurement) return checkMeasurement(*report.measurement);
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
  std::erase_if(reports, [&](const Report& report) {
    const auto why = checkReport(report, bounds);
    if (why) log.add(topic, *why);
    return why.has_value();
  });
}

}  // namespace wsn::common

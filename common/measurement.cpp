#include "common/measurement.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace wsn::common {
namespace {

struct KindRow {
  MeasurementKind kind;
  std::string_view name;
  std::size_t dimension;
};

// Indexed by the enumerator's value; a new kind is one row here.
constexpr std::array<KindRow, 6> kKinds{{
    {MeasurementKind::position, "position", 2},
    {MeasurementKind::bearing, "bearing", 1},
    {MeasurementKind::range_bearing_rate, "range_bearing_rate", 3},
    {MeasurementKind::azimuth_elevation, "azimuth_elevation", 2},
    {MeasurementKind::signal_strength, "signal_strength", 1},
    {MeasurementKind::presence, "presence", 0},
}};

constexpr bool tableInEnumOrder() {
  for (std::size_t i = 0; i < kKinds.size(); ++i)
    if (static_cast<std::size_t>(kKinds[i].kind) != i || kKinds[i].dimension > kMaxMeasurementDimension) return false;
  return true;
}
static_assert(tableInEnumOrder(), "kKinds must list every MeasurementKind at its value, within kMaxMeasurementDimension");

const KindRow* rowOf(MeasurementKind kind) {
  const auto i = static_cast<std::size_t>(kind);
  return i < kKinds.size() ? &kKinds[i] : nullptr;
}

bool allFinite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double d) { return std::isfinite(d); });
}

}  // namespace

bool Measurement::hasNoise() const {
  return std::any_of(noise.begin(), noise.end(), [](double r) { return r != 0.0; });
}

std::string_view measurementKindName(MeasurementKind kind) {
  const KindRow* row = rowOf(kind);
  return row ? row->name : "unknown";
}

std::optional<MeasurementKind> measurementKindNamed(std::string_view name) {
  for (const KindRow& row : kKinds)
    if (row.name == name) return row.kind;
  return std::nullopt;
}

std::optional<std::size_t> measurementDimension(MeasurementKind kind) {
  const KindRow* row = rowOf(kind);
  if (!row) return std::nullopt;
  return row->dimension;
}

bool wellFormed(const Measurement& m) {
  const auto dimension = measurementDimension(m.kind);
  if (!dimension || m.values.size() != *dimension || !allFinite(m.values)) return false;
  if (!m.noise.empty() && (m.noise.size() != *dimension * *dimension || !allFinite(m.noise))) return false;
  if (m.kind != MeasurementKind::position) {
    if (!m.sensor) return false;
    if (!std::isfinite(m.sensor->x) || !std::isfinite(m.sensor->y) || !std::isfinite(m.sensor->heading)) return false;
    if (!std::isfinite(m.sensor->height) || m.sensor->height < 0.0) return false;
  }
  if (!std::isfinite(m.clutter_density) || m.clutter_density < 0.0) return false;
  return m.class_likelihoods.size() <= kMaxClasses &&
         std::all_of(m.class_likelihoods.begin(), m.class_likelihoods.end(),
                     [](double c) { return std::isfinite(c) && c >= 0.0; });
}

}  // namespace wsn::common

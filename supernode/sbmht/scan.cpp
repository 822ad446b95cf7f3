#include "supernode/sbmht/scan.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/class_evidence.hpp"

namespace wsn::supernode::sbmht {
namespace {

/// c of a measurement when it is one class likelihood per class, finite, non-negative and not all
/// zero (what common::updateClassVector takes); else empty: the report then says nothing about
/// class, as a radar's does.
std::span<const double> classLikelihoodsOf(const common::Measurement& m) {
  const auto& c = m.class_likelihoods;
  if (c.size() != common::kClassCount) return {};
  if (!std::all_of(c.begin(), c.end(), [](double v) { return std::isfinite(v) && v >= 0.0; })) return {};
  if (std::none_of(c.begin(), c.end(), [](double v) { return v > 0.0; })) return {};
  return c;
}

}  // namespace

ReportTerms termsOf(const common::Observation& o, double r2, double lambda_fa, const std::array<double, 4>& gates) {
  ReportTerms t;
  if (!o.measurement) {
    t.z.resize(2);
    t.z << o.x, o.y;
    t.R = MeasurementCovariance::Identity(2, 2) * r2;
    t.clutter_density = lambda_fa;
  } else {
    const common::Measurement& m = *o.measurement;
    const auto model = modelOf(m);
    if (!model) return t;
    t.model = *model;
    t.z = valuesOf(m);
    const auto R = noiseOf(m);
    const bool position = m.kind == common::MeasurementKind::position;
    if (R)
      t.R = *R;
    else if (position)
      t.R = MeasurementCovariance::Identity(2, 2) * r2;
    else
      return t;
    t.clutter_density = m.clutter_density > 0.0 ? m.clutter_density : (position ? lambda_fa : 0.0);
    if (!(t.clutter_density > 0.0)) return t;
  }
  t.position = t.model.kind == common::MeasurementKind::position;
  t.gate = gates[static_cast<std::size_t>(t.model.dimension())];
  t.fix = positionFix(t.model, t.z, t.R);
  if (o.measurement) t.classes = classLikelihoodsOf(*o.measurement);
  t.usable = true;
  return t;
}

std::vector<Scan> scansOf(std::span<const common::Observation> slot, std::span<const common::SensorCoverage> coverage,
                          std::span<const std::int32_t> coverage_of_sensor) {
  std::vector<Scan> scans;
  if (coverage.empty()) {
    scans.emplace_back();
    for (std::size_t j = 0; j < slot.size(); ++j) scans.back().reports.push_back(j);
    return scans;
  }
  // Every listed sensor is a scan, whether it reported or not: its silence is evidence where it looks.
  for (const auto& sensor : coverage) scans.push_back(Scan{&sensor, {}});
  Scan unlisted;
  for (std::size_t j = 0; j < slot.size(); ++j) {
    const common::SensorId id = slot[j].sensor;
    if (id < coverage_of_sensor.size() && coverage_of_sensor[id] >= 0)
      scans[static_cast<std::size_t>(coverage_of_sensor[id])].reports.push_back(j);
    else
      unlisted.reports.push_back(j);
  }
  if (!unlisted.reports.empty()) scans.push_back(std::move(unlisted));
  return scans;
}

}  // namespace wsn::supernode::sbmht

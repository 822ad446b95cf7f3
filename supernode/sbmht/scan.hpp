// How an sbmht scan sees a tick's reports: split into one scan per listed sensor (its silence weighed
// where it looks), and each report turned into the terms the scan and the births use (measurement
// model, value, noise, clutter density, gate, and where it would start a track).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/messages.hpp"
#include "common/sensor_coverage.hpp"
#include "supernode/sbmht/measurement_models.hpp"

namespace wsn::supernode::sbmht {

/// One report as a scan uses it: its measurement function, value, noise and clutter density in its
/// own space, the gate for its dimension, and where it would start a track.
struct ReportTerms {
  bool usable = false;
  /// A field-frame position: the cheap distance pre-check before the EKFs applies.
  bool position = false;
  MeasurementModel model;
  MeasurementVector z;
  MeasurementCovariance R;
  double clutter_density = 0.0;
  double gate = 0.0;
  std::optional<PositionFix> fix;
  /// Its class likelihoods c (eqs. 19-23), one per common::kClassCount class; empty when it
  /// carries none or a c the engine cannot use (another class count, a negative entry, all zero).
  std::span<const double> classes;
};

/// The terms of observation o. A plain position (the position engines' reports) has the engine's
/// own noise (r2 = measurement_sigma^2 per axis) and clutter density lambda_fa (per area). Any other
/// measurement must carry its R and its clutter density in its own space (common/measurement.hpp):
/// a bearing's lambda per radian cannot be made from a density per area; without them the report
/// is not usable. `gates` holds the gate on d^2 for each report dimension 0..3.
ReportTerms termsOf(const common::Observation& o, double r2, double lambda_fa, const std::array<double, 4>& gates);

/// The reports one sensor gave at a tick (all reports when the engine has no coverage).
struct Scan {
  const common::SensorCoverage* coverage = nullptr;  ///< null: uniform detection_probability
  std::vector<std::size_t> reports;                  ///< indices into the tick's slot
};

/// The scans of a tick's reports: without coverage one scan of them all; with it one per listed
/// sensor in `coverage`'s order, reported or not, then one of the unlisted sensors' reports if any.
/// coverage_of_sensor maps a sensor id to its index in `coverage`, or -1.
std::vector<Scan> scansOf(std::span<const common::Observation> slot, std::span<const common::SensorCoverage> coverage,
                          std::span<const std::int32_t> coverage_of_sensor);

}  // namespace wsn::supernode::sbmht

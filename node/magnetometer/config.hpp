// The magnetometer model's keys of `sensor_model` (Oh et al. 2005 §VIII's testbed, with the
// physical model of the ADMAN/§VIII specification, B3): its settings struct, field table and how
// the scenario loader reads and writes them.
#pragma once

#include "common/config/field_table.hpp"
#include "common/scenario_config.hpp"
#include "node/sensor_model_registry.hpp"

namespace wsn::node::magnetometer {

/// Two-axis magnetometers sampled at sample_rate_hz that detect a passing magnet by Oh eq. (11):
/// the mean size of the sample-to-sample change of the field vector over the last `window`
/// samples above `threshold`. Lengths in sensor pitches, field readings in ADC counts.
struct MagnetometerSettings : common::SensorModelSettingsOf<MagnetometerSettings> {
  double sample_rate_hz = 10.0;  ///< f_s
  double tick_s = 0.5;           ///< seconds per tick; a whole number of samples
  std::int32_t window = 5;       ///< W of eq. (11)
  double threshold = 80.0;       ///< eta of eq. (11), counts
  double magnet_height = 0.2;    ///< h: the magnet's height above the sensor plane, pitches
  double magnet_strength = 125.0;  ///< K: dipole strength, counts x pitch^3
  double offset_spread = 100.0;  ///< per-axis offset o = 512 + U(-spread, spread), counts
  double noise_sigma = 5.0;      ///< sigma_n: read noise per axis and sample, counts
  double drift_sigma = 1.0;      ///< bias random walk per axis and sample, counts
  double jump_rate_hz = 0.005;   ///< lambda_j: bias jumps (offset re-centring) per sensor and second
  double jump_max = 1000.0;      ///< a jump's size is U(0, jump_max) counts, in a random direction
  double adc_max = 1023.0;       ///< readings are clipped to [0, adc_max] per axis
  friend bool operator==(const MagnetometerSettings&, const MagnetometerSettings&) = default;

  std::int32_t samplesPerTick() const;
};

const common::config::FieldTable<MagnetometerSettings>& settingsTable();

/// The loader's view of these settings (for the registry).
SensorModelSettingsSpec settingsSpec();

}  // namespace wsn::node::magnetometer

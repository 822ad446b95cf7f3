// The signal-strength model's keys of `sensor_model` (Oh et al. eq. 5): its settings struct, its
// field table and how the scenario loader reads, checks and writes them.
#pragma once

#include "common/config/field_table.hpp"
#include "common/scenario_config.hpp"
#include "node/sensor_model_registry.hpp"

namespace wsn::node::signal_strength {

/// Oh eq. (5): z = beta / (1 + gamma |s - x|^alpha) + w within the sensing range Rs, z = w
/// outside, w ~ N(0, noise_sigma^2); detection when z >= eta.
struct SignalStrengthSettings : common::SensorModelSettingsOf<SignalStrengthSettings> {
  double alpha = 2.0;
  /// Oh §VII: beta = 3 (1 + gamma Rs^alpha); derived by the loader when not given.
  double beta = 9.75;
  double gamma = 1.0;
  double eta = 2.0;
  double noise_sigma = 1.0;
  friend bool operator==(const SignalStrengthSettings&, const SignalStrengthSettings&) = default;
};

const common::config::FieldTable<SignalStrengthSettings>& settingsTable();

/// The loader's view of these settings (for the registry).
SensorModelSettingsSpec settingsSpec();

}  // namespace wsn::node::signal_strength

// The acoustic model's keys of `sensor_model` (An et al. 2014 eq. 1-4, with the environmental
// noise of An et al. 2013): its settings structs, field tables, the paper's noise presets, and
// how the scenario loader reads, checks and writes them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/config/field_table.hpp"
#include "common/scenario_config.hpp"
#include "node/sensor_model_registry.hpp"

namespace wsn::node::acoustic {

/// Acoustic sensors that hear the targets' sound with the Doppler effect, An et al. 2014 eq. (1)-(4).
/// A target of sensing range SR emits Pt = threshold * SR^alpha every detection step; a sensor
/// reports (id, floor(Ps / threshold)) when Ps >= threshold.
struct DetectionConfig {
  double threshold = 1.0;           ///< cs (gamma_s): the sensor threshold, in power units
  double sound_speed = 343.0;       ///< Vs, length units per second
  double detection_step_s = 0.005;  ///< Delta t of the detection model (2014 §3.1)
  double tick_s = 0.1;              ///< seconds per tick: the fusion centre runs once a tick (2014 §5)
  /// Each emission's power is Pt (1 + f U(-1, 1)), f = power_fluctuation (2014 §5.2: 0, 0.2, 0.4).
  double power_fluctuation = 0.0;
  friend bool operator==(const DetectionConfig&, const DetectionConfig&) = default;
};

/// One kind of sporadic environmental noise, An et al. 2013 §3.1: at any time `fraction` of the
/// sensors, chosen at random, hear noise of power gamma_s (1 + U(0, 1)) for `duration_s` seconds.
struct NoiseComponent {
  double fraction = 0.0;
  double duration_s = 0.1;
  friend bool operator==(const NoiseComponent&, const NoiseComponent&) = default;
};

/// Environmental noise: a named preset of the 2013 paper (noise1: 0.1 s on 6 %; noise2: 0.1 s on
/// 5 % + 0.5 s on 1 %; noise3: 0.1 s on 5 % + 1 s on 1 %) or explicit components.
struct EnvironmentalNoiseConfig {
  std::string preset = "none";  ///< none, noise1, noise2, noise3 or custom (components given)
  std::vector<NoiseComponent> components;
  friend bool operator==(const EnvironmentalNoiseConfig&, const EnvironmentalNoiseConfig&) = default;
};

/// Everything of `sensor_model` the acoustic model reads besides kind and sensing_range.
struct AcousticSettings : common::SensorModelSettingsOf<AcousticSettings> {
  double alpha = 2.0;  ///< An et al. 2014 eq. (3): Ps = Pt / d^alpha
  DetectionConfig acoustic;
  EnvironmentalNoiseConfig environmental_noise;
  friend bool operator==(const AcousticSettings&, const AcousticSettings&) = default;
};

/// The components of a named preset; nullopt for an unknown name ("none" has none).
std::optional<std::vector<NoiseComponent>> noisePreset(const std::string& name);

const common::config::FieldTable<AcousticSettings>& settingsTable();  ///< alpha (the rest: sub-sections)
const common::config::FieldTable<DetectionConfig>& detectionTable();
const common::config::FieldTable<EnvironmentalNoiseConfig>& environmentalNoiseTable();  ///< preset
const common::config::FieldTable<NoiseComponent>& noiseComponentTable();

/// The loader's view of these settings (for the registry).
SensorModelSettingsSpec settingsSpec();

}  // namespace wsn::node::acoustic

// The ADMAN model's keys of `sensor_model` (received signal strength, the two-stage GLRT and MLMC
// localisation; the ADMAN/§VIII specification, part A): its settings struct, field table and how
// the scenario loader reads and writes them.
#pragma once

#include <cstdint>

#include "common/config/field_table.hpp"
#include "common/scenario_config.hpp"
#include "node/adman/adman.hpp"
#include "node/sensor_model_registry.hpp"

namespace wsn::node::adman {

/// Which MLMC search places the targets.
enum class Localisation { factorised = 0, joint = 1 };

/// Sensors that measure the received signal strength in dB of every target (eq. 1), tell a target
/// inside r0 from one in between by two GLRT stages, and place each detected target by MLMC. Lengths
/// in the scenario's unit (metres in ADMAN's scenario), powers in dB.
struct AdmanSettings : common::SensorModelSettingsOf<AdmanSettings> {
  double power_db = 40.0;            ///< Psi at the reference distance (the paper's "4 dB" read as 40)
  double reference_distance = 1.0;   ///< d0
  double attenuation = 2.0;          ///< alpha
  double noise_sigma_db = 0.17321;   ///< sigma of v: the paper's variance 0.03
  double false_alarm_probability = 0.01;  ///< P_FA of each GLRT stage
  double sensor_pitch = 1.0;         ///< the grid's pitch (derived from the layout)
  double inside_radius = 0.5;        ///< r0 (derived: half the pitch, discs that touch)
  std::int32_t particles = 3000;     ///< P
  Localisation localisation = Localisation::factorised;
  std::int32_t sweeps = 2;           ///< factorised MLMC's sweeps
  double interaction_range = 4.0;    ///< others of a target: attached within it (derived: 4 pitches)
  friend bool operator==(const AdmanSettings&, const AdmanSettings&) = default;

  PowerModel power() const { return {power_db, reference_distance, attenuation}; }
  Thresholds glrtThresholds() const;
  MlmcSettings mlmc(std::uint64_t seed) const;
};

const common::config::FieldTable<AdmanSettings>& settingsTable();

/// The loader's view of these settings (for the registry).
SensorModelSettingsSpec settingsSpec();

}  // namespace wsn::node::adman

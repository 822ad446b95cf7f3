// The sbmht engine's parameters: the plain struct it runs with, its field table (key, unit, range,
// default, meaning) and the derivations of the parameters that default to the scenario's own models.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "supernode/engine.hpp"

namespace wsn::supernode::sbmht {

/// Resolved parameters (see paramTable() for meaning, defaults and ranges).
struct SbmhtParams {
  double detection_probability = 0.9;
  double false_alarm_density = 1e-4;
  double birth_density = 1e-5;
  double measurement_sigma = 0.5;
  double initial_velocity_sigma = 2.0;
  double gate_chi2 = 9.21;
  double sprt_alpha = 1e-3;
  double sprt_beta = 0.1;
  double drop_score = 10.0;
  std::int32_t max_misses = 3;
  std::int32_t n_scan = 3;
  std::int32_t hypotheses = 20;
  std::int32_t initial_score = 0;  ///< 0: blackman, 1: paper (InitialScore)
  double stop_sigma = 0.1;
  double cv_slow_sigma = 0.15;
  double cv_fast_sigma = 0.75;
  double stop_time_constant = 20.0;
  double slow_time_constant = 30.0;
  double fast_time_constant = 10.0;
  double merge_radius = 0.0;
  std::int32_t confirm_reports = 3;   ///< a tentative track that took reports at this many ticks is confirmed
  double delivery_probability = 1.0;  ///< scales each sensor's PD where the engine has coverage
  std::int32_t max_coast_ticks = 60;  ///< a leaf no sensor could see for this many ticks running is deleted
  std::int32_t bearing_pair_births = 1;  ///< 1: two ungated bearings of two sensors start a tree where they cross
  std::int32_t use_road_network = 1;  ///< 1: algorithm 1 (the scenario's roads in the IMM and N-scan), 0: algorithm 2
  double road_along_sigma = 1.0;      ///< sigma_d of eq. 6
  double road_across_sigma = 0.1;     ///< sigma_n of eq. 6
  double road_location_sigma = 1.0;   ///< the road map's own error across the road
  double road_gate_distance = 15.0;   ///< the road model is active within this distance of a road
  double road_time_constant = 30.0;   ///< mean sojourn in the road model
  std::int32_t road_sections_kept = 3;  ///< Nk: N-scan keeps the best branch of up to this many road sections

  static SbmhtParams fromContext(const EngineContext& context);
};

/// The parameters' one description: key, member, unit, range, default (SbmhtParams{}) and meaning.
const config::FieldTable<SbmhtParams>& paramTable();

/// By key, how the parameters with a physical meaning default to values derived from the
/// scenario's own sensor, network and target models.
std::map<std::string, common::ParamDerivation> paramDerivations();

}  // namespace wsn::supernode::sbmht

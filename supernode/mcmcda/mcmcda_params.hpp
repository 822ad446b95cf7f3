// The MCMCDA engine's parameters: the resolved struct, its field table (key, unit, range, default,
// meaning) and the derived defaults that measure eq. (3)'s model on the scenario's own models.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "supernode/engine.hpp"
#include "supernode/mcmcda/problem.hpp"

namespace wsn::supernode::mcmcda {

/// Resolved parameters (see paramTable() for meaning, defaults and ranges).
struct McmcdaParams {
  ModelParams model;
  std::int64_t iterations = 1000;        ///< nmc per tick
  double greedy_gate_chi2 = 9.21;        ///< gate of the greedy start for the newest tick
  std::int32_t confirm_observations = 3;  ///< observations (all time) before a track is reported
  double merge_radius = 0.0;             ///< same-tick reports this close are merged first (0: none)

  /// From the engine context's resolved params (paramTable() decodes them) and its dynamics.
  static McmcdaParams fromContext(const EngineContext& context);
};

/// The parameters' one description: key, member, unit, range, default (McmcdaParams{}) and meaning.
const config::FieldTable<McmcdaParams>& paramTable();

/// The model of eq. (3) follows the scenario: each parameter with a physical meaning is measured
/// on the scenario's own sensor, network and target models (observation_model/) unless set.
std::map<std::string, common::ParamDerivation> paramDerivations();

}  // namespace wsn::supernode::mcmcda

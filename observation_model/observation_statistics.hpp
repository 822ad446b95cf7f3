// Measures a scenario's ObservationStatistics from its own models: the sensor model by a short
// deterministic simulation of its field, the network by Oh et al. eq. (7) over the topology, the
// targets from their birth, death and speed model. Engines derive their `auto` parameters from it.
#pragma once

#include "common/observation_statistics.hpp"
#include "common/param_spec.hpp"
#include "common/scenario_config.hpp"

namespace wsn::observation_model {

/// The statistics of `scenario`'s models. Independent of run.seed (the simulation has its own
/// fixed seed): the statistics describe the model, so every seed of a sweep runs with the same
/// derived parameters.
common::ObservationStatistics observationStatistics(const common::Scenario& scenario);

/// A source that measures `scenario`'s statistics on first use and keeps them; `scenario` must
/// outlive it. What the parameter resolution takes (common/param_spec.hpp).
common::StatisticsSource lazyStatistics(const common::Scenario& scenario);

/// The target-model part alone (no simulation): birth density, termination, velocity and speed.
void deriveTargetStatistics(const common::Scenario& scenario, common::ObservationStatistics& stats);

}  // namespace wsn::observation_model

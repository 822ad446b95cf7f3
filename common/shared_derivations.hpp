// Derivations that several components share: a parameter with the same physical meaning (a report's
// error, a new track's velocity prior, the targets' speed, births and ends) is derived from the
// scenario the same way in every engine and association.
#pragma once

#include <cmath>

#include "common/observation_statistics.hpp"
#include "common/param_spec.hpp"

namespace wsn::common {

/// R = r^2 I of a report: the sensor model's measured report error.
inline ParamDerivation reportErrorDerivation() {
  return {
      "the sensor model's report error (localisation and fusion)",
      [](const StatisticsSource& stats, const std::map<std::string, EngineParam>&) { return stats().position_sigma; }};
}

/// What merge_radius means, in every engine that has it.
inline constexpr const char* kMergeRadiusMeaning =
    "reports of one tick within this of a stronger one join it, merged into one at their power-weighted centre of "
    "mass before association: for sensor models that report every detecting sensor (Oh §VIII's magnetometers). "
    "0: none";

/// How close two reports of one tick must lie to be merged into one before tracking: 0 (none)
/// when the sensor model reports a target once a tick, else the reach that joins one target's
/// reports (measured on the model by the probe).
inline ParamDerivation mergeRadiusDerivation() {
  return {"0 when the sensor model reports a target once a tick, else the distance that joins one target's reports",
          [](const StatisticsSource& stats, const std::map<std::string, EngineParam>&) {
            return stats().report_merge_radius;
          }};
}

/// The prior std. deviation of a new track's velocity per axis: the rms velocity of new targets,
/// widened by one tick of process noise (so that it is never 0 for targets that start at rest).
inline ParamDerivation newTrackVelocityDerivation() {
  return {"rms velocity of new targets per axis, with one tick of process noise",
          [](const StatisticsSource& stats, const std::map<std::string, EngineParam>&) {
            const ObservationStatistics& s = stats();
            const double q = s.process_noise_sigma * s.delta;
            return Derived{std::hypot(s.velocity_sigma.value, q), "hypot(" + shortNumber(s.velocity_sigma.value) +
                                                                      " (" + s.velocity_sigma.how + "), q delta)"};
          }};
}

/// v-bar of MCMCDA's links: the targets' speed bound plus 3 sqrt 2 of the resolved
/// `measurement_sigma` (two reports one tick apart differ by the step plus two errors per axis).
inline ParamDerivation linkSpeedDerivation() {
  return {"the targets' speed bound + 3 sqrt 2 measurement_sigma",
          [](const StatisticsSource& stats, const std::map<std::string, EngineParam>& r) {
            const ObservationStatistics& s = stats();
            const double sigma = r.at("measurement_sigma").value;
            return Derived{s.max_speed.value + 3.0 * std::sqrt(2.0) * sigma,
                           shortNumber(s.max_speed.value) + " (" + s.max_speed.how + ") + 3 sqrt 2 x sigma " +
                               shortNumber(sigma)};
          }};
}

/// pz of eq. (3): how targets end (death probability, leaving the region, lifetimes).
inline ParamDerivation terminationDerivation() {
  return {"targets.death_probability, leaving the region, scripted and drawn lifetimes",
          [](const StatisticsSource& stats, const std::map<std::string, EngineParam>&) {
            return stats().termination_probability;
          }};
}

/// lambda_b of eq. (3): new targets per unit area per tick.
inline ParamDerivation birthDensityDerivation() {
  return {"targets.birth_rate, the scripted and the drawn targets",
          [](const StatisticsSource& stats, const std::map<std::string, EngineParam>&) { return stats().birth_density; }};
}

}  // namespace wsn::common

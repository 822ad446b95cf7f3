// Derivations that several engines share: a parameter with the same physical meaning (a report's
// error, a new track's velocity prior) is derived from the scenario the same way in every engine.
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

}  // namespace wsn::common

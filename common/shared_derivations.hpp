// Derivations that several components share: a parameter with the same physical meaning (a report's
// error, a new track's velocity prior, the targets' speed, births and ends) is derived from the
// scenario the same way in every engine and association.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "common/observation_statistics.hpp"
#include "common/param_spec.hpp"
#include "common/track_confirmation.hpp"

namespace wsn::common {

/// R = r^2 I of a report: the sensor model's measured report error.
inline ParamDerivation reportErrorDerivation() {
  return {
      "the sensor model's report error (localisation and fusion)",
      [](const StatisticsSource& stats, const std::map<std::string, EngineParam>&) { return stats().position_sigma; }};
}

/// How many consecutive misses end a track (or bound a gap in it), as every engine judges them: at
/// the newest tick, where the reports of the last few ticks may still be on their way, a run of k
/// misses is rarer than 1 % once prod_{j<k} (1 - pd_j) <= 0.01, pd_j the chance that a live
/// target's report of the tick j ticks back has arrived (common::rareLiveEdgeMissRun). A report
/// that is only late is therefore not taken for a miss, and one that is on time is not waited for
/// longer than its lag needs. At least `at_least`, at most `at_most` (0: the window size).
inline ParamDerivation liveEdgeMissDerivation(std::int32_t at_least, std::int32_t at_most) {
  return {"consecutive misses at the newest ticks rarer than 1 %, a report counted once it has arrived (sensed, "
          "and delivered with a delay up to its lag)" +
              (at_least > 1 ? ", at least " + std::to_string(at_least) : std::string()) +
              (at_most == 0 ? ", at most window_size" : std::string()),
          [at_least, at_most](const StatisticsSource& stats, const std::map<std::string, EngineParam>&) {
            const ObservationStatistics& s = stats();
            const auto pd = s.detectionByLag();
            const std::int32_t cap = at_most == 0 ? s.window_size : at_most;
            const std::int32_t k = std::max(at_least, rareLiveEdgeMissRun(pd, kRareMissRun, cap));
            return Derived{static_cast<double>(k),
                           (at_least > 1 ? "max(" + std::to_string(at_least) + ", " : std::string()) +
                               "smallest k with prod_{j<k} (1 - pd_j) <= 0.01" + (at_least > 1 ? ")" : "") +
                               ", pd_j arrived by lag j: " + shortNumber(pd.front()) + " on time .. " +
                               shortNumber(pd.back()) + " in the window" +
                               (at_most == 0 ? ", at most window_size " + std::to_string(cap) : std::string())};
          }};
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

/// The reports a new track needs before it is reported, with the fewest wrong track-ticks per tick
/// (common/track_confirmation.hpp): chains of clutter that fit the gates of `gate_param`, each kept
/// for `chain_param` ticks (a lone report: one), against the wait of every new target; at most
/// max_n. Reads the resolved false_alarm_density, detection_probability, birth_density,
/// measurement_sigma and initial_velocity_sigma: 1 without clutter.
inline Derived clutterConfirmation(const ObservationStatistics& s, const std::map<std::string, EngineParam>& r,
                                   const std::string& gate_param, const std::string& chain_param,
                                   std::int32_t max_n) {
  const double lambda_f = r.at("false_alarm_density").value;
  const double pd = r.at("detection_probability").value;
  const double births = birthsPerTick(r.at("birth_density").value, s.region_area, s.run_ticks);
  const auto gates = newTrackGates(r.at(gate_param).value, r.at("measurement_sigma").value,
                                   r.at("initial_velocity_sigma").value, s.process_noise_sigma, s.delta);
  // A chain of clutter is reported until chain_param ticks pass without a continuation; a lone
  // report (n = 1) only at the tick it arrives, unless the next one continues it.
  const double chain_life = r.at(chain_param).value;
  const auto n = leastCostConfirmation(
      [&](std::int32_t k) {
        return falseTrackRate(k, lambda_f, s.region_area, gates.first, gates.later) * (k == 1 ? 1.0 : chain_life);
      },
      1.0, births, [&](std::int32_t k) { return ticksForReports(k, pd); }, 1, max_n);
  return Derived{static_cast<double>(n), "fewest wrong track-ticks: chains of clutter (lambda_f " +
                                             shortNumber(lambda_f) + " over " + shortNumber(s.region_area) +
                                             ", each kept " + chain_param + " ticks, a lone report 1) against the wait of " +
                                             shortNumber(births) + " births per tick at pd " + shortNumber(pd)};
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

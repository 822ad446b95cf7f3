#include "supernode/mcmcda/mcmcda_params.hpp"

#include <algorithm>
#include <string>

#include "common/shared_derivations.hpp"
#include "common/track_confirmation.hpp"

namespace wsn::supernode::mcmcda {
namespace {

using common::Derived;
using common::shortNumber;
using Statistics = common::ObservationStatistics;
using Resolved = std::map<std::string, common::EngineParam>;

/// A run of misses this rare ends a track.
constexpr double kRareMissRun = 0.01;

}  // namespace

std::map<std::string, common::ParamDerivation> paramDerivations() {
  std::map<std::string, common::ParamDerivation> d;
  d["detection_probability"] = {
      "the sensor model's sensing probability x the share of the window's reports that have arrived when the "
      "engine decides (delays included)",
      [](const common::StatisticsSource& stats, const Resolved&) {
        const Statistics& s = stats();
        // The posterior weighs every tick of the window with one pd, but at the newest tick the last
        // ticks' delayed reports are still on their way: with the in-window pd (0.9999 at pte = 0,
        // pde = 0.3) every late report was an unlikely miss and tracks broke at the live edge, so
        // that eps_K was worse without loss than with 10 % of it.
        const auto by_lag = s.detectionByLag();
        return Derived{s.windowDetectionProbability(),
                       shortNumber(s.sensing_probability.value) + " sensed (" + s.sensing_probability.how +
                           ") x arrival averaged over the window's lags (" + shortNumber(by_lag.front()) +
                           " on time .. " + shortNumber(by_lag.back()) + " in the window; " +
                           s.delivery_probability.how + ")"};
      }};
  d["termination_probability"] = common::terminationDerivation();
  d["birth_density"] = common::birthDensityDerivation();
  d["false_alarm_density"] = {
      "the sensor model's false reports x the network's delivery",
      [](const common::StatisticsSource& stats, const Resolved&) {
        const Statistics& s = stats();
        return Derived{s.falseAlarmDensity(), shortNumber(s.false_report_density.value) + " reported (" +
                                                  s.false_report_density.how + ") x " +
                                                  shortNumber(s.delivery_probability.value) + " delivered"};
      }};
  d["measurement_sigma"] = common::reportErrorDerivation();
  d["merge_radius"] = common::mergeRadiusDerivation();
  d["initial_velocity_sigma"] = common::newTrackVelocityDerivation();
  d["max_speed"] = common::linkSpeedDerivation();
  d["max_gap"] = {"ticks until a run of misses at the newest tick (sensed and not delayed) is rarer than 1 %, at "
                  "most window_size",
                  [](const common::StatisticsSource& stats, const Resolved&) {
                    const Statistics& s = stats();
                    // Judged at the live edge, where a delayed report has not arrived yet: a
                    // track whose reports are late must still be continued and reported.
                    const double pd = s.onTimeDetectionProbability();
                    return Derived{static_cast<double>(common::rareMissRun(pd, kRareMissRun, s.window_size)),
                                   "smallest k with (1 - pd)^k <= 0.01 at pd " + shortNumber(pd) +
                                       " on time, at most window_size " + std::to_string(s.window_size)};
                  }};
  d["confirm_observations"] = {
      "observations that balance reported chains of clutter against the wait of every new target",
      [](const common::StatisticsSource& stats, const Resolved& r) {
        return common::clutterConfirmation(stats(), r, "greedy_gate_chi2", "max_gap", std::max(2, stats().window_size));
      }};
  return d;
}

const config::FieldTable<McmcdaParams>& paramTable() {
  using config::integer;
  using config::real;
  static const config::FieldTable<McmcdaParams> table{
      "tracker.params (mcmcda)",
      {
          integer<McmcdaParams>("iterations", &McmcdaParams::iterations, 1.0, 1e7, "",
                                "nmc: chain iterations per tick"),
          real<McmcdaParams>(
              "detection_probability", [](McmcdaParams & p) -> auto& { return p.model.detection_probability; },
              config::closed(1e-3, 0.999), "",
              "pd of eq. (3): probability that a live target's report reaches the window at a tick (detection "
              "times delivery)"),
          real<McmcdaParams>(
              "termination_probability", [](McmcdaParams & p) -> auto& { return p.model.termination_probability; },
              config::closed(1e-6, 0.999), "", "pz of eq. (3): probability that a target disappears at a tick"),
          real<McmcdaParams>(
              "birth_density", [](McmcdaParams & p) -> auto& { return p.model.birth_density; },
              config::closed(1e-12, 1.0), "1/(separation² tick)",
              "lambda_b of eq. (3): new targets per unit area per tick"),
          real<McmcdaParams>(
              "false_alarm_density", [](McmcdaParams & p) -> auto& { return p.model.false_alarm_density; },
              config::closed(1e-12, 1.0), "1/(separation² tick)",
              "lambda_f of eq. (3): delivered false reports per unit area per tick"),
          real<McmcdaParams>(
              "measurement_sigma", [](McmcdaParams & p) -> auto& { return p.model.measurement_sigma; },
              config::closed(1e-3, 100.0), "separations",
              "std. deviation of a fused observation's position error per axis, R = sigma^2 I (sensor separations)"),
          real<McmcdaParams>(
              "initial_velocity_sigma", [](McmcdaParams & p) -> auto& { return p.model.initial_velocity_sigma; },
              config::closed(1e-3, 100.0), "separations/tick",
              "prior std. deviation of a new track's velocity per axis (sensor separations per tick)"),
          real<McmcdaParams>(
              "max_speed", [](McmcdaParams & p) -> auto& { return p.model.max_speed; }, config::closed(1e-3, 1000.0),
              "separations/tick",
              "v-bar: an observation d ticks after another is a candidate successor within d * v-bar"),
          integer<McmcdaParams>(
              "max_gap", [](McmcdaParams & p) -> auto& { return p.model.max_gap; }, 1.0, 50.0, "ticks",
              "d-bar: largest tick gap inside a track (d-bar - 1 consecutive misses)"),
          real<McmcdaParams>(
              "stop_probability", [](McmcdaParams & p) -> auto& { return p.model.stop_probability; },
              config::closed(1e-3, 0.999), "",
              "gamma: the extension proposal stops after each step with this probability"),
          real<McmcdaParams>(
              "greedy_gate_chi2", &McmcdaParams::greedy_gate_chi2, config::closed(0.1, 1000.0), "",
              "gate (squared Mahalanobis distance) of the greedy start that joins the newest observations to tracks"),
          integer<McmcdaParams>(
              "confirm_observations", &McmcdaParams::confirm_observations, 1.0, 1000.0, "observations",
              "observations a track needs (in all, before the window included) before it is reported"),
          real<McmcdaParams>("merge_radius", &McmcdaParams::merge_radius, config::closed(0.0, 1e6), "separations",
                             common::kMergeRadiusMeaning),
      }};
  return table;
}

McmcdaParams McmcdaParams::fromContext(const EngineContext& context) {
  McmcdaParams p = common::decodeParams(paramTable(), context.params);
  p.model.process_noise_sigma = context.dynamics.process_noise_sigma;
  p.model.delta = context.dynamics.delta;
  return p;
}

}  // namespace wsn::supernode::mcmcda

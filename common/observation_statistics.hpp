// What a scenario's own models say about the observations a supernode receives and the targets
// behind them: the quantities from which engines derive the parameters a scenario leaves out
// (tracker.params: auto). Plain data, so the engines derive without knowing the sensor or network
// models; observation_model/ measures it from those models.
#pragma once

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace wsn::common {

/// A value computed from the scenario, with how, in words for the resolved scenario.yaml.
struct Derived {
  double value = 0.0;
  std::string how;
};

struct ObservationStatistics {
  // Measured on the scenario's own sensor model (a deterministic simulation of its field).
  Derived position_sigma;        ///< per-axis rms error of a target's report (region units)
  Derived sensing_probability;   ///< a live target gives at least one report at a tick
  Derived false_report_density;  ///< reports that are not a target's one report, per area per tick
  /// Same-tick reports closer than this are one target's (0: the model reports a target once a
  /// tick); position_sigma is the error of the merged report then.
  Derived report_merge_radius;
  // From the network model (Oh §V, eq. 7 over the topology's hop histogram).
  Derived delivery_probability;  ///< a report reaches its supernode's window (delay < ws)
  Derived on_time_probability;   ///< a report reaches its supernode at the tick it was made (no delay)
  /// [j]: a report reaches its supernode with a delay <= j ticks, j = 0 .. ws - 1 ([0] is
  /// on_time_probability, [ws - 1] delivery_probability): how much of the last ticks an engine
  /// deciding at the newest tick has received.
  std::vector<double> arrival_by_lag;
  // From the target model (targets, dynamics, region).
  Derived birth_density;            ///< new targets per area per tick
  Derived termination_probability;  ///< a live target ends (dies or leaves the region) at a tick
  Derived velocity_sigma;           ///< per-axis rms velocity of a new target (per tick)
  Derived max_speed;                ///< bound on a target's speed (per tick), drift over its life included
  /// Sensors within the weakest target's sensing range, on average: sensor density x pi SR^2 (how
  /// many raw detections its cluster holds, for engines that cluster detections).
  Derived sensors_per_weakest_target;

  double region_area = 0.0;
  double sensor_spacing = 1.0;       ///< Ds (sensors.spacing), the rule-based engine's length unit
  double process_noise_sigma = 0.0;  ///< q of Oh eq. (8)
  double delta = 1.0;
  std::int32_t window_size = 10;
  std::int32_t run_ticks = 100;

  /// pd of Oh eq. (3): sensed and delivered into the window.
  double detectionProbability() const { return sensing_probability.value * delivery_probability.value; }
  /// A live target's report is there at the newest tick: what a run of misses at the live edge
  /// (a track's deletion, a gap) is judged by, since delayed reports arrive only later.
  double onTimeDetectionProbability() const { return sensing_probability.value * on_time_probability.value; }
  /// [j]: a live target's report of the tick j ticks back is there at the newest tick, sensed and
  /// arrived (what a miss count at the live edge is judged by; common::rareLiveEdgeMissRun).
  std::vector<double> detectionByLag() const {
    std::vector<double> pd = arrival_by_lag;
    if (pd.empty()) pd.push_back(delivery_probability.value);
    for (double& p : pd) p *= sensing_probability.value;
    return pd;
  }
  /// A live target's report of a tick in the window is there when the engine decides at the newest
  /// tick: detectionByLag() averaged over the window's ticks (what a posterior over the whole
  /// window, with one pd for all its ticks, expects to see of a target).
  double windowDetectionProbability() const {
    const auto pd = detectionByLag();
    double sum = 0.0;
    for (double p : pd) sum += p;
    return sum / static_cast<double>(pd.size());
  }
  /// lambda_f of Oh eq. (3): false reports that are delivered into the window.
  double falseAlarmDensity() const { return false_report_density.value * delivery_probability.value; }
};

/// A number as a derivation note shows it: four significant digits.
inline std::string shortNumber(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

}  // namespace wsn::common

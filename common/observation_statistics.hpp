// What a scenario's own models say about the observations a supernode receives and the targets
// behind them: the quantities from which engines derive the parameters a scenario leaves out
// (tracker.params: auto). Plain data, so the engines derive without knowing the sensor or network
// models; observation_model/ measures it from those models.
#pragma once

#include <cstdint>
#include <sstream>
#include <string>

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

// Acoustic sensors that hear moving targets with the Doppler effect (An et al. 2014 eq. 1-4) and
// sporadic environmental noise (An et al. 2013 eq. 6-8): each sensor's raw detection per tick.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/geometry.hpp"
#include "common/messages.hpp"
#include "common/scenario_config.hpp"
#include "node/acoustic/config.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/tiling.hpp"

namespace wsn::node::acoustic {

/// A target's path in continuous time: straight between its positions at consecutive ticks.
/// Times in seconds; the target exists (and emits) on [start(), end()].
class Trajectory {
 public:
  /// `positions[i]` is the position at time (first_tick + i) * tick_s; at least one position.
  Trajectory(std::int32_t first_tick, double tick_s, std::vector<common::Vec2> positions);
  double start() const { return first_tick_ * tick_s_; }
  double end() const { return (first_tick_ + static_cast<std::int32_t>(positions_.size()) - 1) * tick_s_; }
  /// Position at time `time` in [start(), end()].
  common::Vec2 at(double time) const;
  /// The retarded emission time of a sound heard at `listener` at time `time`: the tau in
  /// [start(), end()] with sound_speed (time - tau) = |listener - p(tau)|, unique while the target
  /// is slower than sound. nullopt when even the first emission has not reached the listener;
  /// end() when the last emission already passed it.
  std::optional<double> retardedTime(common::Vec2 listener, double time, double sound_speed) const;

 private:
  std::int32_t first_tick_;
  double tick_s_;
  std::vector<common::Vec2> positions_;
};

/// The sensors of one tile, with the acoustic model. Outputs are a pure function of (scenario,
/// seed, tick), the same for every tiling.
///
/// Per tick t (the N = tick_s / detection_step_s detection steps k with k dt in ((t-1) tick_s,
/// t tick_s]): sensor s hears at step k the emissions j of target i with
/// tau*(t_k-1) < j dt <= tau*(t_k) (eq. 3, by the retarded time), each of power
/// Pt,i (1 + f U(-1, 1)) / max(d_s,j, Vs dt / 2)^alpha with Pt,i = cs SR_i^alpha (eq. 4); its
/// target power for the tick is the largest step power, P_s = max_k Ps,k. It detects when
/// P_s + noise >= cs and reports floor((P_s + noise) / cs).
/// What the acoustic sensors of a run are made of: the model's settings, the default sensing
/// range SR, each scripted target's own SR (0: the default) and the seed.
struct AcousticFieldConfig {
  AcousticSettings settings;
  double sensing_range = 1.5;
  std::vector<double> scripted_sensing_ranges;
  std::uint64_t seed = 1;
};

/// What the acoustic field reads of the sensor model, the seed and the scripted targets; throws
/// std::invalid_argument when the sensors are not acoustic.
AcousticFieldConfig fieldConfigOf(const common::SensorModelConfig& sensor_model, std::uint64_t seed,
                                  const std::vector<common::TargetSpec>& scripted_targets);
/// The same, split off a whole scenario (tests and benchmarks).
AcousticFieldConfig fieldConfigOf(const common::Scenario& scenario);

class AcousticField {
 public:
  /// Throws std::invalid_argument when the tile does not lie in the layout's cell grid. Holds
  /// references to the layout and truth, which must outlive it.
  AcousticField(AcousticFieldConfig config, const common::SensorLayout& layout, const Tile& tile,
                const common::Truth& truth);

  /// This tile's detections at `tick`, sorted by sensor id.
  std::vector<common::Report> detect(std::int32_t tick) const;

  /// The environmental-noise power sensor `sensor` hears during `tick` (0 when none).
  double noisePower(common::SensorId sensor, std::int32_t tick) const;
  /// The largest step power Ps,k over the steps of `tick` at `listener`, and the target that
  /// contributes most to that step (kFalseAlarm when none is heard).
  std::pair<double, common::TargetId> targetPower(common::Vec2 listener, std::int32_t tick) const;

 private:
  struct Source {
    common::TargetId id;
    double power;  ///< Pt = cs SR^alpha
    Trajectory path;
    double reach;  ///< beyond this from every point of the path, the target adds < cs / K per step
  };
  /// The targets whose sound can be heard during `tick`, with their paths.
  std::vector<Source> sources(std::int32_t tick) const;
  std::pair<double, common::TargetId> targetPower(common::Vec2 listener, std::int32_t tick,
                                                  std::span<const Source> sources) const;
  /// Pt = cs SR^alpha of target `id`.
  double sourcePower(common::TargetId id) const;

  const common::SensorLayout* layout_;
  const common::Truth* truth_;
  AcousticFieldConfig config_;
  Tile tile_;
  std::vector<common::SensorId> owned_;  ///< this tile's sensors, sorted
  std::int64_t steps_per_tick_ = 20;
  double emissions_per_step_ = 2.0;       ///< n_e: a bound on the emissions one sensor hears in one step
  std::int32_t history_ticks_ = 1;        ///< ticks of each target's path that can still be heard
  std::vector<std::int32_t> noise_ticks_;  ///< duration of each noise component, in ticks
};

}  // namespace wsn::node::acoustic

// Ground truth: target trajectories as a pure function of (scenario, seed), Oh eq. (8), so
// that every process computes the same targets without exchanging them.
#pragma once

#include <cstdint>
#include <vector>

#include "common/messages.hpp"
#include "common/scenario_config.hpp"

namespace wsn::common {

/// One target's state at one tick.
struct TargetState {
  TargetId id = 0;
  double x = 0.0;
  double y = 0.0;
  double vx = 0.0;
  double vy = 0.0;
  TargetClass target_class = TargetClass::kUnknown;  ///< what the target is (its scripted class)
  friend bool operator==(const TargetState&, const TargetState&) = default;
};

/// Oh §VII-A: the per-axis speed magnitude |vx|, |vy| of a random target is uniform in [min, max]
/// per tick (slow 0-1, medium 1-2, fast 2-5), with a random sign.
struct SpeedInterval {
  double min = 0.0;
  double max = 0.0;
};
SpeedInterval speedInterval(SpeedClass speed_class);

/// What the ground truth is a function of: the scenario's world, its seed and length.
struct TruthConfig {
  Rect region;
  TargetsConfig targets;
  DynamicsConfig dynamics;
  std::uint64_t seed = 1;    ///< run.seed
  std::int32_t ticks = 100;  ///< run.ticks (T)
};

/// The truth config of `scenario`: split off at the role edge.
TruthConfig truthConfig(const Scenario& scenario);

/// All targets alive at each tick 1..T, sorted by id.
class Truth {
 public:
  explicit Truth(const TruthConfig& config);
  /// Targets alive at `tick` (empty outside 1..T).
  const std::vector<TargetState>& at(std::int32_t tick) const;
  std::int32_t ticks() const { return static_cast<std::int32_t>(per_tick_.size()) - 1; }
  /// Number of distinct targets over the whole run.
  std::int32_t targetCount() const { return target_count_; }
  /// What target `id` is: its scripted class; unknown for drawn and born targets.
  TargetClass targetClass(TargetId id) const;

 private:
  std::vector<std::vector<TargetState>> per_tick_;  // index 0 unused
  std::int32_t target_count_ = 0;
  std::vector<TargetClass> classes_;  // by id
};

}  // namespace wsn::common

#include "common/truth.hpp"

#include <algorithm>

#include "common/rng.hpp"

namespace wsn::common {
namespace {

struct LiveTarget {
  TargetState state;
  std::int32_t disappear_tick;  // exclusive; INT32_MAX when open-ended
  bool mortal;                  // subject to the per-tick death probability pz
};

/// Oh eq. (8): x_{t+delta} = A_delta x_t + G_delta w_t with w_t ~ N(0, q^2 I).
void propagate(TargetState& s, const DynamicsConfig& dynamics, Stream& noise) {
  const double d = dynamics.delta;
  const double q = dynamics.process_noise_sigma;
  const double wx = q * noise.normal();
  const double wy = q * noise.normal();
  s.x += d * s.vx + 0.5 * d * d * wx;
  s.y += d * s.vy + 0.5 * d * d * wy;
  s.vx += d * wx;
  s.vy += d * wy;
}

}  // namespace

SpeedInterval speedInterval(SpeedClass speed_class) {
  switch (speed_class) {
    case SpeedClass::kSlow: return {0.0, 1.0};
    case SpeedClass::kMedium: return {1.0, 2.0};
    case SpeedClass::kFast: return {2.0, 5.0};
  }
  return {1.0, 2.0};
}

TruthConfig truthConfig(const Scenario& scenario) {
  return {scenario.region, scenario.targets, scenario.dynamics, scenario.run.seed, scenario.run.ticks};
}

Truth::Truth(const TruthConfig& config) {
  const std::int32_t ticks = config.ticks;
  const std::uint64_t seed = config.seed;
  per_tick_.assign(static_cast<std::size_t>(ticks) + 1, {});

  std::vector<LiveTarget> live;
  TargetId next_id = 0;
  // Scripted targets keep ids 0..n-1 in file order; random births follow.
  std::vector<std::pair<TargetSpec, TargetId>> scripted;
  for (const auto& spec : config.targets.scripted) scripted.emplace_back(spec, next_id++);

  const SpeedInterval speed = speedInterval(config.targets.speed_class);
  const double birth_mean = config.targets.birth_rate * config.region.area();

  for (std::int32_t t = 1; t <= ticks; ++t) {
    // Move everyone alive at t-1 to t, then retire the dead and the departed.
    std::vector<LiveTarget> next;
    for (auto& target : live) {
      if (t >= target.disappear_tick) continue;
      if (target.mortal) {
        Stream death(seed, Purpose::kTruthDeath, static_cast<std::uint64_t>(target.state.id), t);
        if (death.bernoulli(config.targets.death_probability)) continue;
      }
      Stream noise(seed, Purpose::kTruthProcessNoise, static_cast<std::uint64_t>(target.state.id), t);
      propagate(target.state, config.dynamics, noise);
      if (!config.region.contains({target.state.x, target.state.y})) continue;
      next.push_back(target);
    }
    live = std::move(next);

    for (const auto& [spec, id] : scripted) {
      if (spec.appear_tick != t) continue;
      const std::int32_t end = spec.disappear_tick > 0 ? spec.disappear_tick : INT32_MAX;
      live.push_back({{id, spec.position.x, spec.position.y, spec.velocity.x, spec.velocity.y}, end, false});
    }

    Stream births(seed, Purpose::kTruthBirth, 0, t);
    const std::uint64_t born = births.poisson(birth_mean);
    for (std::uint64_t j = 0; j < born; ++j) {
      const TargetId id = next_id++;
      Stream init(seed, Purpose::kTruthInitial, static_cast<std::uint64_t>(id), t);
      TargetState s{id, init.uniform(config.region.x_min, config.region.x_max),
                    init.uniform(config.region.y_min, config.region.y_max), 0.0, 0.0};
      s.vx = init.uniform(speed.min, speed.max) * (init.bernoulli(0.5) ? 1.0 : -1.0);
      s.vy = init.uniform(speed.min, speed.max) * (init.bernoulli(0.5) ? 1.0 : -1.0);
      live.push_back({s, INT32_MAX, true});
    }

    auto& now = per_tick_[static_cast<std::size_t>(t)];
    for (const auto& target : live) now.push_back(target.state);
    std::sort(now.begin(), now.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  }
  target_count_ = next_id;
}

const std::vector<TargetState>& Truth::at(std::int32_t tick) const {
  static const std::vector<TargetState> kNone;
  if (tick < 1 || tick >= static_cast<std::int32_t>(per_tick_.size())) return kNone;
  return per_tick_[static_cast<std::size_t>(tick)];
}

}  // namespace wsn::common

#include "common/truth.hpp"

#include <algorithm>
#include <cmath>

#include "common/rng.hpp"

namespace wsn::common {
namespace {

/// Where a waypoint target is on its route.
struct RouteProgress {
  std::size_t leg = 0;            // on the leg from waypoints[leg] to waypoints[leg + 1], or at the last waypoint
  double along_leg = 0.0;         // from waypoints[leg]
  std::int32_t rest_left = 0;     // ticks still to rest at waypoints[leg]
  std::size_t next_stop = 0;      // into TargetSpec::stops
  bool finished = false;          // past its last waypoint: gone
};

struct LiveTarget {
  TargetState state;
  std::int32_t disappear_tick = INT32_MAX;  // exclusive; INT32_MAX when open-ended
  bool mortal = false;                      // subject to the per-tick death probability pz
  const TargetSpec* route = nullptr;        // a waypoint target's spec; null under eq. (8)
  RouteProgress progress;
};

Vec2 legDirection(const std::vector<Vec2>& waypoints, std::size_t leg) {
  const Vec2 d = waypoints[leg + 1] - waypoints[leg];
  return (1.0 / std::hypot(d.x, d.y)) * d;
}

/// Motion along leg `leg` of a route with `speeds`: the speed goes from speeds[leg] to speeds[leg + 1]
/// at the constant acceleration a = (v1^2 - v0^2) / (2 L), so v(s)^2 = v0^2 + 2 a s at s along it.
struct LegMotion {
  double start_speed = 0.0;
  double end_speed = 0.0;
  double acceleration = 0.0;
  double length = 0.0;

  LegMotion(const TargetSpec& spec, std::size_t leg)
      : start_speed(spec.speeds[leg]), end_speed(spec.speeds[leg + 1]),
        length(distance(spec.waypoints[leg], spec.waypoints[leg + 1])) {
    acceleration = (end_speed * end_speed - start_speed * start_speed) / (2.0 * length);
  }
  double speedAt(double along) const {
    return std::sqrt(std::max(0.0, start_speed * start_speed + 2.0 * acceleration * along));
  }
  /// Ticks from `along` to the leg's end.
  double timeToEnd(double along) const {
    if (acceleration == 0.0) return (length - along) / start_speed;
    return (end_speed - speedAt(along)) / acceleration;
  }
  /// Distance covered from `along` in `time` ticks (less than timeToEnd(along)).
  double distanceIn(double along, double time) const {
    return speedAt(along) * time + 0.5 * acceleration * time * time;
  }
};

/// The state on the route: on a leg, moving along it at its speed there; at rest or at the end, still.
void placeOnRoute(TargetState& s, const TargetSpec& spec, const RouteProgress& p, bool moving) {
  const auto& w = spec.waypoints;
  const bool on_leg = p.leg + 1 < w.size();
  const Vec2 direction = on_leg ? legDirection(w, p.leg) : Vec2{};
  const Vec2 position = on_leg ? w[p.leg] + p.along_leg * direction : w[p.leg];
  const double speed = !on_leg ? 0.0 : spec.speeds.empty() ? spec.speed : LegMotion(spec, p.leg).speedAt(p.along_leg);
  const Vec2 velocity = moving && on_leg ? speed * direction : Vec2{};
  s.x = position.x;
  s.y = position.y;
  s.vx = velocity.x;
  s.vy = velocity.y;
}

/// A waypoint target at appear_tick: at its first waypoint, resting there if a stop says so.
void startRoute(LiveTarget& target) {
  const TargetSpec& spec = *target.route;
  RouteProgress& p = target.progress;
  if (!spec.stops.empty() && spec.stops.front().at == 0) {
    p.rest_left = spec.stops.front().ticks;
    p.next_stop = 1;
  }
  placeOnRoute(target.state, spec, p, p.rest_left == 0 && spec.waypoints.size() > 1);
}

/// One tick along the route, exactly: a tick that reaches a waypoint goes on along the next leg by
/// what is left of `speed` (with `speeds`, of the tick's time), unless the target stops there (the
/// tick ends at the waypoint) or it is the last one. Sets `finished` the tick after the last
/// waypoint (and its rest).
void advanceOnRoute(LiveTarget& target) {
  const TargetSpec& spec = *target.route;
  const auto& w = spec.waypoints;
  RouteProgress& p = target.progress;
  if (p.rest_left > 0) {
    --p.rest_left;
    placeOnRoute(target.state, spec, p, false);
    return;
  }
  if (p.leg + 1 >= w.size()) {
    p.finished = true;
    return;
  }
  // What is left of the tick: a distance at one speed, a time where the speed changes along the legs.
  const bool one_speed = spec.speeds.empty();
  double remaining = one_speed ? spec.speed : 1.0;
  while (true) {
    const double to_leg_end = one_speed ? distance(w[p.leg], w[p.leg + 1]) - p.along_leg
                                        : LegMotion(spec, p.leg).timeToEnd(p.along_leg);
    if (remaining < to_leg_end) {
      p.along_leg += one_speed ? remaining : LegMotion(spec, p.leg).distanceIn(p.along_leg, remaining);
      placeOnRoute(target.state, spec, p, true);
      return;
    }
    remaining -= to_leg_end;
    ++p.leg;
    p.along_leg = 0.0;
    if (p.next_stop < spec.stops.size() && static_cast<std::size_t>(spec.stops[p.next_stop].at) == p.leg) {
      p.rest_left = spec.stops[p.next_stop++].ticks;
      placeOnRoute(target.state, spec, p, false);
      return;
    }
    if (p.leg + 1 == w.size()) {
      placeOnRoute(target.state, spec, p, false);
      return;
    }
  }
}

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

/// Oh §VII-A's "10 targets appear and disappear at random times": target `id`'s life, velocity
/// and start, drawn from its own stream so that one target's draw never moves another's.
TargetSpec drawnTarget(const TruthConfig& config, TargetId id) {
  const TargetsConfig& targets = config.targets;
  Stream draw(config.seed, Purpose::kTruthDrawn, static_cast<std::uint64_t>(id), 0);
  const std::int32_t longest = std::min(targets.lifetime_max, config.ticks);
  const std::int32_t shortest = std::min(targets.lifetime_min, longest);
  const auto life = static_cast<std::int32_t>(std::min<double>(
      longest, shortest + std::floor(draw.uniform() * (longest - shortest + 1))));
  const auto latest_start = static_cast<double>(config.ticks + 1 - life);  // the life fits the run
  TargetSpec spec;
  spec.appear_tick = static_cast<std::int32_t>(std::min(latest_start, 1.0 + std::floor(draw.uniform() * latest_start)));
  spec.disappear_tick = spec.appear_tick + life;
  const SpeedInterval speed = speedInterval(targets.speed_class);
  spec.velocity.x = draw.uniform(speed.min, speed.max) * (draw.bernoulli(0.5) ? 1.0 : -1.0);
  spec.velocity.y = draw.uniform(speed.min, speed.max) * (draw.bernoulli(0.5) ? 1.0 : -1.0);

  // The start: its straight path stays 5 % in from the region's edges for the whole life, or, for
  // a path longer than the region allows, for as long as any start keeps it in.
  const Rect& r = config.region;
  const double margin_x = 0.05 * r.width();
  const double margin_y = 0.05 * r.height();
  const double inner_w = r.width() - 2.0 * margin_x;
  const double inner_h = r.height() - 2.0 * margin_y;
  double steps = (life - 1.0) * config.dynamics.delta;  // eq. (8) moves a target delta v per tick
  if (std::abs(spec.velocity.x) * steps > inner_w) steps = inner_w / std::abs(spec.velocity.x);
  if (std::abs(spec.velocity.y) * steps > inner_h) steps = inner_h / std::abs(spec.velocity.y);
  const auto start = [&](double lo, double hi, double v) {
    const double travel = v * steps;
    return draw.uniform(lo + std::max(0.0, -travel), hi - std::max(0.0, travel));
  };
  spec.position.x = start(r.x_min + margin_x, r.x_max - margin_x, spec.velocity.x);
  spec.position.y = start(r.y_min + margin_y, r.y_max - margin_y, spec.velocity.y);
  return spec;
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
  // Scripted targets keep ids 0..n-1 in file order, drawn targets (targets.count) follow, then
  // random births. A drawn target lives like a scripted one, with its plan from drawnTarget().
  std::vector<std::pair<TargetSpec, TargetId>> scripted;
  for (const auto& spec : config.targets.scripted) scripted.emplace_back(spec, next_id++);
  for (std::int32_t k = 0; k < config.targets.count; ++k) {
    const TargetId id = next_id++;
    scripted.emplace_back(drawnTarget(config, id), id);
  }

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
      if (target.route != nullptr) {
        // A route is driven exactly: no draw from the noise stream, so other targets are unmoved.
        advanceOnRoute(target);
        if (target.progress.finished) continue;
      } else {
        Stream noise(seed, Purpose::kTruthProcessNoise, static_cast<std::uint64_t>(target.state.id), t);
        propagate(target.state, config.dynamics, noise);
      }
      if (!config.region.contains({target.state.x, target.state.y})) continue;
      next.push_back(target);
    }
    live = std::move(next);

    for (const auto& [spec, id] : scripted) {
      if (spec.appear_tick != t) continue;
      const std::int32_t end = spec.disappear_tick > 0 ? spec.disappear_tick : INT32_MAX;
      LiveTarget target;
      target.state = {id, spec.position.x, spec.position.y, spec.velocity.x, spec.velocity.y};
      target.disappear_tick = end;
      if (!spec.waypoints.empty()) {
        target.route = &spec;
        startRoute(target);
      }
      live.push_back(target);
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
      LiveTarget newborn;
      newborn.state = s;
      newborn.mortal = true;
      live.push_back(newborn);
    }

    auto& now = per_tick_[static_cast<std::size_t>(t)];
    for (const auto& target : live) {
      now.push_back(target.state);
      const auto id = static_cast<std::size_t>(target.state.id);
      if (id < config.targets.scripted.size()) now.back().target_class = config.targets.scripted[id].target_class;
    }
    std::sort(now.begin(), now.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  }
  target_count_ = next_id;
  classes_.assign(static_cast<std::size_t>(next_id), TargetClass::kUnknown);
  for (std::size_t i = 0; i < config.targets.scripted.size(); ++i) classes_[i] = config.targets.scripted[i].target_class;
}

TargetClass Truth::targetClass(TargetId id) const {
  if (id < 0 || static_cast<std::size_t>(id) >= classes_.size()) return TargetClass::kUnknown;
  return classes_[static_cast<std::size_t>(id)];
}

const std::vector<TargetState>& Truth::at(std::int32_t tick) const {
  static const std::vector<TargetState> kNone;
  if (tick < 1 || tick >= static_cast<std::int32_t>(per_tick_.size())) return kNone;
  return per_tick_[static_cast<std::size_t>(tick)];
}

}  // namespace wsn::common

#include "node/acoustic/acoustic_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include "common/rng.hpp"

namespace wsn::node::acoustic {
namespace {

/// At most this many noise components: their streams are keyed by sensor * kMaxNoiseComponents + c.
constexpr std::size_t kMaxNoiseComponents = 8;
/// Far emissions are summed while they could add this share of cs in all (see sources()).
constexpr double kNegligibleShare = 1e-3;
/// A bound on how many ticks back the path of a target is followed, whatever the bounds give.
constexpr std::int32_t kMaxHistoryTicks = 200;

std::int64_t floorIndex(double time, double step) { return static_cast<std::int64_t>(std::floor(time / step + 1e-9)); }

double power(double distance, double alpha) { return alpha == 2.0 ? distance * distance : std::pow(distance, alpha); }

}  // namespace

// ---------------------------------------------------------------------------------------------
// Trajectory

Trajectory::Trajectory(std::int32_t first_tick, double tick_s, std::vector<common::Vec2> positions)
    : first_tick_(first_tick), tick_s_(tick_s), positions_(std::move(positions)) {
  if (positions_.empty()) throw std::invalid_argument("acoustic trajectory: no positions");
}

common::Vec2 Trajectory::at(double time) const {
  const double u = std::clamp((time - start()) / tick_s_, 0.0, static_cast<double>(positions_.size() - 1));
  const auto i = std::min(static_cast<std::size_t>(u), positions_.size() - 1);
  if (i + 1 >= positions_.size()) return positions_.back();
  const double f = u - static_cast<double>(i);
  return positions_[i] + f * (positions_[i + 1] - positions_[i]);
}

std::optional<double> Trajectory::retardedTime(common::Vec2 listener, double time, double sound_speed) const {
  // h(tau) = Vs (time - tau) - |listener - p(tau)| falls strictly while the target is subsonic;
  // the root is the emission heard now.
  const auto h = [&](double tau) { return sound_speed * (time - tau) - common::distance(listener, at(tau)); };
  if (time < start() || h(start()) < 0.0) return std::nullopt;
  const double upper = std::min(time, end());
  if (h(upper) >= 0.0) return upper;
  // The segment [t_i, t_i+1] holding the root: walk back from the one holding `upper`.
  auto i = static_cast<std::size_t>(std::min((upper - start()) / tick_s_, static_cast<double>(positions_.size() - 1)));
  if (i + 1 >= positions_.size() && i > 0) --i;
  while (i > 0 && h(start() + static_cast<double>(i) * tick_s_) < 0.0) --i;
  const double t0 = start() + static_cast<double>(i) * tick_s_;
  const double t1 = std::min(upper, t0 + tick_s_);
  // On the segment p(t0 + u) = a + v u, so |w - v u|^2 = Vs^2 (c - u)^2 with w = listener - a and
  // c = time - t0: A u^2 + B u + C = 0 with A = |v|^2 - Vs^2 < 0.
  const common::Vec2 a = positions_[std::min(i, positions_.size() - 1)];
  const common::Vec2 b = positions_[std::min(i + 1, positions_.size() - 1)];
  const common::Vec2 v = (1.0 / tick_s_) * (b - a);
  const common::Vec2 w = listener - a;
  const double c = time - t0;
  const double vs2 = sound_speed * sound_speed;
  const double A = v.x * v.x + v.y * v.y - vs2;
  const double B = 2.0 * (vs2 * c - (w.x * v.x + w.y * v.y));
  const double C = w.x * w.x + w.y * w.y - vs2 * c * c;
  const double span = t1 - t0;
  const double disc = B * B - 4.0 * A * C;
  if (disc >= 0.0) {
    // Both roots without cancellation (q has the sign of B); the physical one lies in the segment
    // with the sound emitted before it is heard (u <= c).
    const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    const double tolerance = 1e-9 * (1.0 + tick_s_);
    for (const double u : {q / A, q != 0.0 ? C / q : 0.0})
      if (u >= -tolerance && u <= span + tolerance && u <= c + tolerance) return t0 + std::clamp(u, 0.0, span);
  }
  // Rounding left no root in the bracket: bisection on the sign change of h.
  double lo = t0;
  double hi = t1;
  for (int n = 0; n < 60; ++n) {
    const double mid = 0.5 * (lo + hi);
    (h(mid) >= 0.0 ? lo : hi) = mid;
  }
  return lo;
}

// ---------------------------------------------------------------------------------------------
// AcousticField

AcousticFieldConfig fieldConfigOf(const common::SensorModelConfig& sensor_model, std::uint64_t seed,
                                  const std::vector<common::TargetSpec>& scripted_targets) {
  if (sensor_model.kind != "acoustic_doppler")
    throw std::invalid_argument("AcousticField: the scenario's sensor_model.kind is not acoustic_doppler");
  AcousticFieldConfig config{common::settingsOf<AcousticSettings>(sensor_model), sensor_model.sensing_range, {}, seed};
  for (const auto& spec : scripted_targets) config.scripted_sensing_ranges.push_back(spec.sensing_range);
  return config;
}

AcousticFieldConfig fieldConfigOf(const common::Scenario& scenario) {
  return fieldConfigOf(scenario.sensor_model, scenario.run.seed, scenario.targets.scripted);
}

AcousticField::AcousticField(AcousticFieldConfig config, const common::SensorLayout& layout, const Tile& tile,
                             const common::Truth& truth)
    : layout_(&layout), truth_(&truth), config_(std::move(config)), tile_(tile),
      owned_(tileSensorIds(layout, tile, "AcousticField")) {
  const auto& ac = config_.settings.acoustic;
  const auto& components = config_.settings.environmental_noise.components;
  if (components.size() > kMaxNoiseComponents)
    throw std::invalid_argument("AcousticField: " + std::to_string(components.size()) +
                                " environmental noise components; at most " + std::to_string(kMaxNoiseComponents));
  steps_per_tick_ = std::llround(ac.tick_s / ac.detection_step_s);
  for (const auto& c : components)
    noise_ticks_.push_back(std::max<std::int32_t>(1, static_cast<std::int32_t>(std::lround(c.duration_s / ac.tick_s))));

  // Bounds over the whole run: the fastest target, the largest sensing range, every target.
  double fastest = 0.0;
  double widest = config_.sensing_range;
  for (const double range : config_.scripted_sensing_ranges) widest = std::max(widest, range);
  for (std::int32_t t = 1; t <= truth.ticks(); ++t)
    for (const auto& s : truth.at(t)) fastest = std::max(fastest, std::hypot(s.vx, s.vy) / ac.tick_s);
  // Emissions heard within one step: at most floor(Vs / (Vs - v)) + 1, since consecutive steps'
  // retarded times are at most dt Vs / (Vs - v) apart.
  emissions_per_step_ = std::floor(ac.sound_speed / std::max(ac.sound_speed - fastest, 1e-9)) + 1.0;
  const double all = std::max(1, truth.targetCount());
  const double far = widest * std::pow(emissions_per_step_ * (1.0 + ac.power_fluctuation) * all / kNegligibleShare,
                                       1.0 / config_.settings.alpha);
  history_ticks_ = std::min(kMaxHistoryTicks, static_cast<std::int32_t>(std::ceil(far / (ac.sound_speed * ac.tick_s))) + 1);
}

double AcousticField::sourcePower(common::TargetId id) const {
  const auto& scripted = config_.scripted_sensing_ranges;
  const auto index = static_cast<std::size_t>(id);
  const double range = id >= 0 && index < scripted.size() && scripted[index] > 0.0 ? scripted[index] : config_.sensing_range;
  return config_.settings.acoustic.threshold * std::pow(range, config_.settings.alpha);
}

std::vector<AcousticField::Source> AcousticField::sources(std::int32_t tick) const {
  const auto& ac = config_.settings.acoustic;
  // Paths over the last history_ticks_ ticks, by target id (ordered: sums are in id order).
  std::map<common::TargetId, std::pair<std::int32_t, std::vector<common::Vec2>>> paths;
  for (std::int32_t t = std::max(1, tick - history_ticks_); t <= tick; ++t)
    for (const auto& s : truth_->at(t)) {
      paths.try_emplace(s.id, t, std::vector<common::Vec2>{}).first->second.second.push_back({s.x, s.y});
    }
  std::vector<Source> out;
  for (auto& [id, path] : paths) {
    const double pt = sourcePower(id);
    out.push_back({id, pt, Trajectory(path.first, ac.tick_s, std::move(path.second)), 0.0});
  }
  // A target adds less than cs / K at a sensor farther than R = (n_e (1 + f) Pt / (cs / K))^(1/alpha)
  // from every emission it can hear in a step, so K sources together stay below cs there.
  const double k = static_cast<double>(std::max<std::size_t>(out.size(), 1));
  for (auto& source : out)
    source.reach = std::pow(emissions_per_step_ * (1.0 + ac.power_fluctuation) * source.power * k / ac.threshold,
                            1.0 / config_.settings.alpha);
  return out;
}

double AcousticField::noisePower(common::SensorId sensor, std::int32_t tick) const {
  const auto& components = config_.settings.environmental_noise.components;
  const std::uint64_t seed = config_.seed;
  double total = 0.0;
  for (std::size_t c = 0; c < components.size(); ++c) {
    const std::uint64_t key = std::uint64_t{sensor} * kMaxNoiseComponents + c;
    const auto duration = static_cast<std::uint64_t>(noise_ticks_[c]);
    common::Stream phase(seed, common::Purpose::kEnvironmentalNoisePhase, key, 0);
    const std::uint64_t episode = (static_cast<std::uint64_t>(std::max(tick, 0)) + phase.below(duration)) / duration;
    common::Stream noise(seed, common::Purpose::kEnvironmentalNoise, key, static_cast<std::int64_t>(episode));
    if (noise.uniform() < components[c].fraction)
      total += config_.settings.acoustic.threshold * (1.0 + noise.uniform());  // 2013 eq. (6)
  }
  return total;
}

std::pair<double, common::TargetId> AcousticField::targetPower(common::Vec2 listener, std::int32_t tick) const {
  const auto all = sources(tick);
  return targetPower(listener, tick, all);
}

std::pair<double, common::TargetId> AcousticField::targetPower(common::Vec2 listener, std::int32_t tick,
                                                               std::span<const Source> all) const {
  const auto& ac = config_.settings.acoustic;
  const double dt = ac.detection_step_s;
  const double alpha = config_.settings.alpha;
  const double nearest = 0.5 * ac.sound_speed * dt;  // eq. (3) resolves no wavefront finer
  const std::int64_t first_step = static_cast<std::int64_t>(tick - 1) * steps_per_tick_ + 1;
  double total = 0.0;
  double loudest = 0.0;
  common::TargetId loudest_target = common::kFalseAlarm;
  for (const auto& source : all) {
    const std::int64_t first_emission = static_cast<std::int64_t>(std::ceil(source.path.start() / dt - 1e-9));
    const std::int64_t last_emission = floorIndex(source.path.end(), dt);
    // Eq. (3) for the steps k of the tick: sensor s hears the emissions j with
    // tau*(t_k-1) < j dt <= tau*(t_k). Over the whole tick these are tau*(t_first-1) < j dt <= tau*(t_last).
    const auto before = source.path.retardedTime(listener, static_cast<double>(first_step - 1) * dt, ac.sound_speed);
    const auto after = source.path.retardedTime(
        listener, static_cast<double>(first_step + steps_per_tick_ - 1) * dt, ac.sound_speed);
    if (!after) continue;
    const std::int64_t lo = before ? std::max(floorIndex(*before, dt) + 1, first_emission) : first_emission;
    const std::int64_t hi = std::min(floorIndex(*after, dt), last_emission);
    double energy = 0.0;
    for (std::int64_t j = lo; j <= hi; ++j) {
      double pt = source.power;
      if (ac.power_fluctuation > 0.0) {
        common::Stream fluctuation(config_.seed, common::Purpose::kAcousticPower,
                                   static_cast<std::uint64_t>(source.id), j);
        pt *= 1.0 + ac.power_fluctuation * fluctuation.uniform(-1.0, 1.0);
      }
      const double d = std::max(common::distance(listener, source.path.at(static_cast<double>(j) * dt)), nearest);
      energy += pt / power(d, alpha);  // eq. (4), summed over the steps of the tick
    }
    total += energy;
    if (energy > loudest) {
      loudest = energy;
      loudest_target = source.id;
    }
  }
  // The fusion centre's input: the mean step power over the interval (see the header).
  return {total / static_cast<double>(steps_per_tick_), loudest_target};
}

std::vector<common::Report> AcousticField::detect(std::int32_t tick) const {
  const auto& ac = config_.settings.acoustic;
  const auto all = sources(tick);

  // Candidates: the tile's sensors within reach of some target's path, and the noisy ones.
  std::vector<common::SensorId> candidates;
  std::vector<common::SensorId> found;
  for (const auto& source : all) {
    const auto visit = [&](common::Vec2 a, common::Vec2 b) {
      found.clear();
      layout_->collectWithin(0.5 * (a + b), source.reach + 0.5 * common::distance(a, b) + 1e-9 * (1.0 + source.reach), found);
      candidates.insert(candidates.end(), found.begin(), found.end());
    };
    // Only the part of the path whose sound can still arrive within `reach` matters: emitted at most
    // reach / Vs before the tick's first step (emissions older than that are farther than `reach`).
    const double now = static_cast<double>(tick) * ac.tick_s;
    const double t1 = source.path.end();
    const double t0 = std::max(source.path.start(), now - ac.tick_s - source.reach / ac.sound_speed - ac.tick_s);
    if (t1 < t0) continue;
    if (t1 - t0 < 1e-12) visit(source.path.at(t0), source.path.at(t0));
    for (double t = t0; t < t1 - 1e-12; t += ac.tick_s) visit(source.path.at(t), source.path.at(std::min(t + ac.tick_s, t1)));
  }
  // Each owned sensor's noise is drawn once per tick (sorted by id, as owned_ is).
  std::vector<std::pair<common::SensorId, double>> noisy;
  if (!noise_ticks_.empty())
    for (const common::SensorId id : owned_)
      if (const double p = noisePower(id, tick); p > 0.0) {
        noisy.emplace_back(id, p);
        candidates.push_back(id);
      }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());

  std::vector<common::Report> out;
  for (const common::SensorId id : candidates) {
    if (!std::binary_search(owned_.begin(), owned_.end(), id)) continue;
    const auto [target_power, target] = targetPower(layout_->truePosition(id), tick, all);
    const auto hit = std::lower_bound(noisy.begin(), noisy.end(), std::pair{id, 0.0});
    const double noise = hit != noisy.end() && hit->first == id ? hit->second : 0.0;
    const double total = target_power + noise;  // 2013 eq. (8)
    if (!(total >= ac.threshold)) continue;
    const double level = std::floor(total / ac.threshold);
    const common::Vec2 believed = layout_->believedPosition(id);
    // A detection (An et al. 2014 eq. 4) places the target at the sensor: a plain position report.
    out.push_back({tick, id, believed.x, believed.y, target,
                   level >= static_cast<double>(std::numeric_limits<std::int32_t>::max())
                       ? std::numeric_limits<std::int32_t>::max()
                       : static_cast<std::int32_t>(level)});
  }
  return out;
}

}  // namespace wsn::node::acoustic

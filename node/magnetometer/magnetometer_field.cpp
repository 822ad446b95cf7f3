#include "node/magnetometer/magnetometer_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "common/rng.hpp"

namespace wsn::node::magnetometer {

common::Vec2 horizontalField(common::Vec2 magnet, common::Vec2 sensor, double height, double strength) {
  const common::Vec2 d = sensor - magnet;
  const double rho2 = d.x * d.x + d.y * d.y;
  const double r2 = rho2 + height * height;
  // 3 K h rho / r^5 along d / rho: the rho cancels.
  const double scale = 3.0 * strength * height / (r2 * r2 * std::sqrt(r2));
  return {scale * d.x, scale * d.y};
}

double changeStatistic(std::span<const common::Vec2> samples) {
  if (samples.size() < 2) throw std::invalid_argument("changeStatistic: needs W + 1 >= 2 samples");
  double sum = 0.0;
  for (std::size_t i = 1; i < samples.size(); ++i) sum += common::distance(samples[i], samples[i - 1]);
  return sum / static_cast<double>(samples.size() - 1);
}

ChangeDetector::ChangeDetector(std::int32_t window) : changes_(static_cast<std::size_t>(std::max(1, window)), 0.0) {}

double ChangeDetector::push(common::Vec2 sample) {
  if (started_) {
    const double change = common::distance(sample, previous_);
    sum_ += change - changes_[next_];
    changes_[next_] = change;
    next_ = (next_ + 1) % changes_.size();
    // Recomputed when the ring wraps, so that rounding does not accumulate over a long run.
    if (next_ == 0) {
      sum_ = 0.0;
      for (const double c : changes_) sum_ += c;
    }
  }
  previous_ = sample;
  started_ = true;
  return value();
}

MagnetometerFieldConfig fieldConfigOf(const common::SensorModelConfig& sensor_model, std::uint64_t seed) {
  if (sensor_model.kind != "magnetometer")
    throw std::invalid_argument("magnetometer field: sensor_model.kind is '" + sensor_model.kind + "'");
  return {common::settingsOf<MagnetometerSettings>(sensor_model), sensor_model.sensing_range, seed};
}

MagnetometerField::MagnetometerField(MagnetometerFieldConfig config, const common::SensorLayout& layout,
                                     const Tile& tile, const common::Truth& truth)
    : config_(std::move(config)), layout_(&layout), truth_(&truth) {
  const auto& s = config_.settings;
  for (const common::SensorId id : tileSensorIds(layout, tile, "MagnetometerField")) {
    common::Stream draw(config_.seed, common::Purpose::kMagnetometerOffset, id, 0);
    const common::Vec2 offset{512.0 + draw.uniform(-s.offset_spread, s.offset_spread),
                              512.0 + draw.uniform(-s.offset_spread, s.offset_spread)};
    sensors_.push_back({id, layout.truePosition(id), offset, {0.0, 0.0}, ChangeDetector(s.window)});
  }
}

void MagnetometerField::positionsAt(double tick_time, std::vector<std::pair<common::TargetId, common::Vec2>>& out) const {
  out.clear();
  const auto tick = static_cast<std::int32_t>(std::ceil(tick_time - 1e-12));
  const double before = static_cast<double>(tick) - tick_time;  // in [0, 1): how far before `tick`
  const auto& previous = truth_->at(tick - 1);
  for (const auto& target : truth_->at(tick)) {
    common::Vec2 at{target.x - before * target.vx, target.y - before * target.vy};
    const auto it = std::lower_bound(previous.begin(), previous.end(), target.id,
                                     [](const common::TargetState& s, common::TargetId id) { return s.id < id; });
    if (it != previous.end() && it->id == target.id)  // straight between its positions at tick - 1 and tick
      at = {target.x + before * (it->x - target.x), target.y + before * (it->y - target.y)};
    out.emplace_back(target.id, at);
  }
}

std::vector<common::Report> MagnetometerField::detect(std::int32_t tick) {
  if (tick <= last_tick_)
    throw std::logic_error("MagnetometerField: tick " + std::to_string(tick) + " asked after tick " +
                           std::to_string(last_tick_));
  const auto& s = config_.settings;
  const std::int64_t per_tick = s.samplesPerTick();
  const std::int64_t first = static_cast<std::int64_t>(tick - 1) * per_tick + 1;
  const std::int64_t last = static_cast<std::int64_t>(tick) * per_tick;
  const double jump_probability = std::min(1.0, s.jump_rate_hz / s.sample_rate_hz);
  const double label_reach = 2.0 * config_.sensing_range;

  struct Best {
    double d = -1.0;
    std::int64_t sample = 0;
  };
  std::vector<Best> best(sensors_.size());
  std::vector<std::pair<common::TargetId, common::Vec2>> targets;
  // Eq. (11) at a sample looks W samples back: a target that ended just before the tick (it left
  // the region, or its scripted life ended) still moves D. Such a report names that target.
  std::vector<std::vector<std::pair<common::TargetId, common::Vec2>>> positions_of_tick{last_positions_};
  // Samples of skipped ticks (none in a run, which asks every tick) only advance the state.
  for (std::int64_t i = next_sample_; i <= last; ++i) {
    const double seconds = static_cast<double>(i) / s.sample_rate_hz;
    positionsAt(seconds / s.tick_s, targets);
    if (i >= first) positions_of_tick.push_back(targets);
    if (i == last) last_positions_ = targets;
    for (std::size_t k = 0; k < sensors_.size(); ++k) {
      Sensor& sensor = sensors_[k];
      common::Stream draw(config_.seed, common::Purpose::kMagnetometerSample, sensor.id, static_cast<std::int64_t>(i));
      const double nx = s.noise_sigma * draw.normal();
      const double ny = s.noise_sigma * draw.normal();
      sensor.bias.x += s.drift_sigma * draw.normal();
      sensor.bias.y += s.drift_sigma * draw.normal();
      if (draw.bernoulli(jump_probability)) {
        const double size = draw.uniform(0.0, s.jump_max);
        const double angle = draw.uniform(0.0, 2.0 * std::numbers::pi);
        sensor.bias.x += size * std::cos(angle);
        sensor.bias.y += size * std::sin(angle);
      }
      common::Vec2 field{0.0, 0.0};
      for (const auto& [id, at] : targets) field = field + horizontalField(at, sensor.at, s.magnet_height, s.magnet_strength);
      const common::Vec2 reading{std::clamp(sensor.offset.x + sensor.bias.x + field.x + nx, 0.0, s.adc_max),
                                 std::clamp(sensor.offset.y + sensor.bias.y + field.y + ny, 0.0, s.adc_max)};
      const double d = sensor.detector.push(reading);
      if (i >= first && d > best[k].d) best[k] = {d, i};
    }
  }
  next_sample_ = last + 1;
  last_tick_ = tick;

  std::vector<common::Report> out;
  for (std::size_t k = 0; k < sensors_.size(); ++k) {
    if (!(best[k].d > s.threshold)) continue;  // eq. (11): strictly above eta
    const Sensor& sensor = sensors_[k];
    // The nearest target within reach at the sample of the largest D, else in the tick before it.
    common::TargetId label = common::kFalseAlarm;
    const auto at_sample = static_cast<std::size_t>(best[k].sample - first + 1);
    for (const std::size_t index : {at_sample, std::size_t{0}}) {
      double nearest = label_reach;
      for (const auto& [id, at] : positions_of_tick[index]) {
        const double distance = common::distance(at, sensor.at);
        if (distance <= nearest) {
          nearest = distance;
          label = id;
        }
      }
      if (label != common::kFalseAlarm) break;
    }
    const common::Vec2 believed = layout_->believedPosition(sensor.id);
    const double level = std::min(best[k].d, static_cast<double>(std::numeric_limits<std::int32_t>::max()));
    out.push_back({tick, sensor.id, believed.x, believed.y, label, static_cast<std::int32_t>(std::floor(level)), {}});
  }
  return out;
}

}  // namespace wsn::node::magnetometer

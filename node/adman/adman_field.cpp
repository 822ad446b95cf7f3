#include "node/adman/adman_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "common/rng.hpp"

namespace wsn::node::adman {
namespace {

/// The largest distance between a sensor's believed and true position: the believed view of a rule
/// may reach that much further than the true one, so the exchange reaches twice that further.
double largestLocalisationError(const common::SensorLayout& layout) {
  double largest = 0.0;
  for (common::SensorId id = 0; id < layout.size(); ++id)
    largest = std::max(largest, common::distance(layout.truePosition(id), layout.believedPosition(id)));
  return largest;
}

std::vector<common::Vec2> positionsOf(std::span<const common::TargetState> targets) {
  std::vector<common::Vec2> out;
  out.reserve(targets.size());
  for (const auto& t : targets) out.push_back({t.x, t.y});
  return out;
}

}  // namespace

AdmanField::AdmanField(const AdmanSettings& settings, std::uint64_t seed, const common::SensorLayout& layout,
                       const Tile& tile, const common::Truth& truth)
    : settings_(settings),
      seed_(seed),
      layout_(&layout),
      tile_(tile),
      truth_(&truth),
      own_(tileSensorIds(layout, tile, "AdmanField")),
      thresholds_(settings.glrtThresholds()),
      mlmc_(settings.mlmc(seed)) {
  // 1e-6 of the pitch of slack: a reading sent needlessly costs nothing, a missing one would change a rule.
  reach_ = viewReach(mlmc_) + 2.0 * largestLocalisationError(layout) + 1e-6 * settings.sensor_pitch;
}

std::vector<common::SensorReading> AdmanField::read(std::int32_t tick) const {
  const std::vector<common::Vec2> targets = positionsOf(truth_->at(tick));
  const PowerModel power = settings_.power();
  std::vector<common::SensorReading> out;
  out.reserve(own_.size());
  for (const common::SensorId id : own_) {
    common::Stream noise(seed_, common::Purpose::kRssNoise, id, tick);
    out.push_back({id, receivedDb(power, layout_->truePosition(id), targets) + settings_.noise_sigma_db * noise.normal()});
  }
  return out;
}

std::vector<common::SensorReading> AdmanField::boundaryReadings(std::span<const common::SensorReading> own) const {
  std::vector<common::SensorReading> out;
  for (const auto& reading : own)
    if (nearSharedSide(*layout_, tile_, layout_->truePosition(reading.sensor), reach_)) out.push_back(reading);
  return out;
}

std::vector<common::Report> AdmanField::report(std::int32_t tick, std::span<const common::SensorReading> own,
                                               std::span<const common::SensorReading> foreign) const {
  std::vector<common::SensorReading> known(own.begin(), own.end());
  for (const auto& reading : foreign)
    if (reading.sensor < layout_->size() && std::isfinite(reading.z)) known.push_back(reading);
  std::stable_sort(known.begin(), known.end(), [](const auto& a, const auto& b) { return a.sensor < b.sensor; });
  known.erase(std::unique(known.begin(), known.end(), [](const auto& a, const auto& b) { return a.sensor == b.sensor; }),
              known.end());
  // The grid rules read true positions (the layout is known); MLMC, the positions the sensors believe.
  std::vector<Reading> grid_view, believed_view;
  grid_view.reserve(known.size());
  believed_view.reserve(known.size());
  for (const auto& reading : known) {
    grid_view.push_back({reading.sensor, layout_->truePosition(reading.sensor), reading.z});
    believed_view.push_back({reading.sensor, layout_->believedPosition(reading.sensor), reading.z});
  }
  const std::vector<Attachment> attachments = attach(grid_view, thresholds_, mlmc_.neighbours);
  std::vector<std::size_t> attached;
  for (std::size_t a = 0; a < attachments.size(); ++a)
    if (std::binary_search(own_.begin(), own_.end(), attachments[a].sensor)) attached.push_back(a);
  if (attached.empty()) return {};

  const auto& targets = truth_->at(tick);
  const double label_reach = 2.0 * std::numbers::sqrt2 * settings_.inside_radius;
  std::vector<common::Report> out;
  for (const Placement& placed : place(believed_view, attachments, attached, tick, mlmc_)) {
    const common::SensorId sensor = placed.attachment.sensor;
    const common::Vec2 at = layout_->truePosition(sensor);
    // The target the estimate is about: the nearest to it of those the sensor can hear.
    common::TargetId label = common::kFalseAlarm;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& target : targets) {
      const common::Vec2 l{target.x, target.y};
      const double d = common::distance(placed.at, l);
      if (common::distance(at, l) <= label_reach && d < nearest) {
        nearest = d;
        label = target.id;
      }
    }
    common::Measurement measurement = common::Measurement::position(placed.at.x, placed.at.y);
    measurement.noise = {placed.cov_xx, placed.cov_xy, placed.cov_xy, placed.cov_yy};
    out.push_back({tick, sensor, placed.at.x, placed.at.y, label, static_cast<std::int32_t>(placed.attachment.kind),
                   common::MeasurementRef(std::move(measurement))});
  }
  return out;
}

}  // namespace wsn::node::adman

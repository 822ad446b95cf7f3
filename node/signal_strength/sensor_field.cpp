#include "node/signal_strength/sensor_field.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/rng.hpp"
#include "node/signal_strength/sensor_model.hpp"

namespace wsn::node {
namespace {

/// Slack on range tests against tile bounds. Bounds are computed from cell indices while
/// sensors are binned by floor(), which can disagree in the last bits (and sensors at the far
/// region edge are clamped into the last cell), so these tests err on the generous side: a
/// reading sent or kept needlessly is filtered by the exact test later, a missed one would
/// change the election.
double withSlack(double range, double sensing_range) { return range + 1e-6 * (1.0 + sensing_range); }
double boundaryReach(double sensing_range) { return withSlack(2.0 * sensing_range, sensing_range); }

/// Targets with usable coordinates in canonical (id) order, so that signal sums and the
/// attribution of reports never depend on the order the caller passed them in.
std::vector<common::TargetState> canonicalTargets(std::span<const common::TargetState> targets) {
  std::vector<common::TargetState> sorted;
  sorted.reserve(targets.size());
  for (const auto& target : targets)
    if (std::isfinite(target.x) && std::isfinite(target.y)) sorted.push_back(target);
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    if (a.id != b.id) return a.id < b.id;
    if (a.x != b.x) return a.x < b.x;
    return a.y < b.y;
  });
  return sorted;
}

/// A reading a sensor can hear, bucketed by the cell of its true position for range search.
struct Heard {
  std::int32_t cell = 0;
  common::SensorId sensor = 0;
  double z = 0.0;
  common::Vec2 position;  ///< true position, fetched once
};

}  // namespace

SensorField::SensorField(const signal_strength::SignalStrengthSettings& model, double sensing_range,
                         std::uint64_t seed, const common::SensorLayout& layout, const Tile& tile)
    : layout_(&layout), model_(model), sensing_range_(sensing_range), seed_(seed), tile_(tile),
      q_(noiseExceedanceProbability(model)), skips_(q_) {
  if (tile.cell_col_begin < 0 || tile.cell_col_end > layout.cellColumns() || tile.cell_col_begin >= tile.cell_col_end ||
      tile.cell_row_begin < 0 || tile.cell_row_end > layout.cellRows() || tile.cell_row_begin >= tile.cell_row_end)
    throw std::invalid_argument("SensorField: tile " + std::to_string(tile.index) +
                                " is empty or outside the sensor cell grid");
}

bool SensorField::ownsSensor(common::SensorId id) const {
  return id < layout_->size() && tile_.ownsCell(*layout_, layout_->cellOf(layout_->truePosition(id)));
}

std::vector<common::SensorReading> SensorField::detect(std::int32_t tick,
                                                       std::span<const common::TargetState> targets) const {
  DetectStats stats;
  return detect(tick, targets, stats);
}

std::vector<common::SensorReading> SensorField::detect(std::int32_t tick, std::span<const common::TargetState> targets,
                                                       DetectStats& stats) const {
  stats = DetectStats{};
  const common::SensorLayout& layout = *layout_;
  const auto sorted_targets = canonicalTargets(targets);

  // Sensors of this tile within Rs of each target, as (sensor, target index) pairs.
  std::vector<std::pair<common::SensorId, std::size_t>> in_range;
  std::vector<common::SensorId> found;
  for (std::size_t k = 0; k < sorted_targets.size(); ++k) {
    const common::Vec2 x{sorted_targets[k].x, sorted_targets[k].y};
    if (tile_.bounds.distanceTo(x) > withSlack(sensing_range_, sensing_range_)) continue;
    layout.collectWithin(x, sensing_range_, found);
    for (common::SensorId id : found)
      if (ownsSensor(id)) in_range.emplace_back(id, k);
  }
  std::sort(in_range.begin(), in_range.end());

  // Oh et al., eq. 5 for sensors near a target: the terms of every target within Rs add up.
  std::vector<common::SensorReading> readings;
  std::vector<common::SensorId> near;  // sorted, because in_range is
  for (std::size_t begin = 0; begin < in_range.size();) {
    const common::SensorId id = in_range[begin].first;
    const common::Vec2 s = layout.truePosition(id);
    double signal = 0.0;
    std::size_t end = begin;
    for (; end < in_range.size() && in_range[end].first == id; ++end) {
      const auto& target = sorted_targets[in_range[end].second];
      signal += signalStrength(model_, common::distance(s, {target.x, target.y}));
    }
    begin = end;
    common::Stream noise(seed_, common::Purpose::kSensorNoise, id, tick);
    const double z = signal + model_.noise_sigma * noise.normal();
    ++stats.exact_draws;
    near.push_back(id);
    if (z >= model_.eta) readings.push_back({id, z});
  }

  // Everywhere else z = sigma w (Oh eq. 5, no target in range), which exceeds eta independently
  // per sensor with probability q. Walking a cell's sensors with Geometric(q) gaps draws exactly
  // those Bernoulli(q) outcomes: the first hit is at k with probability (1 - q)^k q, i.e. k
  // misses then a hit, and each later gap starts afresh (memorylessness), so every sensor is hit
  // independently with probability q; N sensors give N q exceedances per tick on average
  // (227.5 for the 10^4 sensors of Oh §VII). A hit sensor's value is then w | w >= eta / sigma.
  // Cost: O(1 + hits) per cell. The stream is keyed by the cell, never the tile, and a hit on a
  // near sensor (whose exact value came above) consumes its gap like any other, so the draws
  // do not depend on the tiling.
  const std::int32_t columns = layout.cellColumns();
  const double tail_start = model_.noise_sigma > 0.0 ? model_.eta / model_.noise_sigma : 0.0;
  for (std::int32_t row = tile_.cell_row_begin; row < tile_.cell_row_end; ++row) {
    for (std::int32_t column = tile_.cell_col_begin; column < tile_.cell_col_end; ++column) {
      ++stats.cells_visited;
      const std::int32_t cell = row * columns + column;
      const auto& sensors = layout.sensorsInCell(cell);
      if (q_ <= 0.0 || sensors.empty()) continue;
      common::Stream stream(seed_, common::Purpose::kNoiseExceedance, static_cast<std::uint64_t>(cell), tick);
      const std::uint64_t count = sensors.size();
      // position = index of the next exceedance; skips are capped at what is left of the cell.
      std::uint64_t position = skips_.drawUpTo(stream, count);
      while (position < count) {
        const common::SensorId id = sensors[position];
        if (std::binary_search(near.begin(), near.end(), id)) {
          ++stats.skipped_hits;
        } else {
          const double z = model_.noise_sigma > 0.0 ? model_.noise_sigma * sampleNormalTail(stream, tail_start) : 0.0;
          readings.push_back({id, z});
          ++stats.exceedances;
        }
        position += 1 + skips_.drawUpTo(stream, count - position - 1);
      }
    }
  }

  std::sort(readings.begin(), readings.end(), [](const auto& a, const auto& b) { return a.sensor < b.sensor; });
  return readings;
}

bool SensorField::isBoundarySensor(common::SensorId id) const {
  if (id >= layout_->size()) return false;
  return nearSharedSide(*layout_, tile_, layout_->truePosition(id), boundaryReach(sensing_range_));
}

std::vector<common::SensorReading> SensorField::boundaryReadings(std::span<const common::SensorReading> own) const {
  std::vector<common::SensorReading> boundary;
  for (const auto& reading : own)
    if (isBoundarySensor(reading.sensor)) boundary.push_back(reading);
  std::stable_sort(boundary.begin(), boundary.end(), [](const auto& a, const auto& b) { return a.sensor < b.sensor; });
  return boundary;
}

std::vector<common::Report> SensorField::fuse(std::int32_t tick, std::span<const common::SensorReading> own,
                                              std::span<const common::SensorReading> foreign,
                                              std::span<const common::TargetState> targets) const {
  const common::SensorLayout& layout = *layout_;
  const double hearing = 2.0 * sensing_range_;
  const double hearing2 = hearing * hearing;
  const double reach = boundaryReach(sensing_range_);

  // Everything the tile's sensors can hear, in canonical (cell, sensor) order. A sensor that
  // appears twice (malformed input) keeps its largest value.
  std::vector<Heard> heard;
  heard.reserve(own.size() + foreign.size());
  auto hear = [&](const common::SensorReading& reading, bool must_reach) {
    if (reading.sensor >= layout.size() || !(reading.z >= model_.eta)) return;
    const common::Vec2 p = layout.truePosition(reading.sensor);
    if (must_reach && tile_.bounds.distanceTo(p) > reach) return;
    heard.push_back({layout.cellOf(p), reading.sensor, reading.z, p});
  };
  for (const auto& reading : own) hear(reading, false);
  for (const auto& reading : foreign) hear(reading, true);
  std::sort(heard.begin(), heard.end(), [](const Heard& a, const Heard& b) {
    if (a.cell != b.cell) return a.cell < b.cell;
    if (a.sensor != b.sensor) return a.sensor < b.sensor;
    return a.z > b.z;
  });
  heard.erase(std::unique(heard.begin(), heard.end(), [](const Heard& a, const Heard& b) { return a.sensor == b.sensor; }),
              heard.end());

  const auto sorted_targets = canonicalTargets(targets);
  const double range2 = sensing_range_ * sensing_range_;
  const std::int32_t columns = layout.cellColumns();
  const std::int32_t rows = layout.cellRows();

  // Cells have side 2 Rs, so the 2 Rs neighbourhood of a sensor lies in the 3 x 3 cells around
  // its own: three runs of 3 consecutive cells (rows above, same, below). Candidates come in
  // cell order, so the start of each run only moves forward: one cursor per run, O(1)
  // amortised instead of a search per candidate.
  std::size_t cursor[3] = {0, 0, 0};
  std::vector<common::Report> reports;
  std::vector<const Heard*> group;
  for (const Heard& candidate : heard) {
    const std::int32_t column = candidate.cell % columns;
    const std::int32_t row = candidate.cell / columns;
    if (!tile_.ownsCell(column, row)) continue;
    const std::int32_t first_column = std::max(0, column - 1);
    const std::int32_t last_column = std::min(columns - 1, column + 1);

    // Oh et al., eq. 6 election: z_i must beat every reading heard within 2 Rs (true
    // positions); equal readings go to the smaller sensor id, so exactly one of them reports.
    group.clear();
    bool beaten = false;
    for (std::int32_t dr = -1; dr <= 1 && !beaten; ++dr) {
      const std::int32_t r = row + dr;
      if (r < 0 || r >= rows) continue;
      const std::int32_t run_begin = r * columns + first_column;
      const std::int32_t run_end = r * columns + last_column;
      std::size_t& at = cursor[dr + 1];
      while (at < heard.size() && heard[at].cell < run_begin) ++at;
      for (std::size_t k = at; k < heard.size() && heard[k].cell <= run_end; ++k) {
        const Heard& other = heard[k];
        if (other.sensor == candidate.sensor) continue;
        if (common::squaredDistance(candidate.position, other.position) > hearing2) continue;
        if (other.z > candidate.z || (other.z == candidate.z && other.sensor < candidate.sensor)) {
          beaten = true;
          break;
        }
        group.push_back(&other);
      }
    }
    if (beaten) continue;

    // Weighted centre of mass in believed positions, summed in sensor-id order so that every
    // tiling adds the same numbers in the same order.
    group.push_back(&candidate);
    std::sort(group.begin(), group.end(), [](const Heard* a, const Heard* b) { return a->sensor < b->sensor; });
    double sum_z = 0.0;
    double sum_x = 0.0;
    double sum_y = 0.0;
    for (const Heard* member : group) {
      const common::Vec2 believed = layout.believedPosition(member->sensor);
      sum_z += member->z;
      sum_x += member->z * believed.x;
      sum_y += member->z * believed.y;
    }

    common::TargetId target = common::kFalseAlarm;
    double strongest = -1.0;
    for (const auto& candidate_target : sorted_targets) {
      const double d2 = common::squaredDistance(candidate.position, {candidate_target.x, candidate_target.y});
      if (d2 > range2) continue;
      const double term = signalStrength(model_, std::sqrt(d2));
      if (term > strongest) {
        strongest = term;
        target = candidate_target.id;
      }
    }
    // Oh eq. 6 measures a position whose noise is the engine's model: a plain position report.
    reports.push_back({tick, candidate.sensor, sum_x / sum_z, sum_y / sum_z, target});
  }
  std::sort(reports.begin(), reports.end(), [](const auto& a, const auto& b) { return a.sensor < b.sensor; });
  return reports;
}

}  // namespace wsn::node

// One node process's share of the sensor network: detection (Oh eq. 5) for the sensors of one
// tile, the readings other tiles need, and the 2 Rs neighbour election with weighted centre
// of mass (Oh eq. 6). Outputs are a pure function of (scenario, seed, tick, targets): the same
// for every tiling of the field.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/messages.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/signal_strength/sensor_model.hpp"
#include "node/tiling.hpp"

namespace wsn::node {

/// What detect() did in one tick; the work is O(cells + exact_draws + exceedances).
struct DetectStats {
  /// Sensors within Rs of some target, given signal + their own noise draw.
  std::int64_t exact_draws = 0;
  /// Cells of the tile whose noise-exceedance walk ran.
  std::int64_t cells_visited = 0;
  /// Noise-only exceedances: sensors far from every target given a value from the tail.
  std::int64_t exceedances = 0;
  /// Exceedance hits on sensors that already had their exact value (skipped).
  std::int64_t skipped_hits = 0;
};

/// The sensors of one tile. Holds a reference to the layout, which must outlive it.
class SensorField {
 public:
  /// Sensors of `model` detecting within `sensing_range` (Rs), their noise drawn from `seed`.
  /// Throws std::invalid_argument when the tile does not lie in the layout's cell grid.
  SensorField(const signal_strength::SignalStrengthSettings& model, double sensing_range, std::uint64_t seed,
              const common::SensorLayout& layout, const Tile& tile);

  /// The tile this field simulates.
  const Tile& tile() const { return tile_; }
  /// q = P(sigma w >= eta): the per-sensor false-detection probability per tick.
  double exceedanceProbability() const { return q_; }
  /// True when sensor `id` (any sensor of the layout) belongs to this tile.
  bool ownsSensor(common::SensorId id) const;

  /// Oh et al., eq. 5: the readings z >= eta of this tile's sensors at `tick`, sorted by id.
  /// Sensors within Rs of a target get signal + sigma * Stream(seed, kSensorNoise, id, tick).normal();
  /// every other sensor exceeds eta independently with probability q, sampled per cell by
  /// geometric skips (Stream(seed, kNoiseExceedance, cell, tick)), so sensors far from every
  /// target cost nothing individually.
  std::vector<common::SensorReading> detect(std::int32_t tick, std::span<const common::TargetState> targets) const;
  /// Same, and reports the work done in `stats`.
  std::vector<common::SensorReading> detect(std::int32_t tick, std::span<const common::TargetState> targets,
                                            DetectStats& stats) const;

  /// The readings among `own` that a sensor of another tile can hear: those whose true position
  /// is within 2 Rs of a side this tile shares with another tile. Sorted by id.
  std::vector<common::SensorReading> boundaryReadings(std::span<const common::SensorReading> own) const;
  /// True when a reading of sensor `id` belongs in boundaryReadings().
  bool isBoundarySensor(common::SensorId id) const;

  /// Oh et al., eq. 6: every own sensor i with z_i >= eta whose reading beats every reading
  /// z_j >= eta (own or foreign) within 2 Rs (true positions; a tie goes to the smaller id)
  /// reports the z-weighted centre of mass of itself and those neighbours in believed
  /// positions. Report.target is the target with the largest signal term at sensor i among
  /// those within Rs, else kFalseAlarm. Foreign readings out of reach, readings below eta and
  /// unknown sensor ids are ignored. Sorted by sensor id.
  std::vector<common::Report> fuse(std::int32_t tick, std::span<const common::SensorReading> own,
                                   std::span<const common::SensorReading> foreign,
                                   std::span<const common::TargetState> targets) const;

 private:
  const common::SensorLayout* layout_;
  signal_strength::SignalStrengthSettings model_;
  double sensing_range_ = 1.5;
  std::uint64_t seed_ = 0;
  Tile tile_;
  double q_ = 0.0;
  GeometricSkips skips_;
};

}  // namespace wsn::node

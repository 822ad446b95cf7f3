// The ADMAN sensors of one node tile: each reads eq. (1) with its noise, sends the readings other
// tiles need, and reports the targets it attached (inside or in between) at their MLMC places.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/messages.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/adman/adman.hpp"
#include "node/adman/config.hpp"
#include "node/tiling.hpp"

namespace wsn::node::adman {

/// The sensors of one tile. A reading is a pure function of (seed, sensor, tick, targets), every
/// rule reads only what lies within viewReach() of the sensor it decides, and the tile is sent every
/// reading within that reach of its shared sides, so the reports are the same for every tiling.
class AdmanField {
 public:
  AdmanField(const AdmanSettings& settings, std::uint64_t seed, const common::SensorLayout& layout, const Tile& tile,
             const common::Truth& truth);

  /// Eq. (1) plus noise for every own sensor at `tick` (sorted by id): y = theta + sigma
  /// Stream(seed, kRssNoise, sensor, tick).normal().
  std::vector<common::SensorReading> read(std::int32_t tick) const;
  /// The own readings that another tile's rules read (those within the reach of a shared side).
  std::vector<common::SensorReading> boundaryReadings(std::span<const common::SensorReading> own) const;
  /// The attachments of own sensors at `tick`, placed by MLMC, as reports at the estimate with
  /// power_level 3 (inside) or 1 (in between), the particles' spread as the measurement's noise,
  /// labelled with the target nearest to the estimate among those within 2 sqrt2 r0 of the sensor.
  /// Foreign readings of unknown sensors are ignored. Sorted by sensor id.
  std::vector<common::Report> report(std::int32_t tick, std::span<const common::SensorReading> own,
                                     std::span<const common::SensorReading> foreign) const;

  /// How far from a shared side the readings this tile sends reach.
  double exchangeReach() const { return reach_; }

 private:
  AdmanSettings settings_;
  std::uint64_t seed_;
  const common::SensorLayout* layout_;
  Tile tile_;
  const common::Truth* truth_;
  std::vector<common::SensorId> own_;
  Thresholds thresholds_;
  MlmcSettings mlmc_;
  double reach_ = 0.0;
};

}  // namespace wsn::node::adman

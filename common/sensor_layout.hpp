// The sensor field: true and believed positions of every sensor (Oh §V, §VII-B), a pure
// function of (scenario, seed), plus a cell index for range queries; for a list layout also each
// sensor's own type, pose and coverage (ONERA Table I), which sensor models read.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.hpp"
#include "common/messages.hpp"
#include "common/scenario_config.hpp"

namespace wsn::common {

/// What the sensor field is a function of.
struct SensorFieldConfig {
  Rect region;
  SensorLayoutConfig sensors;
  double localisation_sigma = 0.0;  ///< Oh §VII-B: a sensor believes it is at s* + N(0, sigma^2 I)
  double sensing_range = 1.5;       ///< Rs: the index's cells have side 2 Rs
  std::uint64_t seed = 1;           ///< run.seed (random placement, localisation error)
};

/// The cells of a grid layout over `region` at `spacing`: a sensor at each cell centre.
struct GridShape {
  std::uint32_t columns = 0;
  std::uint32_t rows = 0;
  std::uint64_t sensors() const { return static_cast<std::uint64_t>(columns) * rows; }
};
GridShape gridShape(const Rect& region, double spacing);

/// The number of sensors `config` places over `region` (ids 0 .. n - 1), without placing them.
std::uint64_t sensorCount(const SensorLayoutConfig& config, const Rect& region);

/// The sensor-field config of `scenario`: split off at the role edge.
SensorFieldConfig sensorFieldConfig(const Scenario& scenario);

/// What a list layout says about one sensor beyond its position, in radians. Zero fov, range or
/// height: the sensor model's default for the type.
struct PlacedSensor {
  std::string name;
  std::string type;
  double heading = 0.0;  ///< radians counter-clockwise from +x
  double fov = 0.0;      ///< radians, in (0, 2 pi]; 0: the type's default
  double range = 0.0;
  double height = 0.0;
  friend bool operator==(const PlacedSensor&, const PlacedSensor&) = default;
};

/// The record of `config` in radians.
PlacedSensor placedSensorOf(const PlacedSensorConfig& config);

class SensorLayout {
 public:
  explicit SensorLayout(const SensorFieldConfig& field);

  std::size_t size() const { return true_positions_.size(); }
  Vec2 truePosition(SensorId id) const { return true_positions_[id]; }
  /// Where the sensor believes it is: true + N(0, sigma^2 I), Oh §VII-B.
  Vec2 believedPosition(SensorId id) const { return believed_positions_[id]; }
  const std::vector<Vec2>& truePositions() const { return true_positions_; }
  /// True for a list layout, whose sensors each have a PlacedSensor record.
  bool hasPlacedSensors() const { return !placed_.empty(); }
  /// The sensor's record; only for a list layout (hasPlacedSensors()).
  const PlacedSensor& placedSensor(SensorId id) const { return placed_[id]; }

  /// Calls f(id) for every sensor whose true position lies within `radius` of p (inclusive),
  /// in increasing id order.
  template <typename F>
  void forEachWithin(Vec2 p, double radius, F&& f) const {
    std::vector<SensorId> found;
    collectWithin(p, radius, found);
    for (SensorId id : found) f(id);
  }
  /// Ids (sorted) of sensors whose true position lies within `radius` of p (inclusive).
  void collectWithin(Vec2 p, double radius, std::vector<SensorId>& out) const;

  /// The fixed cell grid that also partitions the noise sampling (independent of tiling).
  double cellSize() const { return cell_size_; }
  std::int32_t cellColumns() const { return columns_; }
  std::int32_t cellRows() const { return rows_; }
  std::int32_t cellOf(Vec2 p) const;
  /// Sensors (sorted ids) whose true position falls in cell `cell`.
  const std::vector<SensorId>& sensorsInCell(std::int32_t cell) const { return cells_[cell]; }
  /// Lower-left corner and extent of a cell.
  Rect cellRect(std::int32_t cell) const;

 private:
  Rect region_;
  std::vector<Vec2> true_positions_;
  std::vector<Vec2> believed_positions_;
  std::vector<PlacedSensor> placed_;  // empty unless a list layout
  double cell_size_ = 1.0;
  std::int32_t columns_ = 1;
  std::int32_t rows_ = 1;
  std::vector<std::vector<SensorId>> cells_;
};

}  // namespace wsn::common

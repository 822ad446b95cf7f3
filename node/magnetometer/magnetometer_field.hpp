// Two-axis magnetometers that detect passing magnets by Oh et al. 2005 eq. (11) (§VIII's testbed):
// the field model of a vertical dipole, eq. (11)'s change statistic, and the sensors of one tile,
// sampled within each tick with offsets, read noise and a drifting, jumping bias.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/geometry.hpp"
#include "common/messages.hpp"
#include "common/scenario_config.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/magnetometer/config.hpp"
#include "node/tiling.hpp"

namespace wsn::node::magnetometer {

/// The horizontal field at `sensor` of a vertical dipole at `magnet`, height h above the sensor
/// plane, strength K: 3 K h rho / (rho^2 + h^2)^(5/2) along the magnet-to-sensor direction (rho
/// the horizontal distance; zero right under the magnet).
common::Vec2 horizontalField(common::Vec2 magnet, common::Vec2 sensor, double height, double strength);

/// Oh eq. (11): D = (1/W) sum of |b_i - b_(i-1)| over the last W sample-to-sample changes.
/// `samples` holds W + 1 consecutive readings, oldest first.
double changeStatistic(std::span<const common::Vec2> samples);

/// Eq. (11) run over a stream of readings: push each sample; value() is D over the last W
/// changes (the changes before the first sample count as 0).
class ChangeDetector {
 public:
  explicit ChangeDetector(std::int32_t window);
  /// Adds a reading and returns D after it.
  double push(common::Vec2 sample);
  double value() const { return sum_ / static_cast<double>(changes_.size()); }

 private:
  std::vector<double> changes_;  // ring of the last W change sizes
  std::size_t next_ = 0;
  double sum_ = 0.0;
  bool started_ = false;
  common::Vec2 previous_;
};

/// What the magnetometers of a run are made of.
struct MagnetometerFieldConfig {
  MagnetometerSettings settings;
  double sensing_range = 0.6;  ///< labels: a report within 2 x this of a target is that target's
  std::uint64_t seed = 1;
};

/// What the field reads of the sensor model and the seed; throws std::invalid_argument when the
/// sensors are not magnetometers.
MagnetometerFieldConfig fieldConfigOf(const common::SensorModelConfig& sensor_model, std::uint64_t seed);

/// The magnetometers of one tile. Each tick t holds samples (t - 1) n + 1 ... t n (n =
/// tick_s x sample_rate_hz), sample i at time i / f_s; a target's position between ticks is
/// interpolated along its truth. A sensor's reading is clip(o + bias + sum of the targets' fields
/// + N(0, sigma_n^2 I)); the bias is a random walk with rare jumps. A sensor reports once in a tick
/// when eq. (11) exceeds the threshold at any of its samples: at its believed position, with
/// power_level floor(max D), labelled with the nearest target within 2 sensing ranges at the sample
/// of the largest D, or else at the last sample of the tick before (a target that just ended),
/// else a false alarm. Every random draw is keyed by (seed, sensor, sample), so the reports are a pure
/// function of (scenario, seed, tick), the same for every tiling; ticks must be asked in
/// increasing order (the bias and eq. (11) carry state from sample to sample).
class MagnetometerField {
 public:
  MagnetometerField(MagnetometerFieldConfig config, const common::SensorLayout& layout, const Tile& tile,
                    const common::Truth& truth);

  /// This tile's reports at `tick`, sorted by sensor id; throws std::logic_error for a tick
  /// earlier than one already reported.
  std::vector<common::Report> detect(std::int32_t tick);

 private:
  struct Sensor {
    common::SensorId id;
    common::Vec2 at;      // true position
    common::Vec2 offset;  // o_n
    common::Vec2 bias;    // drift and jumps so far
    ChangeDetector detector;
  };
  /// The targets' positions at time `tick_time` (in ticks), with their ids.
  void positionsAt(double tick_time, std::vector<std::pair<common::TargetId, common::Vec2>>& out) const;

  MagnetometerFieldConfig config_;
  const common::SensorLayout* layout_;
  const common::Truth* truth_;
  std::vector<Sensor> sensors_;  // the tile's, sorted by id
  std::vector<std::pair<common::TargetId, common::Vec2>> last_positions_;  // at the last sample so far
  std::int64_t next_sample_ = 1;
  std::int32_t last_tick_ = 0;
};

}  // namespace wsn::node::magnetometer

// Where each sensor of the field looks and how likely it detects a target there: PD x Pe of ONERA
// eq. (15), a pure function of the scenario (its sensor list, the types' settings, the terrain's
// masks). The node's sensors decide what they see with it, and trackers weigh a miss with it.
#pragma once

#include <memory>
#include <vector>

#include "common/geometry.hpp"
#include "common/messages.hpp"
#include "common/terrain.hpp"

namespace wsn::common {

/// Which masks hide a target from a sensor (docs/ONERA.md §9): a camera or PIR sees through
/// neither buildings nor vegetation, a radar through vegetation, a presence or acoustic sensor
/// through both.
enum class SightBlockers { none, buildings, buildings_and_vegetation };

/// One sensor as a tracker may know it.
struct SensorCoverage {
  SensorId sensor = 0;
  Vec2 position;                      ///< where it measures from (its believed position)
  double heading = 0.0;               ///< radians counter-clockwise from +x
  double fov = 0.0;                   ///< radians, (0, 2 pi]; 2 pi and more: every bearing
  double range = 0.0;                 ///< ground range it covers
  double detection_probability = 0.0; ///< PD of a covered target in its sight, each tick
  SightBlockers blockers = SightBlockers::none;
  /// A presence ("volume") sensor: its report says a target is within its coverage and places it
  /// at the sensor. ONERA lets such reports update tracks but start none.
  bool presence = false;
  friend bool operator==(const SensorCoverage&, const SensorCoverage&) = default;
};

/// Whether p lies within `range` of the sensor and within the sector of width `fov` centred on
/// `heading`, edges included. The one sector test of the field sensors and the trackers.
bool inSector(Vec2 sensor, double heading, double fov, double range, Vec2 p);

/// Whether the terrain's masks of the kinds `blockers` names hide p from a sensor at `from`;
/// nothing is hidden without a terrain.
bool hiddenBy(const Terrain* terrain, SightBlockers blockers, Vec2 from, Vec2 p);

/// PD x Pe at p: the sensor's PD where p is in its sector and sight, else 0.
double detectionProbabilityAt(const SensorCoverage& sensor, Vec2 p, const Terrain* terrain);

/// 1 - prod_i (1 - PD_i(p)): the chance that at least one of `sensors` detects a target at p,
/// each sensor deciding on its own (ONERA eq. 15 over a field).
double sensedProbabilityAt(const std::vector<SensorCoverage>& sensors, Vec2 p, const Terrain* terrain);

/// The mean of sensedProbabilityAt over `region`, at the centres of a cells_per_side^2 grid: the
/// region average that a field's single detection probability stands for.
double meanSensedProbability(const std::vector<SensorCoverage>& sensors, const Rect& region, const Terrain* terrain,
                             int cells_per_side = 200);

/// How a field's detection is shared out over its region: sensedProbabilityAt(p) / the region's
/// mean, so that a model's one detection probability pd, times share(p), is the detection
/// probability at p and still averages to pd. Without coverage (a grid of identical sensors) every
/// point has share 1.
class DetectionShare {
 public:
  DetectionShare() = default;
  /// `sensors` are the ones a tracker hears; `region_mean` the whole field's meanSensedProbability.
  DetectionShare(std::vector<SensorCoverage> sensors, std::shared_ptr<const Terrain> terrain, double region_mean);
  bool uniform() const { return sensors_.empty() || region_mean_ <= 0.0; }
  double at(Vec2 p) const {
    return uniform() ? 1.0 : sensedProbabilityAt(sensors_, p, terrain_.get()) / region_mean_;
  }

 private:
  std::vector<SensorCoverage> sensors_;
  std::shared_ptr<const Terrain> terrain_;
  double region_mean_ = 0.0;
};

}  // namespace wsn::common

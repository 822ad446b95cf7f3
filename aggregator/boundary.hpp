// Tracking errors split by where they happen: near a boundary between two supernodes' tracking
// groups or inside a group, to compare association methods where tracks change hands (Oh §VI).
//
// Definitions (docs/METRICS.md):
//   - Tracking groups are the Voronoi cells of the supernodes (a sensor reports to its nearest
//     supernode, Oh §V). A point p whose nearest supernode is a and second-nearest is b lies
//       s(p) = (‖p − b‖² − ‖p − a‖²) / (2 ‖a − b‖)
//     from the bisector of a and b (s >= 0; ties between equally near supernodes go to the lower
//     index, as in the network model). p is "at a boundary" when s(p) <= band. With one
//     supernode there is no bisector and every point is interior. With three or more, s(p) is
//     the distance to the a|b bisector only, which is what a handoff between a and b sees.
//   - Events come from the CLEAR-MOT mapping (clear_mot.hpp) of the same tick, and each is
//     placed at the true position of its target at that tick:
//       duplicate track-tick: a track left unmatched that lies within the CLEAR-MOT threshold
//         (distance < T) of a target matched to another track, i.e. a second track on a tracked
//         target; placed at the nearest such target (lower id on a tie), counted once per track;
//       identity switch and fragmentation: CLEAR-MOT's own, at the tick CLEAR-MOT counts them.
//   - target_ticks counts the target-ticks of each side, the denominator for rates.
#pragma once

#include <cstdint>
#include <vector>

#include "aggregator/clear_mot.hpp"
#include "common/geometry.hpp"
#include "common/truth.hpp"

namespace wsn::aggregator {

/// Decides whether a point is near a tracking-group boundary.
class BoundaryClassifier {
 public:
  /// `band` in metres, finite and >= 0; supernodes pairwise distinct (else std::invalid_argument).
  BoundaryClassifier(std::vector<common::Vec2> supernodes, double band);

  /// s(p) of the header; +infinity with fewer than two supernodes.
  double bisectorDistance(common::Vec2 p) const;
  bool atBoundary(common::Vec2 p) const { return bisectorDistance(p) <= band_; }
  double band() const { return band_; }
  std::size_t supernodes() const { return supernodes_.size(); }

 private:
  std::vector<common::Vec2> supernodes_;
  double band_;
};

/// Event counts of one side (boundary or interior).
struct BoundaryCounts {
  std::int64_t target_ticks = 0;
  std::int64_t duplicate_track_ticks = 0;
  std::int64_t id_switches = 0;
  std::int64_t fragmentations = 0;
};

struct BoundarySummary {
  double band = 0.0;
  std::int64_t supernodes = 0;
  double mot_threshold = 0.0;
  BoundaryCounts boundary;
  BoundaryCounts interior;
};

/// Places each tick's CLEAR-MOT events at their targets and counts them per side.
class BoundaryAccumulator {
 public:
  /// `mot_threshold` is the CLEAR-MOT threshold T the events were made with (finite, > 0).
  BoundaryAccumulator(std::vector<common::Vec2> supernodes, double band, double mot_threshold);

  /// One tick: the truth given to ClearMotAccumulator::add and what it returned.
  void add(const std::vector<common::TargetState>& truth, const ClearMotTick& events);

  BoundarySummary summary() const;

 private:
  BoundaryCounts& side(const common::TargetState& target);

  BoundaryClassifier classifier_;
  double threshold_;
  BoundaryCounts boundary_;
  BoundaryCounts interior_;
};

}  // namespace wsn::aggregator

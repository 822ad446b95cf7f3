// How the sbmht engine starts new track trees: a tentative tree at every located report no leaf took
// (a radar's range rate giving it a velocity along the line of sight), and, from two sensors'
// bearings that no leaf took, a tree where the rays cross (ONERA §II-C's composite report).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "common/messages.hpp"
#include "common/terrain.hpp"
#include "supernode/sbmht/leaf.hpp"
#include "supernode/sbmht/params.hpp"
#include "supernode/sbmht/scan.hpp"

namespace wsn::supernode::sbmht {

/// A bearing no leaf took in its scan (index into the tick's slot), and its sensor.
struct FreeBearing {
  std::size_t report = 0;
  const common::SensorCoverage* sensor = nullptr;
};

/// Starts the trees of supernode `supernode`, which owns their ids (common::track_id::birth).
class TreeBirths {
 public:
  /// `model_count`: the IMM's models (stop, quiet CV, manoeuvring CV and, with roads, the road model).
  TreeBirths(std::uint32_t supernode, const SbmhtParams& params, std::size_t model_count,
             std::shared_ptr<const common::Terrain> terrain);

  /// L(1), the score a tree of one report starts at (initial_score's rule).
  double initialScore() const { return initial_score_; }
  /// The model probabilities a new track starts with: a report rules out the stop model (eq. 9),
  /// so it moves, model unknown.
  const ModeVector& initialModeProbabilities() const { return initial_probabilities_; }

  /// A tentative tree born at `tick` from `reports` (indices into its slot), at `fix` with the
  /// velocity prior (a radar's range rate along its line of sight), scoring `score`.
  Leaf newTree(common::TrackId id, std::int32_t tick, std::vector<std::int32_t> reports, const PositionFix& fix,
               double score, const ClassVector& classes) const;
  /// Appends to `leaves` the trees `scan`'s reports that locate a target start: every such report of
  /// a sensor that no leaf took (`gated`), or the sensor's first when leaves took them all.
  void startLocatedTrees(std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot,
                         const std::vector<ReportTerms>& terms, const Scan& scan, const std::vector<char>& gated) const;
  /// ONERA §II-C's composite reports: after `scan`, every bearing of its sensor that no leaf took,
  /// paired with each of `earlier` (the free bearings of the tick's earlier scans), starts a
  /// tentative tree where the rays cross, if both sensors could see a target there. The tree took
  /// both reports, so it conflicts with any leaf that took either; the tick's later scans branch it
  /// as any leaf. Keeps `leaves` in leafOrder; appends this scan's free bearings to `earlier`.
  void startBearingPairTrees(std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot,
                             const std::vector<ReportTerms>& terms, const Scan& scan, const std::vector<char>& gated,
                             std::vector<FreeBearing>& earlier) const;

 private:
  /// Where a tree two free bearings start lies, its score and its classes.
  struct PairBirth {
    PositionFix fix;
    double score = 0.0;
    ClassVector classes;
  };
  /// The tree bearings a (of sensor_a) and b (of sensor_b) start; nullopt when their rays do not
  /// cross well, a sensor could not see a target where they do, or their classes exclude each other.
  std::optional<PairBirth> pairBirth(const ReportTerms& a, const common::SensorCoverage& sensor_a, const ReportTerms& b,
                                     const common::SensorCoverage& sensor_b) const;

  std::uint32_t supernode_;
  SbmhtParams params_;
  InitialScore score_rule_;
  double initial_score_;
  ModeVector initial_probabilities_;
  std::shared_ptr<const common::Terrain> terrain_;
};

}  // namespace wsn::supernode::sbmht

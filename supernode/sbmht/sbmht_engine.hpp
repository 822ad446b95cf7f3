// The ONERA supernode engine "sbmht" (Pannetier, Dezert, Sella, FUSION 2014, §IV-A, Fig. 2; Blackman &
// Popoli 1999 ch. 16): a track-oriented multiple-hypothesis tracker with structured branching. Each
// track tree branches on every gated report and on a miss; its leaves are scored by the IMM's
// likelihood ratio (track_score.hpp), judged by Wald's SPRT, clustered when they share reports, and
// combined into the k best global hypotheses per cluster; the tracks' posteriors prune the leaves,
// N-scan pruning keeps the branches that agree with the best hypothesis N ticks back, and duplicate
// leaves are merged. Reports are positions, bearings, radar plots or camera angles (docs/ONERA.md
// §3 and §8); every kind but a bearing can start a track, and two bearings of two sensors start one
// where they cross (§II-C's composite report). Where the scenario lists its sensors,
// each sensor is a scan of its own, its silence weighed by its coverage (common/sensor_coverage.hpp),
// and a bearing keeps the track within its sensor's reach (reach.hpp). Where it has roads, the
// paper's algorithm 1 adds a road model to the IMM and keeps a branch per road section (§2, §3).
// This file is the engine's tick loop; its parameters are in params.hpp, its leaves in leaf.hpp, the
// scans' view of a report in scan.hpp, new trees in births.hpp and the hypotheses in hypotheses.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "common/class_evidence.hpp"
#include "supernode/engine.hpp"
#include "supernode/sbmht/births.hpp"
#include "supernode/sbmht/imm.hpp"
#include "supernode/sbmht/leaf.hpp"
#include "supernode/sbmht/params.hpp"
#include "supernode/sbmht/scan.hpp"
#include "supernode/sbmht/track_score.hpp"
#include "supernode/window_replay.hpp"

namespace wsn::supernode::sbmht {

/// The engine's registration: name "sbmht", its parameters with defaults and ranges, factory.
EngineSpec engineSpec();

/// A confirmed track's class (ONERA eq. 19-23, docs/ONERA.md §4): argmax of its leaf's class vector.
struct TrackClass {
  common::TrackId track = 0;
  /// The most probable class; kUnknown while the vector is uniform (no classifying report yet).
  common::TargetClass target_class = common::TargetClass::kUnknown;
  double probability = 0.0;  ///< its probability in the class vector
  friend bool operator==(const TrackClass&, const TrackClass&) = default;
};

/// Track-oriented MHT with window replay (supernode/window_replay.hpp, shared with GNN): the engine
/// keeps an anchor (its track trees after every tick that already left the window) and replays the
/// window's ticks from it at every step, so a delayed report is processed at its generation tick as
/// if it had been on time. Handoffs are events in that timeline (an adopted track enters at the tick
/// after its last_tick, a released tree leaves after the tick it was released at).
class SbmhtEngine final : public Engine {
 public:
  explicit SbmhtEngine(const EngineContext& context);

  void adopt(const common::TrackHandoff& handoff) override;
  void step(const ObservationWindow& window) override;
  std::vector<common::TrackEstimate> confirmedTracks() const override;
  std::vector<TrackPrediction> predictions() const override;
  /// The class of each track of confirmedTracks(), in the same order.
  std::vector<TrackClass> confirmedClasses() const;
  common::TrackHandoff release(common::TrackId track, std::uint32_t to_supernode) override;

  /// A track hypothesis: one leaf of a track tree (leaf.hpp).
  using Leaf = sbmht::Leaf;
  /// Ends a tick's entries in Leaf::history.
  static constexpr std::int32_t kTickEnd = sbmht::kTickEnd;
  /// a < b lexicographically, as std::vector's operator<: the history order of leaves().
  static bool historyLess(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b) {
    return sbmht::historyLess(a, b);
  }
  /// The IMM's models: stop, quiet CV, manoeuvring CV and, with roads, the road model.
  static constexpr std::size_t kStopMode = 0;
  static constexpr std::size_t kFastMode = 2;
  static constexpr std::size_t kRoadMode = 3;

  /// Leaves at the newest tick, sorted by (tree, history).
  const std::vector<Leaf>& leaves() const { return replay_.current(); }
  /// Clusters whose hypothesis search hit its node budget (the k best found so far were used).
  std::uint64_t truncatedSearches() const { return truncated_searches_; }
  std::uint64_t rejectedHandoffs() const { return rejected_handoffs_; }
  /// Reports (counted at every replay of their tick) that carried no noise R or no clutter density
  /// their kind needs, and so took no part (docs/ONERA.md §8).
  std::uint64_t unusableReports() const { return unusable_reports_; }

 private:
  /// The MHT at `tick` on leaves whose state is at tick - 1: one time update, then a scan per
  /// sensor (one scan of every report without coverage), then hypothesis management.
  void processTick(std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot);
  /// Each report of the slot as the scans use it; counts those that are not usable.
  std::vector<ReportTerms> termsOfSlot(std::span<const common::Observation> slot);
  /// Branches every leaf on the scan's reports and a miss, and starts the scan's births.
  /// Marks in `gated` the reports some leaf took.
  void runScan(std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot,
               const std::vector<ReportTerms>& terms, const Scan& scan, std::vector<char>& gated) const;
  /// Branches one leaf on the scan into `next`: a child for each report in its gate, then the leaf
  /// itself as the miss branch, unless the SPRT deleted them. Marks in `gated` the reports it took.
  void branchLeaf(Leaf& leaf, std::int32_t tick, const std::vector<ReportTerms>& terms, const Scan& scan,
                  std::vector<char>& gated, std::vector<Leaf>& next) const;
  /// The update of a leaf's prediction by report `t` of `scan` when the report falls in its gate
  /// (and, a bearing, within its sensor's reach); nullopt when it is not this leaf's.
  std::optional<ImmUpdate> gatedUpdate(const ImmPrediction& prediction, const ReportTerms& t, const Scan& scan,
                                       const Detectability& seen) const;
  /// The child of `leaf` that took report `report` (its update `hit`, its class update if any).
  Leaf reportBranch(const Leaf& leaf, std::int32_t tick, std::size_t report, ImmUpdate hit, const ReportTerms& t,
                    const std::optional<common::ClassUpdate>& classified, const SprtThresholds& sprt) const;
  /// PD and per-model Pe of the scan's sensor for the leaf's (time-updated) estimate.
  Detectability detectabilityOf(const Scan& scan, const ImmState& imm) const;
  /// Whether the sensor could have seen the target: some moving model's prediction is in sight (the
  /// stop model's Lambda^0 is 1 whatever its Pe, so its silence there is no evidence).
  bool perceivable(const Detectability& detectability) const;
  /// The time update of one leaf: mixing and each model's prediction. Algorithm 1 first picks the
  /// road section nearest the leaf's predicted position; within road_gate_distance the road model
  /// follows that section's segment and its predicted mean is moved onto it, else it is off.
  void timeUpdate(Leaf& leaf) const;
  /// Algorithm 1: the road model's estimate moved onto the leaf's road section, its covariance
  /// projected too (C8, after a report) or left as it is (after a time update).
  void projectRoadMode(Leaf& leaf, bool with_covariance) const;
  /// Closes the tick in every leaf's history; drops leaves that missed max_misses ticks running
  /// (without coverage), that no sensor could see for max_coast_ticks (with coverage), or that
  /// coasted out of the region.
  void endTick(std::vector<Leaf>& leaves, std::int32_t tick) const;
  /// Clusters, k best hypotheses, P(T), hypothesis pruning and (at a tick's end) N-scan pruning.
  void manageHypotheses(std::vector<Leaf>& leaves, std::int32_t tick, bool n_scan_pruning);
  /// A handed-over leaf that should have joined at first_tick, brought up to the anchor at anchor_tick.
  void catchUp(Leaf& leaf, std::int32_t first_tick, std::int32_t anchor_tick) const;

  common::Rect region_;
  /// Each sensor's sector, PD and sight (empty: uniform detection_probability), and the terrain
  /// whose masks hide targets from them.
  std::vector<common::SensorCoverage> coverage_;
  std::vector<std::int32_t> coverage_of_sensor_;  // index into coverage_ by sensor id, or -1
  std::shared_ptr<const common::Terrain> terrain_;
  SbmhtParams params_;
  double delta_ = 1.0;
  /// Algorithm 1: use_road_network and a terrain with roads. The IMM then has a fourth model, the
  /// road model (MotionKind::road), at index kRoadMode.
  bool roads_ = false;
  /// The IMM's updates (report, miss) and, off road, its time update: with roads the road model
  /// is off there (no model switches into it; its probability flows to the CV models).
  Imm imm_;
  /// Algorithm 1: the time update on road section s, segment g: road_imms_[s][g].
  std::vector<std::vector<Imm>> road_imms_;
  SprtThresholds sprt_;
  /// The SPRT for a tree's birth tick: it confirms but does not delete, since L(1) may lie below
  /// T2 (track_score.hpp) and another sensor's scan of the same tick is not yet its next scan.
  SprtThresholds birth_tick_sprt_;
  TreeBirths births_;
  WindowReplay<Leaf> replay_{&Leaf::tree, &leafOrder};
  std::uint64_t truncated_searches_ = 0;
  std::uint64_t rejected_handoffs_ = 0;
  std::uint64_t unusable_reports_ = 0;
  /// The gate on d^2 per report dimension 0..3, all of the probability gate_chi2 has in 2-D.
  std::array<double, 4> gates_{};
  /// P_G: the probability that a target's report falls in its gate, the same for every dimension.
  double gate_probability_ = 1.0;
};

}  // namespace wsn::supernode::sbmht

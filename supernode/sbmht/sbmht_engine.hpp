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
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "common/class_evidence.hpp"
#include "supernode/engine.hpp"
#include "supernode/sbmht/imm.hpp"
#include "supernode/sbmht/track_score.hpp"
#include "supernode/window_replay.hpp"

namespace wsn::supernode::sbmht {

/// The engine's registration: name "sbmht", its parameters with defaults and ranges, factory.
EngineSpec engineSpec();

/// Resolved parameters (see paramTable() for meaning, defaults and ranges).
struct SbmhtParams {
  double detection_probability = 0.9;
  double false_alarm_density = 1e-4;
  double birth_density = 1e-5;
  double measurement_sigma = 0.5;
  double initial_velocity_sigma = 2.0;
  double gate_chi2 = 9.21;
  double sprt_alpha = 1e-3;
  double sprt_beta = 0.1;
  double drop_score = 10.0;
  std::int32_t max_misses = 3;
  std::int32_t n_scan = 3;
  std::int32_t hypotheses = 20;
  std::int32_t initial_score = 0;  ///< 0: blackman, 1: paper (InitialScore)
  double stop_sigma = 0.1;
  double cv_slow_sigma = 0.15;
  double cv_fast_sigma = 0.75;
  double stop_time_constant = 20.0;
  double slow_time_constant = 30.0;
  double fast_time_constant = 10.0;
  double merge_radius = 0.0;
  std::int32_t confirm_reports = 3;   ///< a tentative track that took reports at this many ticks is confirmed
  double delivery_probability = 1.0;  ///< scales each sensor's PD where the engine has coverage
  std::int32_t max_coast_ticks = 60;  ///< a leaf no sensor could see for this many ticks running is deleted
  std::int32_t bearing_pair_births = 1;  ///< 1: two ungated bearings of two sensors start a tree where they cross
  std::int32_t use_road_network = 1;  ///< 1: algorithm 1 (the scenario's roads in the IMM and N-scan), 0: algorithm 2
  double road_along_sigma = 1.0;      ///< sigma_d of eq. 6
  double road_across_sigma = 0.1;     ///< sigma_n of eq. 6
  double road_location_sigma = 1.0;   ///< the road map's own error across the road
  double road_gate_distance = 15.0;   ///< the road model is active within this distance of a road
  double road_time_constant = 30.0;   ///< mean sojourn in the road model
  std::int32_t road_sections_kept = 3;  ///< Nk: N-scan keeps the best branch of up to this many road sections

  static SbmhtParams fromContext(const EngineContext& context);
};

/// A confirmed track's class (ONERA eq. 19-23, docs/ONERA.md §4): argmax of its leaf's class vector.
struct TrackClass {
  common::TrackId track = 0;
  /// The most probable class; kUnknown while the vector is uniform (no classifying report yet).
  common::TargetClass target_class = common::TargetClass::kUnknown;
  double probability = 0.0;  ///< its probability in the class vector
  friend bool operator==(const TrackClass&, const TrackClass&) = default;
};

/// The parameters' one description: key, member, unit, range, default (SbmhtParams{}) and meaning.
const config::FieldTable<SbmhtParams>& paramTable();

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

  /// A track hypothesis: one leaf of a track tree.
  struct Leaf {
    common::TrackId tree = 0;        ///< the tree's id, the track id it reports under
    std::int32_t first_tick = 0;     ///< the tick history starts at
    /// Tick by tick since first_tick: the indices (into that tick's slot, canonical order) of the
    /// reports it took, then kTickEnd; a tick it missed is kTickEnd alone. While a tick's scans
    /// run, its entries are open (no kTickEnd yet). Two leaves of one tree differ only in their
    /// last n_scan ticks (N-scan pruning).
    std::vector<std::int32_t> history;
    ImmState imm;
    TrackScore score;
    std::int32_t last_seen_tick = 0;
    std::int32_t hits = 0;           ///< ticks at which it took a report
    std::int32_t misses = 0;         ///< consecutive ticks without a report
    std::int32_t unseen_ticks = 0;   ///< consecutive ticks without a report that no sensor could see it
    bool perceivable = false;        ///< some sensor could have seen it at the current tick
    bool born_this_tick = false;     ///< its tree started in a scan of the current tick
    double probability = 1.0;        ///< P(T) over the cluster's k best hypotheses
    /// beta of eqs. 19-20 over common::kClassCount classes: eq. 20 from its first report's class
    /// likelihoods (uniform without them), then eq. 19 at every report that carries them.
    /// Of fixed capacity, so that copying a leaf at every branch allocates nothing for it.
    ClassVector classes = common::uniformClassVector();
    bool best = false;               ///< in the best global hypothesis
    /// Algorithm 1: the road section (index into common::Terrain::sections()) its road model
    /// follows this tick, or -1 when no section is within road_gate_distance (the model is off).
    std::int32_t road_section = -1;

    /// The reports it took at `tick` (empty: a miss, or a tick outside its history).
    std::span<const std::int32_t> reportsAt(std::int32_t tick) const;
  };
  /// Ends a tick's entries in Leaf::history.
  static constexpr std::int32_t kTickEnd = -1;
  /// a < b lexicographically, as std::vector's operator<: the history order of leaves(). Faster on
  /// the long common prefix two leaves of one tree share.
  static bool historyLess(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b);
  /// The IMM's models: stop, quiet CV, manoeuvring CV and, with roads, the road model.
  static constexpr std::size_t kStopMode = 0;
  static constexpr std::size_t kFastMode = 2;
  static constexpr std::size_t kRoadMode = 3;
  /// One report as a scan uses it (its measurement model, value, noise, clutter density, gate).
  struct ReportTerms;

  /// Leaves at the newest tick, sorted by (tree, history).
  const std::vector<Leaf>& leaves() const { return replay_.current(); }
  /// Clusters whose hypothesis search hit its node budget (the k best found so far were used).
  std::uint64_t truncatedSearches() const { return truncated_searches_; }
  std::uint64_t rejectedHandoffs() const { return rejected_handoffs_; }
  /// Reports (counted at every replay of their tick) that carried no noise R or no clutter density
  /// their kind needs, and so took no part (docs/ONERA.md §8).
  std::uint64_t unusableReports() const { return unusable_reports_; }

 private:
  /// The reports one sensor gave at a tick (all reports when the engine has no coverage).
  struct Scan {
    const common::SensorCoverage* coverage = nullptr;  ///< null: uniform detection_probability
    std::vector<std::size_t> reports;                  ///< indices into the tick's slot
  };

  /// The MHT at `tick` on leaves whose state is at tick - 1: one time update, then a scan per
  /// sensor (one scan of every report without coverage), then hypothesis management.
  void processTick(std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot);
  /// The scans of a tick's reports, in sensor order.
  std::vector<Scan> scansOf(std::span<const common::Observation> slot) const;
  /// Branches every leaf on the scan's reports and a miss, and starts the scan's births.
  /// Marks in `gated` the reports some leaf took.
  void runScan(std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot,
               const std::vector<ReportTerms>& terms, const Scan& scan, std::vector<char>& gated) const;
  /// A bearing no leaf took in its scan (index into the tick's slot), and its sensor.
  struct FreeBearing {
    std::size_t report = 0;
    const common::SensorCoverage* sensor = nullptr;
  };
  /// ONERA §II-C's composite reports: after `scan`, every bearing of its sensor that no leaf took,
  /// paired with each of `earlier` (the free bearings of the tick's earlier scans), starts a
  /// tentative tree where the rays cross, if both sensors could see a target there. The tree took
  /// both reports, so it conflicts with any leaf that took either; the tick's later scans branch it
  /// as any leaf. Appends this scan's free bearings to `earlier`.
  void startBearingPairTrees(std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot,
                             const std::vector<ReportTerms>& terms, const Scan& scan, const std::vector<char>& gated,
                             std::vector<FreeBearing>& earlier) const;
  /// The rule of a new tree's score, from initial_score.
  InitialScore initialScoreRule() const {
    return params_.initial_score == 1 ? InitialScore::paper : InitialScore::blackman;
  }
  /// A tentative tree born at `tick` from `reports` (indices into its slot), at `fix` with the
  /// velocity prior (a radar's range rate along its line of sight), scoring `score`.
  Leaf newTree(common::TrackId id, std::int32_t tick, std::vector<std::int32_t> reports, const PositionFix& fix,
               double score, const ClassVector& classes) const;
  /// PD and per-model Pe of the scan's sensor for the leaf's (time-updated) estimate.
  Detectability detectabilityOf(const Scan& scan, const ImmState& imm) const;
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
  /// Of leaves whose last n_scan ticks took the same reports, keeps the best-scoring one.
  void mergeDuplicates(std::vector<Leaf>& leaves) const;
  /// Algorithm 1's N-scan rule for the tree in leaves[begin, end): of the branches `keep` drops,
  /// keeps the best-scoring one on each road section no kept branch is on, up to road_sections_kept.
  void keepOtherSections(const std::vector<Leaf>& leaves, std::size_t begin, std::size_t end,
                         std::vector<char>& keep) const;
  /// Confirms a tentative leaf that holds confirm_reports reports (the SPRT may confirm it sooner).
  void confirmByCount(Leaf& leaf) const;
  /// Clusters, k best hypotheses, P(T), hypothesis pruning and (at a tick's end) N-scan pruning.
  void manageHypotheses(std::vector<Leaf>& leaves, std::int32_t tick, bool n_scan_pruning);
  /// A handed-over leaf that should have joined at first_tick, brought up to the anchor at anchor_tick.
  void catchUp(Leaf& leaf, std::int32_t first_tick, std::int32_t anchor_tick) const;
  /// The leaf that speaks for tree `tree` in leaves (best hypothesis, else most probable).
  static const Leaf* representative(const std::vector<Leaf>& leaves, common::TrackId tree);

  std::uint32_t supernode_;
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
  double initial_score_ = 0.0;
  ModeVector initial_probabilities_;
  WindowReplay<Leaf> replay_;
  std::uint64_t truncated_searches_ = 0;
  std::uint64_t rejected_handoffs_ = 0;
  std::uint64_t unusable_reports_ = 0;
  /// The gate on d^2 per report dimension 0..3, all of the probability gate_chi2 has in 2-D.
  std::array<double, 4> gates_{};
  /// P_G: the probability that a target's report falls in its gate, the same for every dimension.
  double gate_probability_ = 1.0;
};

}  // namespace wsn::supernode::sbmht

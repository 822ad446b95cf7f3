// The rule-based centroid tracking engine ("rulebased", An et al. 2014 §3.2-4.3, with the noise
// mitigation of An et al. 2013 §3.3): clusters of detecting sensors, weighted centroids,
// cluster-to-cluster association through merging and splitting, nearest-neighbour
// measurement-to-track association and Kalman filters with NIS-adapted process noise.
// docs/RULEBASED.md says what it does beyond the paper.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/kalman.hpp"
#include "supernode/engine.hpp"
#include "supernode/rulebased/adaptive_noise.hpp"
#include "supernode/rulebased/cluster_association.hpp"
#include "supernode/rulebased/clustering.hpp"
#include "supernode/rulebased/denoise.hpp"

namespace wsn::supernode::rulebased {

/// The engine's registration: name "rulebased", its parameters with defaults and ranges, factory.
EngineSpec engineSpec();

/// Resolved parameters; lengths in sensor separations Ds (scenario.sensors.spacing), times in ticks.
struct RulebasedParams {
  double link_distance = 1.5;
  double measurement_sigma = 0.2;
  double measurement_lag = 0.0;
  double process_noise = 0.002;
  double process_noise_min = 0.0001;
  double process_noise_max = 0.2;
  double claim_gate = 2.0;
  double max_merge_gap = 3.0;
  double merged_split_distance = 2.0;
  double merged_measurement_sigma = 0.4;
  std::int32_t decision_lag = 0;
  std::int32_t confirm_ticks = 2;
  std::int32_t birth_min_sensors = 2;
  std::int32_t max_coast_ticks = 10;
  std::int32_t max_merge_ticks = 600;
  std::int32_t handoff_ghost_ticks = 50;
  bool denoise = false;
  std::int32_t persistence_ticks = 3;
  double denoise_radius = 3.0;
  std::int32_t denoise_min_cluster = 3;
  double jump_gate = 3.0;
  std::int32_t noise_cluster_sensors = 2;
  bool quick_solution = false;

  /// From the engine context's resolved params (paramTable() decodes them).
  static RulebasedParams fromContext(const EngineContext& context);
};

/// The parameters' one description: key, member, unit, range, default (RulebasedParams{}) and meaning.
const config::FieldTable<RulebasedParams>& paramTable();

/// What the engine did so far, for tests and the docs' tables.
struct RulebasedStats {
  std::int64_t ticks = 0;
  std::int64_t merges = 0;             ///< pairs Rule 1 merged, summed over the ticks (a pair merged for 10 ticks counts 10)
  std::int64_t births = 0;             ///< tracks started from persistent unclaimed clusters
  std::int64_t deletions = 0;          ///< tracks dropped after coasting too long
  std::int64_t jump_rejections = 0;    ///< measurements the centroid-jump gate (2013 eq. 15) refused
  std::int64_t noise_clusters = 0;     ///< clusters Noise_find (2014 Algorithm 4.2.1 c) set aside
  std::int64_t detections_in = 0;      ///< detections received
  std::int64_t detections_kept = 0;    ///< detections left after noise mitigation
};

class RulebasedEngine final : public Engine {
 public:
  explicit RulebasedEngine(const EngineContext& context);

  void adopt(const common::TrackHandoff& handoff) override;
  void step(const ObservationWindow& window) override;
  std::vector<common::TrackEstimate> confirmedTracks() const override;
  std::vector<TrackPrediction> predictions() const override;
  common::TrackHandoff release(common::TrackId track, std::uint32_t to_supernode) override;

  /// One target identity: the cluster it is seen as and the Kalman track fed by it.
  struct Identity {
    common::TrackId id = 0;
    common::GaussianState state;  ///< at state_tick
    std::int32_t state_tick = 0;  ///< the last processed tick, or an adopted track's handoff tick
    NisAdaptation noise;
    ClusterSummary cluster;       ///< centroid and radius at the last processed tick (extrapolated while coasting)
    std::int32_t last_seen_tick = 0;
    std::int32_t hits = 0;
    std::int32_t misses = 0;          ///< consecutive ticks without a cluster of its own, not merged
    std::int32_t merged_ticks = 0;    ///< consecutive ticks inside a merged cluster (Rule 3)
    bool merged = false;
  };

  /// The identities after the last processed tick, sorted by id.
  const std::vector<Identity>& identities() const { return identities_; }
  const RulebasedStats& stats() const { return stats_; }
  /// The clusters of the last processed tick, after noise mitigation (for tests and views).
  const std::vector<Cluster>& lastClusters() const { return clusters_; }

 private:
  struct Candidate {  // an unclaimed cluster that may be a new target (2014 Case 2, first subcase)
    common::TrackId id = 0;
    ClusterSummary cluster;
    common::Vec2 measurement;
    common::Vec2 previous_measurement;
    std::int32_t sightings = 0;
  };
  struct Ghost {  // a track handed to another supernode: its clusters here are not new targets
    common::Vec2 position;  // at `tick`
    common::Vec2 velocity;  // per tick
    std::int32_t tick = 0;
  };

  void processTick(std::int32_t tick, std::span<const common::Observation> slot);
  std::vector<Detection> mitigateNoise(std::int32_t tick, std::vector<Detection> detections);
  common::Vec2 measurementOf(const Cluster& cluster) const;
  /// What the association of one tick decided.
  struct Association {
    std::vector<int> own;        ///< per identity: the index of its own cluster in `clusters`, or -1
    std::vector<bool> consumed;  ///< per cluster: taken as an identity's own or as a merged cluster
    std::vector<int> merged_into;  ///< per merged identity: the merged cluster it is in, else -1
  };
  /// Cases 1 and 2 of Algorithm 4.2.1(a); sets each identity's merged flag.
  Association associate(const std::vector<Cluster>& clusters, const std::vector<std::size_t>& claimed,
                        const std::vector<common::GaussianState>& predicted);
  void updateBirthCandidates(std::int32_t tick, const std::vector<Cluster>& clusters,
                             const std::vector<std::size_t>& unclaimed);
  /// Beyond Rule 3: the measurement each merged identity gets from its share of the merged cluster,
  /// when every member of the group is predicted at least merged_split_distance from the others.
  std::vector<std::optional<common::Vec2>> shareMergedClusters(const std::vector<Cluster>& clusters,
                                                               const Association& association,
                                                               const std::vector<common::GaussianState>& predicted) const;
  common::ConstantVelocityModel model(double q, double measurement_sigma) const;
  /// The identity's state predicted to `tick` (>= its state_tick).
  common::GaussianState stateAt(const Identity& identity, std::int32_t tick) const;
  /// Distance from `position` to the nearest ghost's extrapolated position at `tick` (+inf: none).
  double ghostDistance(common::Vec2 position, std::int32_t tick) const;
  /// The claim test: `cluster` lies within r_a + r_d + claim_gate of the identity's cluster or of
  /// its predicted position.
  bool withinClaim(const ClusterSummary& cluster, const ClusterSummary& identity, common::Vec2 predicted) const;

  std::uint32_t supernode_;
  common::Rect region_;
  double spacing_;  ///< Ds
  double delta_;
  RulebasedParams params_;
  NisAdaptationConfig noise_config_;
  PersistenceFilter persistence_;
  std::int32_t processed_tick_ = 0;
  std::int32_t newest_tick_ = 0;  ///< the window's newest tick at the last step
  std::vector<Identity> identities_;
  std::vector<Candidate> candidates_;
  std::vector<Ghost> ghosts_;
  std::vector<Cluster> clusters_;
  RulebasedStats stats_;
};

}  // namespace wsn::supernode::rulebased

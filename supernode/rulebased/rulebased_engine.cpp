#include "supernode/rulebased/rulebased_engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>

#include "common/assignment.hpp"
#include "common/track_confirmation.hpp"
#include "common/track_id.hpp"

namespace wsn::supernode::rulebased {
namespace {

using common::GaussianState;
using common::kVx;
using common::kVy;
using common::kX;
using common::kY;

common::Vec2 positionOf(const GaussianState& s) { return {s.x(kX), s.x(kY)}; }
common::Vec2 velocityOf(const GaussianState& s) { return {s.x(kVx), s.x(kVy)}; }

bool byId(const RulebasedEngine::Identity& a, const RulebasedEngine::Identity& b) { return a.id < b.id; }

using Resolved = std::map<std::string, common::EngineParam>;

/// The sightings a new target's cluster needs follow the clutter that reaches the tracker.
std::map<std::string, common::ParamDerivation> derivations() {
  std::map<std::string, common::ParamDerivation> d;
  d["confirm_ticks"] = {
      "sightings that balance tracks born of clutter against the wait of every new target; 2 with denoise",
      [](const common::StatisticsSource& stats, const Resolved& r) -> common::Derived {
        // With the An et al. 2013 steps on, isolated noise is removed before clustering: the raw
        // report rate the probe measures never reaches the birth test.
        if (r.at("denoise").value != 0.0)
          return {2.0, "denoise on: the noise steps remove the clutter the probe counts; two sightings give a velocity"};
        const common::ObservationStatistics& s = stats();  // measured only when needed
        const double lambda_f = s.falseAlarmDensity();
        // Sightings must come on consecutive ticks, and a tick is decided decision_lag ticks late:
        // what counts is the reports that have arrived by then (delay <= decision_lag).
        const auto pd_by_lag = s.detectionByLag();
        const auto lag = static_cast<std::size_t>(std::max(0.0, r.at("decision_lag").value));
        const double pd = pd_by_lag[std::min(lag, pd_by_lag.size() - 1)];
        const double births = common::birthsPerTick(s.birth_density.value, s.region_area, s.run_ticks);
        // A candidate continues in a cluster within claim_gate Ds of it (single-report clusters):
        // each sighting after the first is a disc of that radius.
        const double reach = r.at("claim_gate").value * s.sensor_spacing;
        const double gate = 3.14159265358979 * reach * reach;
        const auto n = common::leastCostConfirmation(
            [&](std::int32_t k) { return common::falseTrackRate(k, lambda_f, s.region_area, gate, gate); },
            r.at("max_coast_ticks").value, births,
            [&](std::int32_t k) { return common::ticksForConsecutiveReports(k, pd); }, 2, 100);
        return {static_cast<double>(n),
                "fewest wrong track-ticks: candidates of clutter (" + common::shortNumber(lambda_f) +
                    " per area and tick, gate radius claim_gate Ds = " + common::shortNumber(reach) +
                    ", kept max_coast_ticks) against the wait of " + common::shortNumber(births) +
                    " births per tick, sighted on consecutive ticks at pd " + common::shortNumber(pd) +
                    "; at least 2 sightings, which give a velocity"};
      }};
  // A cluster of the weakest target holds about k = density x pi SR^2 sensors, and often fewer.
  // Clusters of up to 2 sensors are residual noise and a lone sensor never a new target when
  // targets are heard by 4 or more (An et al. 2014's ranges at Ds = 25 m); a weaker target's own
  // clusters would be thrown away, so both thresholds follow half of k, at most 2.
  const auto half_cluster = [](double least, const std::string& what) {
    return common::ParamDerivation{
        "half the sensors that hear the weakest target (density x pi SR^2), at most 2",
        [least, what](const common::StatisticsSource& stats, const Resolved&) -> common::Derived {
          const common::Derived& k = stats().sensors_per_weakest_target;
          return {std::clamp(std::floor(k.value / 2.0), least, 2.0),
                  "half of " + common::shortNumber(k.value) + " sensors (" + k.how + "), " + what};
        }};
  };
  d["noise_cluster_sensors"] = half_cluster(0.0, "at most 2: clusters of at most this many are residual noise");
  d["birth_min_sensors"] = half_cluster(1.0, "1 to 2: a new target's cluster holds at least this many");
  return d;
}

}  // namespace

const config::FieldTable<RulebasedParams>& paramTable() {
  using config::integer;
  using config::real;
  static const config::FieldTable<RulebasedParams> table{
      "tracker.params (rulebased)",
      {
          real<RulebasedParams>(
              "link_distance", &RulebasedParams::link_distance, config::closed(0.01, 100.0), "Ds",
              "two detecting sensors are in one cluster when at most this far apart (Ds); on a grid any value in "
              "[1.415, 2) is eq. 6's 8-connectivity"),
          real<RulebasedParams>("measurement_sigma", &RulebasedParams::measurement_sigma, config::closed(1e-3, 100.0),
                                "Ds", "std. deviation of a centroid's position error, R = sigma^2 I (Ds)"),
          real<RulebasedParams>(
              "measurement_lag", &RulebasedParams::measurement_lag, config::closed(0.0, 100.0), "ticks",
              "ticks by which a centroid lags the target, z = x - lag v: acoustic sensors hear where the target "
              "was when the sound left it (docs/RULEBASED.md derives it; 0: no lag)"),
          real<RulebasedParams>(
              "process_noise", &RulebasedParams::process_noise, config::closed(1e-6, 100.0), "Ds/tick²",
              "initial std. deviation q of the acceleration noise of a new track (Ds per tick^2); adapted by the NIS"),
          real<RulebasedParams>("process_noise_min", &RulebasedParams::process_noise_min, config::closed(1e-6, 100.0),
                                "Ds/tick²", "lower bound of the NIS-adapted q (Ds per tick^2)"),
          real<RulebasedParams>("process_noise_max", &RulebasedParams::process_noise_max, config::closed(1e-6, 100.0),
                                "Ds/tick²", "upper bound of the NIS-adapted q (Ds per tick^2)"),
          real<RulebasedParams>(
              "claim_gate", &RulebasedParams::claim_gate, config::closed(0.0, 1000.0), "Ds",
              "a cluster farther than r_a + r_d + claim_gate from every track's cluster is not theirs: a new target "
              "or noise (Ds)"),
          real<RulebasedParams>(
              "max_merge_gap", &RulebasedParams::max_merge_gap, config::closed(-1000.0, 1000.0), "Ds",
              "Rule 1 merges two clusters only when the gap D of eq. 22 between them is at most this (Ds)"),
          real<RulebasedParams>(
              "merged_split_distance", &RulebasedParams::merged_split_distance, config::closed(0.0, 1000.0), "Ds",
              "merged identities predicted at least this far apart share out their merged cluster by nearest "
              "prediction, each updated with its share's centroid; 0: the paper's Rule 3 (they coast) (Ds)"),
          real<RulebasedParams>("merged_measurement_sigma", &RulebasedParams::merged_measurement_sigma,
                                config::closed(1e-3, 100.0), "Ds",
                                "std. deviation of the position error of a share of a merged cluster (Ds)"),
          integer<RulebasedParams>(
              "decision_lag", &RulebasedParams::decision_lag, 0.0, 100.0, "ticks",
              "ticks a tick waits before it is processed, so that reports the network delayed by up to this many "
              "ticks are used; the tracks are predicted to the newest tick (must stay below window_size)"),
          integer<RulebasedParams>("confirm_ticks", &RulebasedParams::confirm_ticks, 1.0, 100.0, "ticks",
                                   "consecutive ticks an unclaimed cluster must be seen before it becomes a track"),
          integer<RulebasedParams>("birth_min_sensors", &RulebasedParams::birth_min_sensors, 1.0, 10000.0, "sensors",
                                   "a candidate becomes a track only when its cluster has at least this many sensors"),
          integer<RulebasedParams>(
              "max_coast_ticks", &RulebasedParams::max_coast_ticks, 1.0, 100000.0, "ticks",
              "consecutive ticks without a cluster (and not merged) after which a track is deleted"),
          integer<RulebasedParams>("max_merge_ticks", &RulebasedParams::max_merge_ticks, 1.0, 100000.0, "ticks",
                                   "consecutive ticks inside a merged cluster after which a track is deleted"),
          integer<RulebasedParams>(
              "handoff_ghost_ticks", &RulebasedParams::handoff_ghost_ticks, 0.0, 100000.0, "ticks",
              "ticks after a handover during which clusters near the handed-over track's extrapolation are left to "
              "the neighbour (the part of its cluster still on this side of the boundary)"),
          integer<RulebasedParams>(
              "denoise", &RulebasedParams::denoise, 0.0, 1.0, "0/1",
              "1: noise mitigation of An et al. 2013 §3.3 (persistence, spatial test, centroid-jump gate)"),
          integer<RulebasedParams>("persistence_ticks", &RulebasedParams::persistence_ticks, 1.0, 100.0, "ticks",
                                   "denoise step 1 (eq. 11): a sensor must detect in this many consecutive ticks"),
          real<RulebasedParams>("denoise_radius", &RulebasedParams::denoise_radius, config::closed(0.0, 1000.0), "Ds",
                                "denoise step 2 (eq. 13-14): the 3 Ds neighbourhood (Ds)"),
          integer<RulebasedParams>(
              "denoise_min_cluster", &RulebasedParams::denoise_min_cluster, 1.0, 10000.0, "sensors",
              "denoise step 2 with several targets: a sensor with this many survivors within denoise_radius is kept"),
          real<RulebasedParams>(
              "jump_gate", &RulebasedParams::jump_gate, config::closed(0.0, 1000.0), "Ds",
              "denoise step 3 (eq. 15): a centroid farther than this from the track's previous one is discarded (Ds)"),
          integer<RulebasedParams>(
              "noise_cluster_sensors", &RulebasedParams::noise_cluster_sensors, 0.0, 10000.0, "sensors",
              "with denoise, Noise_find (2014 Algorithm 4.2.1 c): clusters of at most this many sensors that survive "
              "the denoising steps are residual noise; 0 keeps every cluster"),
          integer<RulebasedParams>("quick_solution", &RulebasedParams::quick_solution, 0.0, 1.0, "0/1",
                                   "1: An et al. 2013 §3.2: a cluster's measurement is its strongest sensor instead of "
                                   "the weighted centroid"),
      }};
  return table;
}

EngineSpec engineSpec() {
  EngineSpec spec;
  spec.name = "rulebased";
  spec.description =
      "rule-based centroid tracker (An et al. 2014): 8-connected clusters of detecting sensors, weighted "
      "centroids, match/merge indicators through merging and splitting, nearest-neighbour Kalman tracks with "
      "NIS-adapted process noise; optional noise mitigation (An et al. 2013). Lengths in sensor separations Ds";
  spec.params = common::paramSpecs(paramTable(), derivations());
  spec.create = [](const EngineContext& context) -> std::unique_ptr<Engine> {
    return std::make_unique<RulebasedEngine>(context);
  };
  spec.check = [](const common::Scenario& scenario) {
    // The lagged tick must still be in the window when it is processed.
    const auto& lag = scenario.tracker.params.at("decision_lag");
    if (lag.value >= scenario.tracker.window_size)
      throw common::ScenarioError(scenario.source_path + ":" + std::to_string(std::max(lag.line, 1)) +
                                  ": 'tracker.params.decision_lag' " + common::config::compactNumber(lag.value) +
                                  " must be below 'tracker.window_size' " + std::to_string(scenario.tracker.window_size));
  };
  return spec;
}

RulebasedParams RulebasedParams::fromContext(const EngineContext& context) {
  return common::decodeParams(paramTable(), context.params);
}

RulebasedEngine::RulebasedEngine(const EngineContext& context)
    : supernode_(context.supernode),
      region_(context.region),
      spacing_(context.sensor_spacing),
      delta_(context.dynamics.delta),
      params_(RulebasedParams::fromContext(context)),
      persistence_(params_.denoise ? params_.persistence_ticks : 1) {
  // The scenario states q in Ds per tick^2; the filter works in the scenario's lengths.
  noise_config_.q_initial = params_.process_noise * spacing_;
  noise_config_.q_min = std::min(params_.process_noise_min, params_.process_noise) * spacing_;
  noise_config_.q_max = std::max(params_.process_noise_max, params_.process_noise) * spacing_;
}

common::ConstantVelocityModel RulebasedEngine::model(double q, double measurement_sigma) const {
  common::ConstantVelocityModel m(delta_, q, measurement_sigma * spacing_);
  // The centroid shows where the target was `measurement_lag` ticks ago: z = x - lag v.
  m.H(0, kVx) = -params_.measurement_lag;
  m.H(1, kVy) = -params_.measurement_lag;
  return m;
}

std::vector<Detection> RulebasedEngine::mitigateNoise(std::int32_t tick, std::vector<Detection> detections) {
  if (!params_.denoise) return detections;
  const auto persistent = persistence_.apply(tick, detections);                                   // step 1
  return spatialFilter(persistent, params_.denoise_radius * spacing_, params_.denoise_min_cluster);  // step 2
}

common::Vec2 RulebasedEngine::measurementOf(const Cluster& cluster) const {
  return params_.quick_solution ? cluster.strongest : cluster.centroid;
}

bool RulebasedEngine::withinClaim(const ClusterSummary& cluster, const ClusterSummary& identity,
                                  common::Vec2 predicted) const {
  const double reach = cluster.radius + identity.radius + params_.claim_gate * spacing_;
  return common::distance(cluster.centroid, identity.centroid) <= reach ||
         common::distance(cluster.centroid, predicted) <= reach;
}

double RulebasedEngine::ghostDistance(common::Vec2 position, std::int32_t tick) const {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Ghost& g : ghosts_)
    nearest = std::min(nearest, common::distance(g.position + static_cast<double>(tick - g.tick) * g.velocity, position));
  return nearest;
}

void RulebasedEngine::adopt(const common::TrackHandoff& handoff) {
  Identity adopted{handoff.track, {}, handoff.last_tick, NisAdaptation(noise_config_), {}, 0, handoff.hits,
                   handoff.misses, 0, false};
  for (int i = 0; i < common::kStateDim; ++i) adopted.state.x(i) = handoff.state[static_cast<std::size_t>(i)];
  adopted.state.P = common::fromRowMajor(handoff.covariance);
  if (!adopted.state.x.allFinite() || !adopted.state.P.allFinite()) return;  // a corrupt handoff continues nothing
  adopted.last_seen_tick = handoff.last_tick;
  // The radius of a typical cluster (four sensors) until the track's first own cluster here.
  adopted.cluster = {positionOf(adopted.state), clusterRadius(4, spacing_)};
  // A track this supernode started lately on the part of the same target's cluster that lies on
  // its side of the boundary is the same target: the handed-over track, with its longer history,
  // replaces it. Tracks handed over earlier are other targets and stay.
  const double reach = params_.claim_gate * spacing_;
  std::erase_if(identities_, [&](const Identity& local) {
    const double gap = common::distance(local.cluster.centroid, adopted.cluster.centroid) -
                       (local.cluster.radius + adopted.cluster.radius);
    const bool born_here_lately = common::track_id::supernodeOf(local.id) == supernode_ &&
                                  handoff.last_tick - common::track_id::birthTick(local.id) <= params_.handoff_ghost_ticks;
    return local.id != adopted.id && born_here_lately && gap <= reach;
  });
  const auto it = std::lower_bound(identities_.begin(), identities_.end(), adopted, byId);
  if (it != identities_.end() && it->id == adopted.id)
    *it = adopted;
  else
    identities_.insert(it, adopted);
}

common::TrackHandoff RulebasedEngine::release(common::TrackId track, std::uint32_t to_supernode) {
  const auto it = std::find_if(identities_.begin(), identities_.end(), [&](const Identity& i) { return i.id == track; });
  if (it == identities_.end()) return {};
  common::TrackHandoff handoff;
  handoff.track = it->id;
  handoff.to_supernode = to_supernode;
  handoff.last_tick = it->state_tick;
  for (int i = 0; i < common::kStateDim; ++i) handoff.state[static_cast<std::size_t>(i)] = it->state.x(i);
  handoff.covariance = common::toRowMajor(it->state.P);
  handoff.hits = it->hits;
  handoff.misses = it->misses;
  handoff.confirmed = true;
  ghosts_.push_back({positionOf(it->state), delta_ * velocityOf(it->state), it->state_tick});
  identities_.erase(it);
  return handoff;
}

void RulebasedEngine::step(const ObservationWindow& window) {
  newest_tick_ = window.newestTick();
  // A tick is processed decision_lag ticks after it happened, so that reports the network delayed
  // by up to that many ticks are in its slot; a report later still is not used (docs/RULEBASED.md).
  const std::int32_t last = newest_tick_ - params_.decision_lag;
  for (std::int32_t tick = std::max(processed_tick_ + 1, window.oldestTick()); tick <= last; ++tick)
    processTick(tick, window.slot(tick));
}

GaussianState RulebasedEngine::stateAt(const Identity& identity, std::int32_t tick) const {
  GaussianState state = identity.state;
  const auto m = model(identity.noise.q(), params_.measurement_sigma);
  for (std::int32_t t = identity.state_tick; t < tick; ++t) state = common::predict(m, state);
  return state;
}

RulebasedEngine::Association RulebasedEngine::associate(const std::vector<Cluster>& clusters,
                                                        const std::vector<std::size_t>& claimed,
                                                        const std::vector<GaussianState>& predicted) {
  const std::size_t tracks = identities_.size();
  Association out{std::vector<int>(tracks, -1), std::vector<bool>(clusters.size(), false), std::vector<int>(tracks, -1)};
  auto& own = out.own;
  if (tracks == 0) return out;
  if (claimed.empty()) {
    for (auto& identity : identities_) identity.merged = false;
    return out;
  }

  std::vector<ClusterSummary> previous;
  for (const auto& identity : identities_) previous.push_back(identity.cluster);
  std::vector<ClusterSummary> current;
  for (const std::size_t a : claimed) current.push_back({clusters[a].centroid, clusters[a].radius});

  if (current.size() < tracks) {
    // 2014 Case 2, M_k < M_k-1: Algorithm 4.2.1(b).
    const auto indicators = mergeSplitIndicators(previous, current, params_.max_merge_gap * spacing_);
    stats_.merges += static_cast<std::int64_t>(indicators.merged.size());
    std::vector<double> best(tracks, std::numeric_limits<double>::infinity());
    for (std::size_t a = 0; a < current.size(); ++a) {
      const auto d = static_cast<std::size_t>(indicators.nearest[a]);
      if (indicators.merge[d]) {  // Rule 3: a merged cluster feeds neither of its targets
        out.consumed[claimed[a]] = true;
        continue;
      }
      const double s = matchDistance(current[a], previous[d]);  // Rule 2: the nearest by eq. (20)
      if (s < best[d]) {
        best[d] = s;
        own[d] = static_cast<int>(claimed[a]);
      }
    }
    for (std::size_t d = 0; d < tracks; ++d) {
      identities_[d].merged = indicators.merge[d];
      if (own[d] >= 0) out.consumed[static_cast<std::size_t>(own[d])] = true;
      if (!indicators.merge[d]) continue;
      // The merged cluster a merged identity is in: the nearest of the merged clusters to its prediction.
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t a = 0; a < current.size(); ++a) {
        const auto chooser = static_cast<std::size_t>(indicators.nearest[a]);
        const double gap = common::distance(current[a].centroid, positionOf(predicted[d]));
        if (indicators.merge[chooser] && gap < nearest) {
          nearest = gap;
          out.merged_into[d] = static_cast<int>(claimed[a]);
        }
      }
      // Beyond Rule 1: a target is in a merged cluster only when its prediction lies within that
      // cluster's reach. One that vanished beside another has no cluster left, not a merged one.
      if (out.merged_into[d] >= 0 &&
          nearest > clusters[static_cast<std::size_t>(out.merged_into[d])].radius + params_.claim_gate * spacing_) {
        identities_[d].merged = false;
        out.merged_into[d] = -1;
      }
    }
    // A merged cluster left with a single merged identity is that identity's own (Rule 2).
    for (std::size_t d = 0; d < tracks; ++d) {
      const int a = out.merged_into[d];
      if (a < 0) continue;
      const auto members = std::count(out.merged_into.begin(), out.merged_into.end(), a);
      if (members > 1) continue;
      identities_[d].merged = false;
      out.merged_into[d] = -1;
      if (own[d] < 0) own[d] = a;
    }
    return out;
  }

  // 2014 Case 1 (M_k = M_k-1) and the case M_k > M_k-1 (a cluster merged before the tracks began
  // splits, a new target appears next to a track, or noise survives): eq. (27) between clusters
  // and the predicted tracks, solved as one optimal assignment so that two tracks never take the
  // same cluster; clusters left over are candidate new targets.
  // A pair outside the claim reach of each other is never assigned: the track coasts rather than
  // jump to the cluster of another target.
  std::vector<double> cost(tracks * current.size(), common::kForbidden);
  for (std::size_t d = 0; d < tracks; ++d) {
    const ClusterSummary track{positionOf(predicted[d]), previous[d].radius};
    for (std::size_t a = 0; a < current.size(); ++a)
      if (withinClaim(current[a], previous[d], track.centroid)) cost[d * current.size() + a] = matchDistance(current[a], track);
  }
  const auto assignment = common::solveAssignment(cost, tracks, current.size());
  for (std::size_t d = 0; d < tracks; ++d) {
    identities_[d].merged = false;
    if (assignment[d] < 0) continue;
    own[d] = static_cast<int>(claimed[static_cast<std::size_t>(assignment[d])]);
    out.consumed[static_cast<std::size_t>(own[d])] = true;
  }
  return out;
}

std::vector<std::optional<common::Vec2>> RulebasedEngine::shareMergedClusters(
    const std::vector<Cluster>& clusters, const Association& association, const std::vector<GaussianState>& predicted) const {
  std::vector<std::optional<common::Vec2>> out(identities_.size());
  if (!(params_.merged_split_distance > 0.0)) return out;
  const double apart = params_.merged_split_distance * spacing_;
  for (std::size_t a = 0; a < clusters.size(); ++a) {
    std::vector<std::size_t> members;
    for (std::size_t d = 0; d < identities_.size(); ++d)
      if (association.merged_into[d] == static_cast<int>(a)) members.push_back(d);
    if (members.size() < 2) continue;
    bool separable = true;
    for (std::size_t i = 0; i < members.size() && separable; ++i)
      for (std::size_t j = i + 1; j < members.size() && separable; ++j)
        separable = common::distance(positionOf(predicted[members[i]]), positionOf(predicted[members[j]])) >= apart;
    if (!separable) continue;  // too close to tell apart: Rule 3, the group coasts
    // Each detection goes to the nearest predicted member; each member's share gives it a weighted
    // centroid (eq. 10) as its measurement.
    std::vector<double> weight(members.size(), 0.0);
    std::vector<int> count(members.size(), 0);
    std::vector<common::Vec2> sum(members.size());
    for (const auto& detection : clusters[a].members) {
      std::size_t best = 0;
      for (std::size_t i = 1; i < members.size(); ++i)
        if (common::squaredDistance(detection.position, positionOf(predicted[members[i]])) <
            common::squaredDistance(detection.position, positionOf(predicted[members[best]])))
          best = i;
      const double w = centroidWeight(detection);
      weight[best] += w;
      ++count[best];
      sum[best] = sum[best] + w * detection.position;
    }
    // One sensor's position says too little about a target inside a merged cluster.
    for (std::size_t i = 0; i < members.size(); ++i)
      if (count[i] >= 2) out[members[i]] = (1.0 / weight[i]) * sum[i];
  }
  return out;
}

void RulebasedEngine::processTick(std::int32_t tick, std::span<const common::Observation> slot) {
  ++stats_.ticks;
  std::vector<Detection> detections;
  detections.reserve(slot.size());
  for (const auto& o : slot) detections.push_back({o.sensor, {o.x, o.y}, o.power_level});
  stats_.detections_in += static_cast<std::int64_t>(detections.size());
  detections = mitigateNoise(tick, std::move(detections));
  stats_.detections_kept += static_cast<std::int64_t>(detections.size());
  clusters_ = clusterDetections(detections, params_.link_distance * spacing_, spacing_);
  if (params_.denoise) {
    // Noise_find (Algorithm 4.2.1 c): a lone noisy sensor next to a target survives the spatial test
    // and, as a cluster of its own, would pass for a split; such small clusters are residual noise.
    const auto before = clusters_.size();
    std::erase_if(clusters_, [&](const Cluster& c) {
      return c.evidence(params_.noise_cluster_sensors + 1) <= params_.noise_cluster_sensors;
    });
    stats_.noise_clusters += static_cast<std::int64_t>(before - clusters_.size());
  }

  std::vector<GaussianState> predicted;
  for (const auto& identity : identities_) predicted.push_back(stateAt(identity, tick));

  // A cluster is claimed by the tracks when it lies near one of them (its previous cluster or its
  // prediction); the others are new targets or noise.
  std::vector<std::size_t> claimed;
  std::vector<std::size_t> unclaimed;
  std::vector<std::size_t> left_to_neighbour;
  for (std::size_t a = 0; a < clusters_.size(); ++a) {
    const ClusterSummary cluster{clusters_[a].centroid, clusters_[a].radius};
    // The part of a handed-over target's cluster still on this side of the boundary belongs to the
    // neighbour's track, unless one of this supernode's own tracks is nearer to it.
    const double ghost = ghostDistance(cluster.centroid, tick);
    bool near = false;
    bool nearer_than_ghost = false;
    for (std::size_t d = 0; d < identities_.size(); ++d) {
      if (!withinClaim(cluster, identities_[d].cluster, positionOf(predicted[d]))) continue;
      near = true;
      nearer_than_ghost = nearer_than_ghost || common::distance(cluster.centroid, positionOf(predicted[d])) < ghost;
    }
    if (ghost <= (params_.claim_gate + params_.jump_gate) * spacing_ && !nearer_than_ghost)
      left_to_neighbour.push_back(a);
    else
      (near ? claimed : unclaimed).push_back(a);
  }

  const Association association = associate(clusters_, claimed, predicted);
  const auto shares = shareMergedClusters(clusters_, association, predicted);
  for (std::size_t d = 0; d < identities_.size(); ++d) {
    Identity& identity = identities_[d];
    identity.state_tick = tick;
    const int own = association.own[d];
    std::optional<common::Vec2> z;
    double sigma = params_.measurement_sigma;
    if (own >= 0) {
      z = measurementOf(clusters_[static_cast<std::size_t>(own)]);
    } else if (shares[d]) {
      z = shares[d];
      sigma = params_.merged_measurement_sigma;
    }
    if (z && params_.denoise && !withinJump(identity.cluster.centroid, *z, params_.jump_gate * spacing_)) {
      ++stats_.jump_rejections;  // 2013 step 3: the centroid jumped, most likely onto noise
      z.reset();
    }
    const auto m = model(identity.noise.q(), sigma);
    const auto updated = z ? common::update(m, predicted[d], common::MeasurementVector(z->x, z->y)) : std::nullopt;
    if (!updated) {  // coast: the prediction, and the centroid extrapolated (Rule 3)
      identity.state = predicted[d];
      identity.cluster.centroid = identity.cluster.centroid + delta_ * velocityOf(predicted[d]);
      if (identity.merged)
        ++identity.merged_ticks;
      else
        ++identity.misses;
      continue;
    }
    identity.noise.observe(
        common::mahalanobisSquared(common::innovation(m, predicted[d], common::MeasurementVector(z->x, z->y))));
    identity.state = *updated;
    if (own >= 0)
      identity.cluster = {clusters_[static_cast<std::size_t>(own)].centroid, clusters_[static_cast<std::size_t>(own)].radius};
    else
      identity.cluster.centroid = *z;  // its share of the merged cluster; the radius stays its own
    identity.last_seen_tick = tick;
    ++identity.hits;
    identity.misses = 0;
    identity.merged_ticks = 0;
  }
  // Claimed clusters that neither a track nor a merge took (more clusters than tracks) may be new
  // targets too.
  for (const std::size_t a : claimed)
    if (!association.consumed[a]) unclaimed.push_back(a);
  std::sort(unclaimed.begin(), unclaimed.end());

  const auto before = identities_.size();
  std::erase_if(identities_, [&](const Identity& i) {
    return i.misses > params_.max_coast_ticks || i.merged_ticks > params_.max_merge_ticks ||
           region_.distanceTo(positionOf(i.state)) > 0.0;
  });
  stats_.deletions += static_cast<std::int64_t>(before - identities_.size());

  std::erase_if(ghosts_, [&](const Ghost& g) { return tick - g.tick > params_.handoff_ghost_ticks; });
  updateBirthCandidates(tick, clusters_, unclaimed);
  processed_tick_ = tick;
}

void RulebasedEngine::updateBirthCandidates(std::int32_t tick, const std::vector<Cluster>& clusters,
                                            const std::vector<std::size_t>& unclaimed) {
  const std::vector<std::size_t>& fresh = unclaimed;

  // Each candidate of the previous tick continues in at most one cluster near it (optimal
  // assignment on eq. 20); the rest start anew, and candidates not seen again are dropped.
  std::vector<double> cost(candidates_.size() * fresh.size(), common::kForbidden);
  for (std::size_t c = 0; c < candidates_.size(); ++c)
    for (std::size_t f = 0; f < fresh.size(); ++f) {
      const Cluster& cluster = clusters[fresh[f]];
      const ClusterSummary summary{cluster.centroid, cluster.radius};
      const double reach = cluster.radius + candidates_[c].cluster.radius + params_.claim_gate * spacing_;
      if (common::distance(cluster.centroid, candidates_[c].cluster.centroid) <= reach)
        cost[c * fresh.size() + f] = matchDistance(summary, candidates_[c].cluster);
    }
  const auto assignment = common::solveAssignment(cost, candidates_.size(), fresh.size());
  std::vector<int> continued(fresh.size(), -1);
  for (std::size_t c = 0; c < candidates_.size(); ++c)
    if (assignment[c] >= 0) continued[static_cast<std::size_t>(assignment[c])] = static_cast<int>(c);

  std::vector<Candidate> next;
  const double sigma = params_.measurement_sigma * spacing_;
  for (std::size_t f = 0; f < fresh.size(); ++f) {
    const Cluster& cluster = clusters[fresh[f]];
    Candidate candidate;
    if (continued[f] >= 0) {
      candidate = candidates_[static_cast<std::size_t>(continued[f])];
      candidate.previous_measurement = candidate.measurement;
    } else {
      candidate.id = common::track_id::birth(supernode_, tick, cluster.members.front().sensor);
    }
    candidate.cluster = {cluster.centroid, cluster.radius};
    candidate.measurement = measurementOf(cluster);
    ++candidate.sightings;
    if (candidate.sightings < params_.confirm_ticks || cluster.evidence(params_.birth_min_sensors) < params_.birth_min_sensors) {
      next.push_back(candidate);
      continue;
    }
    // Two-point initiation: the velocity is the difference of the last two measurements, with
    // the variance of that difference; a single sighting leaves it unknown (one Ds per tick).
    Identity born{candidate.id, {}, tick, NisAdaptation(noise_config_), candidate.cluster, tick, candidate.sightings,
                  0, 0, false};
    common::Vec2 v;
    double velocity_variance = spacing_ * spacing_ / (delta_ * delta_);
    if (candidate.sightings >= 2) {
      v = (1.0 / delta_) * (candidate.measurement - candidate.previous_measurement);
      velocity_variance = 2.0 * sigma * sigma / (delta_ * delta_);
    }
    const common::Vec2 position = candidate.measurement + params_.measurement_lag * v;  // undo the lag
    born.state.x << position.x, position.y, v.x, v.y;
    born.state.P.diagonal() << sigma * sigma, sigma * sigma, velocity_variance, velocity_variance;
    identities_.insert(std::lower_bound(identities_.begin(), identities_.end(), born, byId), born);
    ++stats_.births;
  }
  candidates_ = std::move(next);
}

std::vector<common::TrackEstimate> RulebasedEngine::confirmedTracks() const {
  std::vector<common::TrackEstimate> out;
  for (const auto& identity : identities_) {
    // With a decision lag the last processed tick is behind the newest: report the prediction.
    const GaussianState state = stateAt(identity, std::max(newest_tick_, identity.state_tick));
    common::TrackEstimate e;
    e.track = identity.id;
    e.x = state.x(kX);
    e.y = state.x(kY);
    e.vx = state.x(kVx);
    e.vy = state.x(kVy);
    e.covariance = common::toRowMajor(state.P);
    e.last_seen_tick = identity.last_seen_tick;
    out.push_back(e);
  }
  return out;
}

std::vector<TrackPrediction> RulebasedEngine::predictions() const {
  std::vector<TrackPrediction> out;
  for (const auto& identity : identities_)
    out.push_back({identity.id, positionOf(stateAt(identity, std::max(newest_tick_, identity.state_tick) + 1))});
  return out;
}

}  // namespace wsn::supernode::rulebased

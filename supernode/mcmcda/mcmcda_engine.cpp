#include "supernode/mcmcda/mcmcda_engine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "common/rng.hpp"
#include "common/track_id.hpp"

namespace wsn::supernode::mcmcda {
namespace {

TrackState stateFromHandoff(const common::TrackHandoff& h) {
  // Both engines' filters are axis-symmetric (R = r^2 I, Q and the prior per axis alike), so the
  // x and y blocks of P agree; averaging them makes a foreign or rounded covariance symmetric too.
  const auto P = [&](int r, int c) { return h.covariance[static_cast<std::size_t>(r * 4 + c)]; };
  TrackState s;
  s.tick = h.last_tick;
  s.x = h.state[0];
  s.y = h.state[1];
  s.vx = h.state[2];
  s.vy = h.state[3];
  s.cov.pp = 0.5 * (P(0, 0) + P(1, 1));
  s.cov.pv = 0.25 * (P(0, 2) + P(2, 0) + P(1, 3) + P(3, 1));
  s.cov.vv = 0.5 * (P(2, 2) + P(3, 3));
  return s;
}

bool finite(const TrackState& s) {
  return std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.vx) && std::isfinite(s.vy) &&
         std::isfinite(s.cov.pp) && std::isfinite(s.cov.pv) && std::isfinite(s.cov.vv) && s.cov.pp >= 0.0 &&
         s.cov.vv >= 0.0;
}

/// The per-axis covariance as the 4 x 4 of (x, y, vx, vy): the axes are independent.
std::array<double, 16> fullCovariance(const AxisCovariance& c) {
  return {c.pp, 0, c.pv, 0,  //
          0, c.pp, 0, c.pv,  //
          c.pv, 0, c.vv, 0,  //
          0, c.pv, 0, c.vv};
}

common::TrackEstimate estimate(common::TrackId id, const TrackState& s, std::int32_t last_seen_tick) {
  return {id, s.x, s.y, s.vx, s.vy, fullCovariance(s.cov), last_seen_tick, {}, {}};
}

}  // namespace

EngineSpec engineSpec() {
  EngineSpec spec;
  spec.name = "mcmcda";
  spec.description =
      "sliding-window Markov chain Monte Carlo data association (Oh et al. §VI): samples partitions of the "
      "window's observations into tracks and false alarms under eq. (3), keeps the best";
  spec.params = common::paramSpecs(paramTable(), paramDerivations());
  spec.create = [](const EngineContext& context) -> std::unique_ptr<Engine> {
    return std::make_unique<McmcdaEngine>(context);
  };
  return spec;
}

McmcdaEngine::McmcdaEngine(const EngineContext& context)
    : McmcdaEngine(McmcdaParams::fromContext(context), context.region, context.seed, context.supernode,
                   common::track_id::Space::ofSupernode(context.supernode)) {
  detection_share_ = detectionShare(context);
}

McmcdaEngine::McmcdaEngine(const McmcdaParams& params, const common::Rect& region, std::uint64_t seed,
                           std::uint32_t stream_key, common::track_id::Space ids)
    : stream_key_(stream_key),
      ids_(ids),
      seed_(seed),
      region_(region),
      params_(params),
      motion_(params_.model),
      arrived_by_age_{std::min(1.0, params_.model.detection_probability)} {}

common::TrackId McmcdaEngine::mintId() { return ids_.mint(next_serial_++); }

void McmcdaEngine::adopt(const common::TrackHandoff& handoff) {
  const TrackState state = stateFromHandoff(handoff);
  if (!finite(state)) {
    ++rejected_handoffs_;
    return;
  }
  LiveTrack track;
  track.id = handoff.track;
  ProblemObservation anchor;
  anchor.tick = handoff.last_tick;
  anchor.x = state.x;
  anchor.y = state.y;
  anchor.anchor = true;
  anchor.prior = state;
  track.anchor = anchor;
  // The sender's state is a prediction to last_tick; its target was last seen `misses` ticks
  // before, and the coasting budget counts from there.
  track.anchor_misses = std::max(0, handoff.misses);
  track.past_observations = handoff.hits;
  const auto it = std::lower_bound(tracks_.begin(), tracks_.end(), track.id,
                                   [](const LiveTrack& t, common::TrackId id) { return t.id < id; });
  if (it != tracks_.end() && it->id == track.id)
    *it = std::move(track);  // a track coming back supersedes what we had
  else
    tracks_.insert(it, std::move(track));
}

void McmcdaEngine::step(const ObservationWindow& window) {
  const std::int32_t newest = window.newestTick();
  if (newest < 1) return;
  newest_tick_ = newest;
  oldest_tick_ = window.oldestTick();
  commitLeavingObservations(oldest_tick_);
  // Eq. (3) allows a target one report a tick: a model that reports every detecting sensor has its
  // reports of a tick merged first (merge_radius), and the chain sees one per cluster.
  std::optional<ObservationWindow> merged;
  if (params_.merge_radius > 0.0) merged = window.merged(params_.merge_radius);
  associate(merged ? *merged : window, newest);
}

void McmcdaEngine::associate(const ObservationWindow& window, std::int32_t newest) {
  const WindowProblem wp = buildProblem(window);
  const StartState start = startState(wp, tracks_, group_of_, params_);

  // Algorithm 1: nmc iterations from there, keeping the best partition.
  Sampler sampler(wp.problem);
  sampler.setState(start.partition);
  common::Stream rng(seed_, common::Purpose::kTracker, stream_key_, newest);
  sampler.run(params_.iterations, rng);
  const Partition best = sampler.bestState();
  last_step_ = StepStats{wp.problem.size(), static_cast<std::int32_t>(best.size()), sampler.bestLogPosterior(),
                         sampler.stats()};
  learnDelays(window);
  // Step 5: ω̂'s tracks under the ids they continue, and the anchored tracks a report of the next
  // window could still continue.
  const std::int32_t next_oldest = std::max(1, newest_tick_ + 1 - window.windowSize() + 1);
  tracks_ = adoptBest(std::move(tracks_), wp, best, start.owner, {propose_id_, [this] { return mintId(); }}, params_,
                      next_oldest);
  // A track of one report (confirmation at one report) that the chain did not continue stays while
  // eq. (3) prefers a target to a false alarm for its report, given the ticks it has gone unseen
  // since, whose reports would mostly have arrived by now if it were there. Judged after the chain,
  // which has seen the window's newest reports; a report of the newest tick is decided by
  // confirmation at one report.
  std::erase_if(tracks_, [&](const LiveTrack& t) {
    return t.isOneReport() && t.observations.front().tick < newest_tick_ && !loneTargetLikely(t);
  });
}

void McmcdaEngine::commitLeavingObservations(std::int32_t oldest) {
  // Observations that leave the window are committed: the track's filtered state at the last of
  // them becomes its anchor, so the chain continues the track without re-deciding its past. So is a
  // track of one report: its existence carries on from window to window, and a report up to
  // max_gap ticks later may still continue it.
  for (auto& track : tracks_) {
    std::size_t gone = 0;
    while (gone < track.observations.size() && track.observations[gone].tick < oldest) ++gone;
    if (gone == 0) continue;
    const ObservationKey& last_gone = track.observations[gone - 1];
    ProblemObservation anchor;
    anchor.tick = last_gone.tick;
    anchor.x = last_gone.x;  // links are judged from the observation, as before
    anchor.y = last_gone.y;
    anchor.anchor = true;
    anchor.prior = track.states[gone - 1];
    track.anchor = anchor;
    track.anchor_misses = 0;
    track.past_observations += static_cast<std::int32_t>(gone);
    track.observations.erase(track.observations.begin(), track.observations.begin() + static_cast<std::ptrdiff_t>(gone));
    track.states.erase(track.states.begin(), track.states.begin() + static_cast<std::ptrdiff_t>(gone));
  }
  std::erase_if(tracks_, [&](const LiveTrack& t) { return t.observations.empty() && !canContinue(t, oldest); });
  std::erase_if(released_, [&](const ObservationKey& k) { return k.tick < oldest; });
}

WindowProblem McmcdaEngine::buildProblem(const ObservationWindow& window) const {
  // One anchor per track that has one, then the window's observations — except those of tracks
  // handed to a neighbour: the neighbour's track accounts for them.
  struct Entry {
    ProblemObservation observation;
    ObservationKey key;
    std::int32_t anchor_of = -1;
  };
  std::vector<Entry> entries;
  for (std::size_t k = 0; k < tracks_.size(); ++k)
    if (tracks_[k].anchor) entries.push_back({*tracks_[k].anchor, {}, static_cast<std::int32_t>(k)});
  for (std::int32_t t = window.oldestTick(); t <= window.newestTick(); ++t)
    for (const auto& o : window.slot(t)) {
      const ObservationKey key{o.tick_generated, o.sensor, o.x, o.y};
      if (std::binary_search(released_.begin(), released_.end(), key)) continue;
      entries.push_back({ProblemObservation{o.tick_generated, o.x, o.y, false, {}}, key, -1});
    }
  std::stable_sort(entries.begin(), entries.end(),
                   [](const Entry& a, const Entry& b) { return a.observation.tick < b.observation.tick; });
  std::vector<ProblemObservation> observations;
  std::vector<ObservationKey> keys;
  std::vector<std::int32_t> anchor_of;
  std::vector<std::int32_t> anchor_index(tracks_.size(), -1);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    observations.push_back(entries[i].observation);
    keys.push_back(entries[i].key);
    anchor_of.push_back(entries[i].anchor_of);
    if (entries[i].anchor_of >= 0)
      anchor_index[static_cast<std::size_t>(entries[i].anchor_of)] = static_cast<std::int32_t>(i);
  }
  return WindowProblem{Problem(params_.model, std::move(observations), window.newestTick(), &detection_share_),
                       std::move(keys), std::move(anchor_of), std::move(anchor_index)};
}

void McmcdaEngine::learnDelays(const ObservationWindow& window) {
  // Learn from the oldest slot once it is final (the window is full: anything later is stale),
  // and from each tick once. Every delivered report counts, whatever ω̂ made of it.
  const std::int32_t settled = window.newestTick() - window.windowSize() + 1;
  if (settled < 1 || settled <= settled_tick_) return;
  settled_tick_ = settled;
  if (delay_counts_.empty()) {
    delay_counts_.assign(static_cast<std::size_t>(window.windowSize()), 0.0);
    arrived_by_age_.assign(delay_counts_.size(), 0.0);
  }
  for (const auto& o : window.slot(settled)) {
    const auto delay = static_cast<std::size_t>(std::max(0, o.tick_delivered - o.tick_generated));
    delay_counts_[std::min(delay, delay_counts_.size() - 1)] += 1.0;
    delay_total_ += 1.0;
  }
  // pd of eq. (3) is the chance that a live target's report of a tick is in the window, averaged
  // over the window's ticks (derived so: sensed x arrived by each lag, averaged). Its share by age
  // follows the delays: pd_a = pd F(a) / mean_j F(j), F(a) = P(delay <= a) from every delivered
  // report, with one pseudo-report on time so that it starts at "no delays". Not learnt from ω̂'s
  // tracks, whose hits over the ticks between their first and last report count the bursts of a
  // lossy network and none of the silences around them, nor a target seen once.
  std::vector<double> delivered(delay_counts_.size());
  double on_time = 1.0;
  for (std::size_t d = 0; d < delay_counts_.size(); ++d) {
    on_time += delay_counts_[d];
    delivered[d] = on_time / (delay_total_ + 1.0);
  }
  double mean = 0.0;
  for (const double f : delivered) mean += f;
  mean /= static_cast<double>(delivered.size());
  for (std::size_t d = 0; d < delivered.size(); ++d)
    arrived_by_age_[d] = std::min(1.0, params_.model.detection_probability * delivered[d] / mean);
}

double McmcdaEngine::unseenLikelihood(const LiveTrack& track, std::int32_t tick, double& there_at_tick) const {
  // The target's silence since its last observation (silenceAfter), each tick j's report in the
  // window by now with the probability of its age n - j at the track's predicted position then
  // (arrivedBy). It is there at `tick` when it ended after it, or has not.
  const TrackState& last = track.lastState();
  const auto arrived = [&](std::int32_t j) {
    return arrivedBy(newest_tick_ - j, predictedPosition(last, j, params_.model.delta));
  };
  const Silence s =
      silenceAfter(track.lastSeenTick(), newest_tick_, tick, params_.model.termination_probability, arrived);
  there_at_tick = s.thereAtSplit();
  return s.total();
}

bool McmcdaEngine::probablyAlive(const LiveTrack& track, std::int32_t tick) const {
  double there = 0.0;
  const double all = unseenLikelihood(track, tick, there);
  return there >= all - there;
}

bool McmcdaEngine::loneTargetLikely(const LiveTrack& track) const {
  // Eq. (3) for the report of a one-report track, as the chain weighs a report left out of every
  // track (Problem::unassignedLogDensity): a target born unseen at its tick or before (lambda_b x
  // unseenBirthWeight), detected where it was (pd there), and unseen since, however it ended
  // (unseenLikelihood: by report age, as the delays say); against a false alarm (lambda_f).
  double there = 0.0;
  const ModelParams& m = params_.model;
  const TrackState& at_report = track.lastState();
  const double pd = std::min(1.0, m.detection_probability * detection_share_.at({at_report.x, at_report.y}));
  return m.birth_density * unseenBirthWeight(m, at_report.tick) * pd * unseenLikelihood(track, newest_tick_, there) >=
         m.false_alarm_density;
}

std::vector<McmcdaEngine::LiveTrackView> McmcdaEngine::liveTracks() const {
  std::vector<LiveTrackView> out;
  for (const auto& track : tracks_) {
    if (!isLive(track)) continue;
    const TrackState& last = track.lastState();
    const TrackState now = motion_.predict(last, newest_tick_ - last.tick);
    // No sensor sees a target outside the region: a track that coasted out of it followed a
    // target that left.
    out.push_back({estimate(track.id, now, track.lastSeenTick()), track.observations,
                   track.totalObservations() >= params_.confirm_observations, probablyAlive(track, newest_tick_),
                   region_.contains({now.x, now.y})});
  }
  return out;
}

std::vector<common::TrackEstimate> McmcdaEngine::confirmedTracks() const {
  std::vector<common::TrackEstimate> out;
  for (const auto& view : liveTracks())
    if (view.confirmed && view.probably_alive && view.in_region) out.push_back(view.now);
  return out;
}

std::vector<common::TrackEstimate> McmcdaEngine::tracksAt(std::int32_t tick) const {
  std::vector<common::TrackEstimate> out;
  for (const auto& track : tracks_) {
    if (track.totalObservations() < params_.confirm_observations || track.observations.empty()) continue;
    const std::int32_t first = track.anchor ? track.anchor->tick : track.observations.front().tick;
    if (tick < first || tick > track.observations.back().tick) continue;
    const TrackState* at = track.anchor ? &track.anchor->prior : nullptr;
    std::int32_t seen = track.anchor ? track.anchor->tick - track.anchor_misses : 0;
    for (std::size_t m = 0; m < track.observations.size() && track.observations[m].tick <= tick; ++m) {
      at = &track.states[m];
      seen = track.observations[m].tick;
    }
    out.push_back(estimate(track.id, motion_.predict(*at, tick - at->tick), seen));
  }
  return out;
}

namespace {

/// One Rauch-Tung-Striebel step per axis: the filtered state `at` (at its tick) smoothed with the
/// smoothed state `next` of a later tick, through eq. (8)'s prediction `predicted` of `at` to
/// next's tick: x_s = x_f + C (x_s' - x_p), P_s = P_f + C (P_s' - P_p) C^T, C = P_f F^T P_p^-1.
TrackState smoothWith(const TrackState& at, const TrackState& predicted, const TrackState& next, double gap) {
  const double d = gap;
  // P_f F^T with F = [[1, d], [0, 1]]: rows (pp + d pv, pv), (pv + d vv, vv).
  const double a11 = at.cov.pp + d * at.cov.pv, a12 = at.cov.pv;
  const double a21 = at.cov.pv + d * at.cov.vv, a22 = at.cov.vv;
  const double det = predicted.cov.pp * predicted.cov.vv - predicted.cov.pv * predicted.cov.pv;
  if (!(det > 0.0)) return at;
  const double i11 = predicted.cov.vv / det, i12 = -predicted.cov.pv / det, i22 = predicted.cov.pp / det;
  const double c11 = a11 * i11 + a12 * i12, c12 = a11 * i12 + a12 * i22;
  const double c21 = a21 * i11 + a22 * i12, c22 = a21 * i12 + a22 * i22;
  TrackState s = at;
  const auto axis = [&](double p, double v, double np, double nv, double pp, double pv) {
    return std::pair{p + c11 * (np - pp) + c12 * (nv - pv), v + c21 * (np - pp) + c22 * (nv - pv)};
  };
  std::tie(s.x, s.vx) = axis(at.x, at.vx, next.x, next.vx, predicted.x, predicted.vx);
  std::tie(s.y, s.vy) = axis(at.y, at.vy, next.y, next.vy, predicted.y, predicted.vy);
  // P_s = P_f + C (P_s' - P_p) C^T on the shared per-axis covariance.
  const double d11 = next.cov.pp - predicted.cov.pp, d12 = next.cov.pv - predicted.cov.pv;
  const double d22 = next.cov.vv - predicted.cov.vv;
  const double m11 = c11 * d11 + c12 * d12, m12 = c11 * d12 + c12 * d22;
  const double m21 = c21 * d11 + c22 * d12, m22 = c21 * d12 + c22 * d22;
  s.cov.pp = at.cov.pp + m11 * c11 + m12 * c12;
  s.cov.pv = at.cov.pv + m11 * c21 + m12 * c22;
  s.cov.vv = at.cov.vv + m21 * c21 + m22 * c22;
  return s;
}

}  // namespace

std::optional<std::vector<common::TrackEstimate>> McmcdaEngine::revisedTracks(std::int32_t tick) const {
  std::vector<common::TrackEstimate> out;
  for (const auto& track : tracks_) {
    if (track.totalObservations() < params_.confirm_observations || track.observations.empty()) continue;
    const std::int32_t first = track.anchor ? track.anchor->tick : track.observations.front().tick;
    if (tick < first) continue;
    if (tick > track.observations.back().tick) {
      // Past its last observation (a report still in transit, near the end of a run or a
      // handoff): the filtered state predicted, while its target is more likely there than gone
      // at `tick`, judged by the reports of the ticks after it that have had time to arrive, and
      // inside the region.
      if (!isLive(track) || !probablyAlive(track, tick)) continue;
      const TrackState& last = track.states.back();
      const TrackState predicted = motion_.predict(last, tick - last.tick);
      if (!region_.contains({predicted.x, predicted.y})) continue;
      out.push_back(estimate(track.id, predicted, track.observations.back().tick));
      continue;
    }
    // The track's filtered states in tick order, the anchor's prior first.
    std::vector<const TrackState*> filtered;
    if (track.anchor) filtered.push_back(&track.anchor->prior);
    for (const auto& state : track.states) filtered.push_back(&state);
    // Smooth backwards from the last element while the one before is still at or after `tick`.
    std::size_t k = filtered.size() - 1;
    TrackState smoothed = *filtered[k];
    while (k > 0 && filtered[k - 1]->tick >= tick) {
      const TrackState& at = *filtered[k - 1];
      const std::int32_t gap = smoothed.tick - at.tick;
      smoothed = smoothWith(at, motion_.predict(at, gap), smoothed, gap * params_.model.delta);
      --k;
    }
    // `tick` strictly between two elements (a missed report): the filtered state predicted to it,
    // smoothed with the element after.
    if (smoothed.tick > tick && k > 0) {
      const TrackState between = motion_.predict(*filtered[k - 1], tick - filtered[k - 1]->tick);
      const std::int32_t gap = smoothed.tick - tick;
      smoothed = smoothWith(between, motion_.predict(between, gap), smoothed, gap * params_.model.delta);
    }
    std::int32_t seen = track.anchor ? track.anchor->tick - track.anchor_misses : 0;
    for (const auto& key : track.observations)
      if (key.tick <= tick) seen = key.tick;
    out.push_back(estimate(track.id, smoothed, seen));
  }
  return out;
}

std::vector<TrackPrediction> McmcdaEngine::predictions() const {
  std::vector<TrackPrediction> out;
  for (const auto& track : tracks_) {
    // Handed on even when judged gone for now: the misses travel with it, so the receiver judges
    // it the same way, and late reports may still revive it there. A one-report track is not: the
    // receiver would take it for an established track and keep it going, where here it lives only
    // while eq. (3) prefers a target to a false alarm for its one report (loneTargetLikely).
    if (!isLive(track) || track.isOneReport()) continue;
    const TrackState& last = track.lastState();
    const TrackState next = motion_.predict(last, newest_tick_ + 1 - last.tick);
    out.push_back({track.id, {next.x, next.y}});
  }
  return out;
}

common::TrackHandoff McmcdaEngine::release(common::TrackId id, std::uint32_t to_supernode) {
  const auto it = std::lower_bound(tracks_.begin(), tracks_.end(), id,
                                   [](const LiveTrack& t, common::TrackId value) { return t.id < value; });
  if (it == tracks_.end() || it->id != id)
    throw std::invalid_argument("mcmcda: release of unknown track " + std::to_string(id));
  const TrackState s = motion_.predict(it->lastState(), newest_tick_ - it->lastState().tick);
  common::TrackHandoff h;
  h.track = id;
  h.to_supernode = to_supernode;
  h.last_tick = newest_tick_;
  h.state = {s.x, s.y, s.vx, s.vy};
  h.covariance = fullCovariance(s.cov);
  h.hits = it->totalObservations();
  h.misses = newest_tick_ - it->lastSeenTick();
  h.confirmed = it->totalObservations() >= params_.confirm_observations;
  for (const auto& key : it->observations) released_.insert(std::upper_bound(released_.begin(), released_.end(), key), key);
  tracks_.erase(it);
  return h;
}

}  // namespace wsn::supernode::mcmcda

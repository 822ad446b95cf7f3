// One MCMCDA data-association problem (Oh et al., §III-B and eq. 3): the observations of a
// window, their candidate-successor neighbourhoods and the per-track log-posterior terms.
// Pure and immutable once built; the sampler (sampler.hpp) moves over partitions of it.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/sensor_coverage.hpp"

namespace wsn::supernode::mcmcda {

/// The model of eq. (3) and eq. (8) as the sampler sees it.
struct ModelParams {
  double detection_probability = 0.7;     ///< pd: a live target's report reaches the window at a tick
  double termination_probability = 0.02;  ///< pz: a target disappears at a tick
  double birth_density = 1e-5;            ///< lambda_b: new targets per unit area per tick
  double false_alarm_density = 6e-4;      ///< lambda_f: false reports per unit area per tick
  double measurement_sigma = 0.2;         ///< r: R = r^2 I for a fused observation
  double process_noise_sigma = 0.15;      ///< q of eq. (8)
  double delta = 1.0;                     ///< sampling interval of eq. (8)
  double initial_velocity_sigma = 1.5;    ///< prior std. deviation of a new track's velocity per axis
  double max_speed = 3.0;                 ///< v-bar: distance per tick a target can cover
  std::int32_t max_gap = 5;               ///< d-bar: largest tick gap between consecutive observations
  double stop_probability = 0.1;          ///< gamma: the extension proposal stops after a step
};

/// The filter state of one axis of eq. (8) — position and velocity — with a covariance shared by
/// both axes. R = r^2 I, Q and the prior are axis-symmetric, so the 4-state filter splits into two
/// 2-state filters with the same covariance; this is exact, not an approximation.
struct AxisCovariance {
  double pp = 0.0;
  double pv = 0.0;
  double vv = 0.0;
};

/// A track's filtered state at `tick`.
struct TrackState {
  std::int32_t tick = 0;
  double x = 0.0;
  double y = 0.0;
  double vx = 0.0;
  double vy = 0.0;
  AxisCovariance cov;
};

/// Eq. (8) on one track, axis by axis: prediction across a gap of ticks (exact: F^d and the
/// noise d single steps accumulate, tabulated up to d-bar), the prior of a new track, and the
/// measurement update with its log-likelihood.
class MotionModel {
 public:
  explicit MotionModel(const ModelParams& params);

  /// `state` predicted `gap` ticks ahead (gap <= 0: unchanged).
  TrackState predict(const TrackState& state, std::int32_t gap) const;
  /// The prior of a new track at an observation (x, y) at `tick`: position variance r^2,
  /// velocity 0 with variance sigma_v^2.
  TrackState initialState(std::int32_t tick, double x, double y) const;
  /// Measurement update of a predicted state with z = (x, y), R = r^2 I; returns log N(nu; 0, S I).
  double correct(TrackState& state, double x, double y) const;

 private:
  struct GapModel {
    double dt = 0.0;
    AxisCovariance q;  // exact eq. (8) process noise accumulated over the gap
  };
  ModelParams params_;
  std::vector<GapModel> gaps_;  // index = gap in ticks, 0 .. d-bar
  double log_two_pi_ = 0.0;
};

/// An observation of the problem. An *anchor* is not a report but the summary of a track's past
/// (its state at `tick`, from before the window or from a neighbouring supernode): it can only be
/// the first element of a track, and a track that starts at it is a continuation, not a birth.
struct ProblemObservation {
  std::int32_t tick = 0;
  double x = 0.0;
  double y = 0.0;
  bool anchor = false;
  TrackState prior;  ///< anchors only: the track's state at `tick`
};

/// Where `state` puts its target at `tick` (constant velocity over ticks of `delta`): the position
/// at which a coasting track's misses are weighed.
inline common::Vec2 predictedPosition(const TrackState& state, std::int32_t tick, double delta) {
  const double ahead = (tick - state.tick) * delta;
  return {state.x + ahead * state.vx, state.y + ahead * state.vy};
}

/// What a target last observed at tick `last` may have done over last + 1 .. `newest` without an
/// observation: ended at some tick j (after living on unseen until then), or lived on unseen to
/// `newest`; each tick it ends with pz or lives on unseen with (1 - pz)(1 - pd_at(j)). Ends at or
/// before `split` and after it are kept apart (the target is there at `split` in the second).
struct Silence {
  double ended_by_split = 0.0;
  double ended_after_split = 0.0;
  double alive = 1.0;  ///< there, unseen, at `newest`
  double thereAtSplit() const { return alive + ended_after_split; }
  double total() const { return thereAtSplit() + ended_by_split; }
};
template <class DetectionAt>
Silence silenceAfter(std::int32_t last, std::int32_t newest, std::int32_t split, double pz, DetectionAt pd_at) {
  Silence s;
  for (std::int32_t j = last + 1; j <= newest; ++j) {
    (j > split ? s.ended_after_split : s.ended_by_split) += s.alive * pz;
    s.alive *= (1.0 - pz) * (1.0 - pd_at(j));
  }
  return s;
}

/// Sum_{b <= tick} of r^(tick - b), r = (1 - pz)(1 - pd): how many more ways a target whose first
/// report is of `tick` came to be than eq. (3)'s "born at its first report" counts. It was born at
/// some tick b from the run's first (tick 1) on and went unseen, and on, until `tick`; at pd near 1
/// this is 1, under heavy loss up to 1 / (1 - r).
double unseenBirthWeight(const ModelParams& params, std::int32_t tick);

class Problem {
 public:
  /// `observations` must be sorted by tick; `last_tick` is T of eq. (3) (the newest tick of the
  /// window). Where the sensors' coverage is known, `share` (which must outlive the problem) shares
  /// pd out over the field for the silence after a track's last element; null means pd everywhere.
  /// Throws std::invalid_argument on unsorted input or parameters out of range.
  Problem(const ModelParams& params, std::vector<ProblemObservation> observations, std::int32_t last_tick,
          const common::DetectionShare* share = nullptr);

  const ModelParams& params() const { return params_; }
  std::int32_t size() const { return static_cast<std::int32_t>(observations_.size()); }
  const ProblemObservation& observation(std::int32_t i) const { return observations_[static_cast<std::size_t>(i)]; }
  std::int32_t tick(std::int32_t i) const { return observations_[static_cast<std::size_t>(i)].tick; }
  bool isAnchor(std::int32_t i) const { return observations_[static_cast<std::size_t>(i)].anchor; }
  std::int32_t lastTick() const { return last_tick_; }
  /// The first element of lastTick() (elements are sorted by tick, so the newest are last);
  /// size() when the newest tick has none.
  std::int32_t newestBegin() const {
    std::int32_t begin = size();
    while (begin > 0 && tick(begin - 1) == last_tick_) --begin;
    return begin;
  }

  /// True when j may directly follow i in a track: 1 <= t_j - t_i <= d-bar, |y_j - y_i| <=
  /// v-bar (t_j - t_i), and j is not an anchor.
  /// (Inline, with the lists below: the sampler's inner loops live on them.)
  bool linked(std::int32_t i, std::int32_t j) const {
    const auto& a = observations_[static_cast<std::size_t>(i)];
    const auto& b = observations_[static_cast<std::size_t>(j)];
    const std::int32_t gap = b.tick - a.tick;
    if (b.anchor || gap < 1 || gap > params_.max_gap) return false;
    return withinReach(b.x - a.x, b.y - a.y, params_.max_speed * gap);
  }
  /// The distance test of linked(): an offset (dx, dy) within `reach`.
  static bool withinReach(double dx, double dy, double reach) { return dx * dx + dy * dy <= reach * reach; }
  /// Candidate successors of i at gap d (1 <= d <= d-bar), in index order.
  std::span<const std::int32_t> successors(std::int32_t i, std::int32_t gap) const {
    const std::size_t k = static_cast<std::size_t>(i * params_.max_gap + gap);
    return range(succ_, succ_start_[k - 1], succ_start_[k]);
  }
  /// All candidate successors of i, gap by gap.
  std::span<const std::int32_t> successors(std::int32_t i) const {
    return range(succ_, succ_start_[static_cast<std::size_t>(i * params_.max_gap)],
                 succ_start_[static_cast<std::size_t>((i + 1) * params_.max_gap)]);
  }

  /// log pi contribution of a track relative to leaving its observations unassigned: eq. (3)'s
  /// prior terms and Kalman likelihood for the track minus the terms of its observations left out
  /// of every track (unassignedLogDensity; for an anchor, its target's silence since its tick).
  /// log pi(omega) = sum over tracks + const. `track` lists observation indices in tick order and
  /// must be a valid track. When `final_state` is given, it receives the filtered state at the
  /// last observation.
  ///
  /// Eq. (3) as Oh et al. write it dates a target's birth at its first report and its end right
  /// after its last (p_z). Both ticks are unobserved, and under heavy loss a live target is unseen
  /// most ticks, so each is summed over: the birth over the ticks before the first report
  /// (unseenBirthWeight), the end over the ticks after the last, or none (the silence, which sums
  /// "ended at tick k" and "still there at T").
  double trackScore(std::span<const std::int32_t> track, TrackState* final_state = nullptr) const;

  /// log of what an observation left out of every track stands for, per unit area: a false alarm
  /// (lambda_f), or the only report of a target in the window — born unseen before it, detected,
  /// and silent since: lambda_b x unseenBirthWeight x pd x silence(T - tick). Without the second,
  /// the chain weighed joining two targets' lone reports into one track against two false alarms,
  /// not against two targets. Anchors: 0.
  double unassignedLogDensity(std::int32_t i) const { return log_unassigned_[static_cast<std::size_t>(i)]; }
  /// The chance that a target last observed at tick `last` gives no observation in last + 1 .. T,
  /// having ended at one of those ticks or not at all (silenceAfter), with each tick's pd the one at
  /// the position `state` (its filtered state at `last`) predicts then (the model's pd without
  /// coverage).
  double silence(std::int32_t last, const TrackState& state) const;

  /// The filtered state of `track` at each of its elements (tick order) into `states`.
  void filterTrack(std::span<const std::int32_t> track, std::vector<TrackState>& states) const;

  const MotionModel& motion() const { return motion_; }

 private:
  /// Runs the filter along `track` from its first element's prior; returns the summed
  /// log-likelihood of the later elements and, when given, the states after each element.
  double filter(std::span<const std::int32_t> track, std::vector<TrackState>* states, TrackState* last) const;
  static std::span<const std::int32_t> range(const std::vector<std::int32_t>& v, std::int32_t begin, std::int32_t end) {
    return {v.data() + begin, static_cast<std::size_t>(end - begin)};
  }

  ModelParams params_;
  std::vector<ProblemObservation> observations_;
  std::int32_t last_tick_;
  void buildSuccessors();
  // Candidate lists in CSR form: successors of i at gap d are
  // succ_[succ_start_[i * dbar + d - 1] .. succ_start_[i * dbar + d]).
  std::vector<std::int32_t> succ_start_;
  std::vector<std::int32_t> succ_;
  MotionModel motion_;
  // Constant log terms of eq. (3).
  double log_pd_ = 0.0;
  double log_miss_ = 0.0;
  double log_continue_ = 0.0;
  const common::DetectionShare* share_ = nullptr;  ///< null: pd is the same everywhere
  std::vector<double> log_silence_;     ///< log silence by T - last, with pd the same everywhere
  std::vector<double> log_birth_at_;    ///< per element: log lambda_b B(tick), a track born there
  std::vector<double> log_unassigned_;  ///< per element: unassignedLogDensity
  double logSilence(std::int32_t last, const TrackState& state) const {
    if (share_ == nullptr) return log_silence_[static_cast<std::size_t>(last_tick_ - last)];
    return std::log(silence(last, state));
  }
};

}  // namespace wsn::supernode::mcmcda

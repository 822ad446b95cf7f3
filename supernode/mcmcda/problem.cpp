#include "supernode/mcmcda/problem.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace wsn::supernode::mcmcda {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("mcmcda problem: " + what);
}

/// One tick of eq. (8) on one axis: F = [1 d; 0 1], Q = q^2 G G^T with G = [d^2/2; d].
AxisCovariance stepCovariance(const AxisCovariance& c, double d, double q2) {
  AxisCovariance out;
  out.pp = c.pp + 2.0 * d * c.pv + d * d * c.vv + q2 * d * d * d * d / 4.0;
  out.pv = c.pv + d * c.vv + q2 * d * d * d / 2.0;
  out.vv = c.vv + q2 * d * d;
  return out;
}

/// Measurement update of a predicted state with z = (zx, zy), R = r2 I, per axis (the axes share
/// S = P_pp + r^2). Returns log N(nu; 0, S I) + ln 2 pi, i.e. -(ln S + |nu|^2 / (2 S)).
double correct(TrackState& s, double zx, double zy, double r2) {
  const double S = s.cov.pp + r2;
  const double nux = zx - s.x;
  const double nuy = zy - s.y;
  const double kp = s.cov.pp / S;
  const double kv = s.cov.pv / S;
  s.x += kp * nux;
  s.y += kp * nuy;
  s.vx += kv * nux;
  s.vy += kv * nuy;
  const AxisCovariance c = s.cov;
  s.cov.pp = c.pp - kp * c.pp;
  s.cov.pv = c.pv - kp * c.pv;
  s.cov.vv = c.vv - kv * c.pv;
  return -(std::log(S) + 0.5 * (nux * nux + nuy * nuy) / S);
}

}  // namespace

Problem::Problem(const ModelParams& params, std::vector<ProblemObservation> observations, std::int32_t last_tick)
    : params_(params), observations_(std::move(observations)), last_tick_(last_tick) {
  const auto& p = params_;
  require(p.detection_probability > 0.0 && p.detection_probability < 1.0, "detection probability must be in (0, 1)");
  require(p.termination_probability > 0.0 && p.termination_probability < 1.0,
          "termination probability must be in (0, 1)");
  require(p.birth_density > 0.0 && p.false_alarm_density > 0.0, "birth and false-alarm densities must be > 0");
  require(p.measurement_sigma > 0.0 && p.process_noise_sigma >= 0.0 && p.delta > 0.0 &&
              p.initial_velocity_sigma > 0.0,
          "sigmas and delta must be positive");
  require(p.max_speed > 0.0 && p.max_gap >= 1, "max speed must be > 0 and max gap >= 1");
  require(p.stop_probability > 0.0 && p.stop_probability < 1.0, "stop probability must be in (0, 1)");
  for (std::size_t i = 1; i < observations_.size(); ++i)
    require(observations_[i - 1].tick <= observations_[i].tick, "observations must be sorted by tick");

  log_pd_ = std::log(p.detection_probability);
  log_miss_ = std::log1p(-p.detection_probability);
  log_continue_ = std::log1p(-p.termination_probability);
  log_terminate_ = std::log(p.termination_probability);
  log_birth_ = std::log(p.birth_density);
  log_false_alarm_ = std::log(p.false_alarm_density);
  log_two_pi_ = std::log(2.0 * std::numbers::pi);

  const double q2 = p.process_noise_sigma * p.process_noise_sigma;
  gaps_.resize(static_cast<std::size_t>(p.max_gap) + 1);
  for (std::int32_t g = 1; g <= p.max_gap; ++g) {
    // Q over g ticks = sum_i F^i Q1 F^iT: the covariance g single steps add to a zero prior.
    AxisCovariance acc;
    for (std::int32_t s = 0; s < g; ++s) acc = stepCovariance(acc, p.delta, q2);
    gaps_[static_cast<std::size_t>(g)] = GapModel{g * p.delta, acc};
  }

  // Candidate successors (Oh: an observation at t + d within d * v-bar of one at t, d <= d-bar),
  // built once per problem so that no move searches for them.
  const std::int32_t n = size();
  const std::int32_t dbar = p.max_gap;
  succ_start_.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(dbar) + 1, 0);
  std::vector<std::int32_t> pred_count(static_cast<std::size_t>(n) + 1, 0);
  std::int32_t first_later = 0;  // first index with a tick > tick(i)
  for (std::int32_t i = 0; i < n; ++i) {
    while (first_later < n && tick(first_later) <= tick(i)) ++first_later;
    for (std::int32_t d = 1; d <= dbar; ++d) {
      for (std::int32_t j = first_later; j < n && tick(j) <= tick(i) + d; ++j)
        if (tick(j) == tick(i) + d && linked(i, j)) {
          succ_.push_back(j);
          ++pred_count[static_cast<std::size_t>(j) + 1];
        }
      succ_start_[static_cast<std::size_t>(i * dbar + d)] = static_cast<std::int32_t>(succ_.size());
    }
  }
  for (std::int32_t j = 0; j < n; ++j) pred_count[static_cast<std::size_t>(j) + 1] += pred_count[static_cast<std::size_t>(j)];
  pred_start_ = pred_count;
  pred_.assign(succ_.size(), 0);
  std::vector<std::int32_t> fill(pred_start_.begin(), pred_start_.end() - 1);
  for (std::int32_t i = 0; i < n; ++i)
    for (const std::int32_t j : successors(i)) pred_[static_cast<std::size_t>(fill[static_cast<std::size_t>(j)]++)] = i;
}

TrackState Problem::initialState(std::int32_t i) const {
  const auto& o = observation(i);
  TrackState s;
  s.tick = o.tick;
  s.x = o.x;
  s.y = o.y;
  s.cov.pp = params_.measurement_sigma * params_.measurement_sigma;
  s.cov.vv = params_.initial_velocity_sigma * params_.initial_velocity_sigma;
  return s;
}

TrackState Problem::predict(const TrackState& state, std::int32_t gap) const {
  TrackState out = state;
  out.tick = state.tick + gap;
  if (gap <= 0) return out;
  if (gap <= params_.max_gap) {
    const GapModel& g = gapModel(gap);
    const double d = g.dt;
    out.x += d * state.vx;
    out.y += d * state.vy;
    const AxisCovariance& c = state.cov;
    out.cov.pp = c.pp + 2.0 * d * c.pv + d * d * c.vv + g.q.pp;
    out.cov.pv = c.pv + d * c.vv + g.q.pv;
    out.cov.vv = c.vv + g.q.vv;
    return out;
  }
  const double q2 = params_.process_noise_sigma * params_.process_noise_sigma;
  for (std::int32_t s = 0; s < gap; ++s) {
    out.x += params_.delta * out.vx;
    out.y += params_.delta * out.vy;
    out.cov = stepCovariance(out.cov, params_.delta, q2);
  }
  return out;
}

double Problem::trackScore(std::span<const std::int32_t> track, TrackState* final_state) const {
  const std::int32_t n = static_cast<std::int32_t>(track.size());
  const std::int32_t first = track.front();
  const bool anchored = isAnchor(first);
  TrackState s = anchored ? observation(first).prior : initialState(first);
  const double r2 = params_.measurement_sigma * params_.measurement_sigma;

  // Kalman likelihood from the second element on (eq. 8): sum log N(nu; 0, S), S = (P_pp + r^2) I.
  double log_likelihood = 0.0;
  for (std::int32_t k = 1; k < n; ++k) {
    const auto& o = observation(track[static_cast<std::size_t>(k)]);
    s = predict(s, o.tick - s.tick);
    log_likelihood += correct(s, o.x, o.y, r2) - log_two_pi_;
  }
  if (final_state != nullptr) *final_state = s;

  // Eq. (3)'s prior terms for this track. A birth brings lambda_b (the uniform density of the
  // birth position is inside it, as 1/V is inside lambda_f for a false alarm); an anchor is a
  // continuing target and brings no birth term, but leaving it unassigned would have meant "ended
  // at once" (p_z), which this track replaces.
  const std::int32_t t_start = observation(first).tick;
  const std::int32_t t_end = observation(track.back()).tick;
  const std::int32_t detections = anchored ? n - 1 : n;
  const std::int32_t alive_ticks = anchored ? t_end - t_start : t_end - t_start + 1;
  double prior = (t_end - t_start) * log_continue_ + detections * log_pd_ + (alive_ticks - detections) * log_miss_;
  if (t_end < last_tick_) prior += log_terminate_;
  if (anchored) {
    if (t_start < last_tick_) prior -= log_terminate_;
  } else {
    prior += log_birth_;
  }
  return prior + log_likelihood - detections * log_false_alarm_;
}

void Problem::filterTrack(std::span<const std::int32_t> track, std::vector<TrackState>& states) const {
  states.clear();
  const std::int32_t first = track.front();
  TrackState s = isAnchor(first) ? observation(first).prior : initialState(first);
  states.push_back(s);
  const double r2 = params_.measurement_sigma * params_.measurement_sigma;
  for (std::size_t k = 1; k < track.size(); ++k) {
    const auto& o = observation(track[k]);
    s = predict(s, o.tick - s.tick);
    correct(s, o.x, o.y, r2);
    states.push_back(s);
  }
}

}  // namespace wsn::supernode::mcmcda

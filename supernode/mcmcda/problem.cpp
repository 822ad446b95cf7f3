#include "supernode/mcmcda/problem.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

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

}  // namespace

MotionModel::MotionModel(const ModelParams& params) : params_(params), log_two_pi_(std::log(2.0 * std::numbers::pi)) {
  const double q2 = params.process_noise_sigma * params.process_noise_sigma;
  gaps_.resize(static_cast<std::size_t>(std::max(params.max_gap, 0)) + 1);
  for (std::int32_t g = 1; g <= params.max_gap; ++g) {
    // Q over g ticks = sum_i F^i Q1 F^iT: the covariance g single steps add to a zero prior.
    AxisCovariance acc;
    for (std::int32_t s = 0; s < g; ++s) acc = stepCovariance(acc, params.delta, q2);
    gaps_[static_cast<std::size_t>(g)] = GapModel{g * params.delta, acc};
  }
}

TrackState MotionModel::initialState(std::int32_t tick, double x, double y) const {
  TrackState s;
  s.tick = tick;
  s.x = x;
  s.y = y;
  s.cov.pp = params_.measurement_sigma * params_.measurement_sigma;
  s.cov.vv = params_.initial_velocity_sigma * params_.initial_velocity_sigma;
  return s;
}

TrackState MotionModel::predict(const TrackState& state, std::int32_t gap) const {
  TrackState out = state;
  out.tick = state.tick + gap;
  if (gap <= 0) return out;
  if (gap < static_cast<std::int32_t>(gaps_.size())) {
    const GapModel& g = gaps_[static_cast<std::size_t>(gap)];
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

double MotionModel::correct(TrackState& s, double zx, double zy) const {
  // Per axis with a shared S = P_pp + r^2: log N(nu; 0, S I) = -ln 2 pi - ln S - |nu|^2 / (2 S).
  const double S = s.cov.pp + params_.measurement_sigma * params_.measurement_sigma;
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
  return -(log_two_pi_ + std::log(S) + 0.5 * (nux * nux + nuy * nuy) / S);
}

double unseenBirthWeight(const ModelParams& params, std::int32_t tick) {
  const double r = (1.0 - params.termination_probability) * (1.0 - params.detection_probability);
  return (1.0 - std::pow(r, std::max(tick, 1))) / (1.0 - r);
}

Problem::Problem(const ModelParams& params, std::vector<ProblemObservation> observations, std::int32_t last_tick,
                 const common::DetectionShare* share)
    : params_(params), observations_(std::move(observations)), last_tick_(last_tick), motion_(params), share_(share) {
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
  require(observations_.empty() || observations_.back().tick <= last_tick_,
          "observations must not be after the last tick");
  if (share_ != nullptr && share_->uniform()) share_ = nullptr;

  log_pd_ = std::log(p.detection_probability);
  log_miss_ = std::log1p(-p.detection_probability);
  log_continue_ = std::log1p(-p.termination_probability);
  // The silence after every tick an element (an anchor too) can hold, with the model's one pd.
  const std::int32_t oldest = observations_.empty() ? last_tick_ : std::min(last_tick_, observations_.front().tick);
  const auto everywhere = [&](std::int32_t) { return p.detection_probability; };
  log_silence_.resize(static_cast<std::size_t>(last_tick_ - oldest) + 1);
  for (std::size_t k = 0; k < log_silence_.size(); ++k) {
    const std::int32_t last = last_tick_ - static_cast<std::int32_t>(k);
    const Silence quiet = silenceAfter(last, last_tick_, last_tick_, p.termination_probability, everywhere);
    log_silence_[k] = std::log(quiet.total());
  }
  // Per element: a track born there, and the element left out of every track. A lone report's
  // target: its heading is unknown, so its silence is judged with the field's pd.
  log_birth_at_.assign(observations_.size(), 0.0);
  log_unassigned_.assign(observations_.size(), 0.0);
  for (std::size_t i = 0; i < observations_.size(); ++i) {
    const auto& o = observations_[i];
    if (o.anchor) continue;
    const double born = p.birth_density * unseenBirthWeight(p, o.tick);
    log_birth_at_[i] = std::log(born);
    const double lone_target =
        born * p.detection_probability * std::exp(log_silence_[static_cast<std::size_t>(last_tick_ - o.tick)]);
    log_unassigned_[i] = std::log(p.false_alarm_density + lone_target);
  }

  buildSuccessors();
}

void Problem::buildSuccessors() {
  // Candidate successors (Oh: an observation at t + d within d * v-bar of one at t, d <= d-bar),
  // built once per problem so that no move searches for them. Each tick's observations are binned
  // into vertical bands of width d-bar * v-bar (the farthest reach) and sorted by y within a band,
  // so the candidates of i at t + d are found in the two or three bands that |x - x_i| <= d * v-bar
  // touches, by a binary search for |y - y_i| <= d * v-bar, instead of a scan of the whole tick:
  // the aggregator's window over a city holds thousands of elements per tick, of which a handful
  // are in reach (at 10^6 sensors an x strip alone held 16 times the candidates it linked).
  const std::int32_t n = size();
  const std::int32_t dbar = params_.max_gap;
  succ_start_.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(dbar) + 1, 0);
  if (n == 0) return;
  const std::int32_t first_tick = tick(0);
  const auto span = static_cast<std::size_t>(tick(n - 1) - first_tick) + 1;
  double x_min = observation(0).x;
  double x_max = x_min;
  for (const auto& o : observations_) {
    x_min = std::min(x_min, o.x);
    x_max = std::max(x_max, o.x);
  }
  // At most kMaxBands bands, however small v-bar is against the spread of the observations.
  constexpr double kMaxBands = 4096.0;
  const double width = std::max({params_.max_speed * dbar, (x_max - x_min) / kMaxBands, 1e-9});
  const auto band_of = [&](double x) {
    const double band = std::floor((x - x_min) / width);
    return std::isfinite(band) ? static_cast<std::int32_t>(std::clamp(band, 0.0, kMaxBands)) : 0;
  };
  const std::int32_t bands = band_of(x_max) + 1;
  // Each entry carries what the link test reads, so the search stays in this array.
  struct Entry {
    std::int32_t band;
    double y;
    std::int32_t index;
    double x;
    bool anchor;
  };
  std::vector<Entry> entries;  // by tick, then band, then y
  entries.reserve(static_cast<std::size_t>(n));
  for (std::int32_t j = 0; j < n; ++j) {
    const auto& o = observation(j);
    entries.push_back({band_of(o.x), o.y, j, o.x, o.anchor});
  }
  // Indices ascend with tick, so sorting each tick's run keeps the ticks in order.
  std::vector<std::size_t> tick_begin(span + 1, 0);
  for (std::int32_t j = 0; j < n; ++j) ++tick_begin[static_cast<std::size_t>(tick(j) - first_tick) + 1];
  for (std::size_t t = 0; t < span; ++t) tick_begin[t + 1] += tick_begin[t];
  // band_begin[t * (bands + 1) + b]: the first entry of band b at tick t.
  std::vector<std::size_t> band_begin(span * static_cast<std::size_t>(bands + 1), 0);
  for (std::size_t t = 0; t < span; ++t) {
    const auto first = entries.begin() + static_cast<std::ptrdiff_t>(tick_begin[t]);
    const auto last = entries.begin() + static_cast<std::ptrdiff_t>(tick_begin[t + 1]);
    std::sort(first, last, [](const Entry& a, const Entry& b) { return std::tie(a.band, a.y, a.index) < std::tie(b.band, b.y, b.index); });
    std::size_t at = tick_begin[t];
    for (std::int32_t b = 0; b <= bands; ++b) {
      while (at < tick_begin[t + 1] && entries[at].band < b) ++at;
      band_begin[t * static_cast<std::size_t>(bands + 1) + static_cast<std::size_t>(b)] = at;
    }
  }
  succ_.reserve(static_cast<std::size_t>(n) * 4);
  std::vector<std::int32_t> found;
  for (std::int32_t i = 0; i < n; ++i) {
    const auto& o = observation(i);
    for (std::int32_t d = 1; d <= dbar; ++d) {
      const auto t = static_cast<std::size_t>(tick(i) + d - first_tick);
      if (t < span) {
        const double reach = params_.max_speed * d;
        found.clear();
        for (std::int32_t b = band_of(o.x - reach); b <= std::min(bands - 1, band_of(o.x + reach)); ++b) {
          const std::size_t row = t * static_cast<std::size_t>(bands + 1) + static_cast<std::size_t>(b);
          const auto end = entries.begin() + static_cast<std::ptrdiff_t>(band_begin[row + 1]);
          auto it = std::lower_bound(entries.begin() + static_cast<std::ptrdiff_t>(band_begin[row]), end, o.y - reach,
                                     [](const Entry& e, double y) { return e.y < y; });
          // linked(i, j) with the gap known to be d: not an anchor, within d * v-bar.
          for (; it != end && it->y <= o.y + reach; ++it)
            if (!it->anchor && withinReach(it->x - o.x, it->y - o.y, reach)) found.push_back(it->index);
        }
        std::sort(found.begin(), found.end());  // index order, as the moves expect
        succ_.insert(succ_.end(), found.begin(), found.end());
      }
      succ_start_[static_cast<std::size_t>(i * dbar + d)] = static_cast<std::int32_t>(succ_.size());
    }
  }
}

double Problem::filter(std::span<const std::int32_t> track, std::vector<TrackState>* states,
                       TrackState* last) const {
  const auto& head = observation(track.front());
  TrackState s = head.anchor ? head.prior : motion_.initialState(head.tick, head.x, head.y);
  if (states != nullptr) {
    states->clear();
    states->push_back(s);
  }
  double log_likelihood = 0.0;
  for (std::size_t k = 1; k < track.size(); ++k) {
    const auto& o = observation(track[k]);
    s = motion_.predict(s, o.tick - s.tick);
    log_likelihood += motion_.correct(s, o.x, o.y);
    if (states != nullptr) states->push_back(s);
  }
  if (last != nullptr) *last = s;
  return log_likelihood;
}

double Problem::trackScore(std::span<const std::int32_t> track, TrackState* final_state) const {
  const std::int32_t n = static_cast<std::int32_t>(track.size());
  const std::int32_t first = track.front();
  const bool anchored = isAnchor(first);
  // Kalman likelihood from the second element on (eq. 8): sum log N(nu; 0, S), S = (P_pp + r^2) I.
  TrackState last;
  const double log_likelihood = filter(track, nullptr, &last);
  if (final_state != nullptr) *final_state = last;

  // Eq. (3)'s prior terms for this track. A birth brings lambda_b (the uniform density of the
  // birth position is inside it, as 1/V is inside lambda_f for a false alarm), at any tick its
  // target went unseen before its first report; an anchor is a continuing target and brings no
  // birth term, but left unassigned it would have meant its target's silence since its tick,
  // which this track replaces. After the last element, the silence to T.
  const std::int32_t t_start = observation(first).tick;
  const std::int32_t t_end = observation(track.back()).tick;
  const std::int32_t detections = anchored ? n - 1 : n;
  const std::int32_t alive_ticks = anchored ? t_end - t_start : t_end - t_start + 1;
  double prior = (t_end - t_start) * log_continue_ + detections * log_pd_ + (alive_ticks - detections) * log_miss_;
  prior += logSilence(t_end, last);
  if (anchored) {
    prior -= logSilence(t_start, observation(first).prior);
  } else {
    prior += log_birth_at_[static_cast<std::size_t>(first)];
  }
  double unassigned = 0.0;
  for (const auto i : track) unassigned += log_unassigned_[static_cast<std::size_t>(i)];
  return prior + log_likelihood - unassigned;
}

double Problem::silence(std::int32_t last, const TrackState& state) const {
  const double pd = params_.detection_probability;
  const auto at_path = [&](std::int32_t tick) {
    return share_ == nullptr ? pd : std::min(1.0, pd * share_->at(predictedPosition(state, tick, params_.delta)));
  };
  return silenceAfter(last, last_tick_, last_tick_, params_.termination_probability, at_path).total();
}

void Problem::filterTrack(std::span<const std::int32_t> track, std::vector<TrackState>& states) const {
  filter(track, &states, nullptr);
}

}  // namespace wsn::supernode::mcmcda

#include "node/adman/adman.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/rng.hpp"

namespace wsn::node::adman {
namespace {

constexpr double kFloorDb = -300.0;
constexpr double kFloorLinear = 1e-30;  // 10^(kFloorDb / 10)
/// Particle streams per tick: one per factorised sweep (1..kMaxSweeps) and one for the joint search.
constexpr std::int64_t kStreamsPerTick = 16;
constexpr std::int32_t kJointStream = 15;
static_assert(kMaxSweeps < kJointStream, "a factorised sweep's stream must not be the joint search's");

/// Slack on the grid-neighbour radii, so that a grid's rounding never drops a neighbour.
constexpr double kNeighbourSlack = 1.01;

/// A bucket grid over the view's positions, for "every reading within r of p" queries.
class ViewIndex {
 public:
  ViewIndex(std::span<const Reading> view, double cell) : view_(view), cell_(cell) {
    for (std::size_t i = 0; i < view.size(); ++i) buckets_[key(view[i].at)].push_back(i);
  }
  /// Indices (ascending) of the readings within `radius` of p, inclusive.
  std::vector<std::size_t> within(common::Vec2 p, double radius) const {
    std::vector<std::size_t> out;
    const auto [cx0, cy0] = key({p.x - radius, p.y - radius});
    const auto [cx1, cy1] = key({p.x + radius, p.y + radius});
    const double r2 = radius * radius;
    for (std::int64_t cx = cx0; cx <= cx1; ++cx)
      for (std::int64_t cy = cy0; cy <= cy1; ++cy) {
        const auto it = buckets_.find({cx, cy});
        if (it == buckets_.end()) continue;
        for (const std::size_t i : it->second)
          if (common::squaredDistance(view_[i].at, p) <= r2) out.push_back(i);
      }
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  std::pair<std::int64_t, std::int64_t> key(common::Vec2 p) const {
    return {static_cast<std::int64_t>(std::floor(p.x / cell_)), static_cast<std::int64_t>(std::floor(p.y / cell_))};
  }
  std::span<const Reading> view_;
  double cell_;
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::size_t>> buckets_;
};

/// Where a sensor of `view` is, by id (the view is sorted by id).
std::size_t indexOf(std::span<const Reading> view, common::SensorId sensor) {
  const auto it = std::lower_bound(view.begin(), view.end(), sensor,
                                   [](const Reading& r, common::SensorId id) { return r.sensor < id; });
  if (it == view.end() || it->sensor != sensor)
    throw std::invalid_argument("adman: attachment at sensor " + std::to_string(sensor) + " has no reading in the view");
  return static_cast<std::size_t>(it - view.begin());
}

double samplingRadius(Kind kind, double inside_radius) {
  return kind == Kind::inside ? inside_radius : std::numbers::sqrt2 * inside_radius;
}

/// The variance per axis of a uniform disc's share per particle: P particles over pi R^2 leave each
/// a cell of area pi R^2 / P, whose uniform spread per axis is that area / 12.
double cloudResolution(Kind kind, const MlmcSettings& settings) {
  const double radius = samplingRadius(kind, settings.inside_radius);
  return std::numbers::pi * radius * radius / static_cast<double>(settings.particles) / 12.0;
}

common::Vec2 uniformInDisc(common::Stream& draw, common::Vec2 centre, double radius) {
  const double r = radius * std::sqrt(draw.uniform());
  const double phi = 2.0 * std::numbers::pi * draw.uniform();
  return {centre.x + r * std::cos(phi), centre.y + r * std::sin(phi)};
}

/// The log-likelihood of a block whose sensors already receive `fixed` (linear) from the targets
/// held fixed, plus the moving targets `moving`.
double blockLogLikelihood(std::span<const Reading> view, std::span<const std::size_t> block,
                          std::span<const double> fixed, std::span<const common::Vec2> moving,
                          const PowerModel& model, double sigma_db) {
  double sum = 0.0;
  for (std::size_t b = 0; b < block.size(); ++b) {
    const Reading& reading = view[block[b]];
    double linear = fixed[b];
    for (const common::Vec2 l : moving) linear += model.linearAt(common::distance(reading.at, l));
    const double residual = reading.y - toDb(linear);
    sum += residual * residual;
  }
  return -sum / (2.0 * sigma_db * sigma_db);
}

/// The best of `candidates` (log-likelihoods `scores`) and the likelihood-weighted covariance of
/// component `k` of the candidates, floored at `resolution` (the variance per axis the particle
/// cloud cannot resolve: one particle often takes all the weight).
struct Best {
  std::size_t index = 0;
  double cov_xx = 0.0, cov_xy = 0.0, cov_yy = 0.0;
};
Best bestOf(const std::vector<std::vector<common::Vec2>>& candidates, const std::vector<double>& scores, std::size_t k,
            double resolution) {
  Best best;
  for (std::size_t i = 1; i < scores.size(); ++i)
    if (scores[i] > scores[best.index]) best.index = i;
  best.cov_xx = best.cov_yy = resolution;
  const double top = scores[best.index];
  if (!std::isfinite(top)) return best;  // no particle explains the readings: only the floor is known
  double w_sum = 0.0, mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < scores.size(); ++i) {
    const double w = std::exp(scores[i] - top);
    w_sum += w;
    mx += w * candidates[i][k].x;
    my += w * candidates[i][k].y;
  }
  mx /= w_sum;
  my /= w_sum;
  for (std::size_t i = 0; i < scores.size(); ++i) {
    const double w = std::exp(scores[i] - top) / w_sum;
    const double dx = candidates[i][k].x - mx;
    const double dy = candidates[i][k].y - my;
    best.cov_xx += w * dx * dx;
    best.cov_xy += w * dx * dy;
    best.cov_yy += w * dy * dy;
  }
  return best;
}

}  // namespace

double upperTail(double x) { return 0.5 * std::erfc(x / std::numbers::sqrt2); }

double upperTailInverse(double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("upperTailInverse: p must be in (0, 1)");
  // The refinement below subtracts Q(x) from p, which cancels when both are near 1; 1 - p is exact
  // for p >= 0.5, so the upper half goes through the symmetry Q^-1(p) = -Q^-1(1 - p).
  if (p > 0.5) return -upperTailInverse(1.0 - p);
  // Acklam's rational approximation of the normal quantile at 1 - p (relative error 1.15e-9),
  // then one Halley step on Q(x) - p, which brings it to machine precision.
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                 1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01,  -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                 3.754408661907416e+00};
  const double lower = 1.0 - p;  // the quantile of the lower tail
  double x = 0.0;
  if (lower < 0.02425) {
    const double q = std::sqrt(-2.0 * std::log(lower));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  } else if (lower <= 1.0 - 0.02425) {
    const double q = lower - 0.5;
    const double r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  } else {
    const double q = std::sqrt(-2.0 * std::log(p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }
  // Halley on f(x) = Q(x) - p, f' = -phi(x), f'' = x phi(x).
  const double e = upperTail(x) - p;
  const double u = -e * std::sqrt(2.0 * std::numbers::pi) * std::exp(x * x / 2.0);
  return x - u / (1.0 + x * u / 2.0);
}

double PowerModel::linearScale() const {
  return std::pow(10.0, power_db / 10.0) * std::pow(reference_distance, attenuation);
}

double PowerModel::linearAt(double distance) const {
  const double d = std::max(distance, 1e-9 * reference_distance);
  return linearScale() / (attenuation == 2.0 ? d * d : std::pow(d, attenuation));
}

double toDb(double linear) { return linear > kFloorLinear ? 10.0 * std::log10(linear) : kFloorDb; }

double receivedDb(const PowerModel& model, common::Vec2 sensor, std::span<const common::Vec2> targets) {
  double linear = 0.0;
  for (const common::Vec2 l : targets) linear += model.linearAt(common::distance(sensor, l));
  return toDb(linear);
}

Thresholds thresholds(const PowerModel& model, double inside_radius, double sigma_db, double false_alarm) {
  if (!(inside_radius > 0.0)) throw std::invalid_argument("adman thresholds: the inside radius r0 must be > 0");
  if (!(sigma_db >= 0.0)) throw std::invalid_argument("adman thresholds: the noise sigma must be >= 0");
  if (!(false_alarm > 0.0 && false_alarm < 1.0))
    throw std::invalid_argument("adman thresholds: the false-alarm probability must be in (0, 1)");
  Thresholds t;
  t.delta1 = toDb(model.linearAt(inside_radius));
  t.delta2 = toDb(model.linearAt(std::numbers::sqrt2 * inside_radius));
  const double margin = sigma_db * upperTailInverse(false_alarm);
  t.tau_inside = t.delta1 + margin;
  t.tau_between = t.delta2 + margin;
  return t;
}

double glrtLogRatio(double y, double delta, double sigma_db) {
  const double th3 = std::max(y, delta);
  const double th2 = std::min(y, delta);
  return (2.0 * th3 * y - 2.0 * th2 * y - th3 * th3 + th2 * th2) / (2.0 * sigma_db * sigma_db);
}

double detectionProbability(double theta, double tau, double sigma_db) {
  if (sigma_db == 0.0) return theta > tau ? 1.0 : 0.0;
  return upperTail((tau - theta) / sigma_db);
}

double Neighbourhood::n4() const { return kNeighbourSlack * pitch; }
double Neighbourhood::n8() const { return kNeighbourSlack * std::numbers::sqrt2 * pitch; }

std::vector<Attachment> attach(std::span<const Reading> view, const Thresholds& thresholds,
                               const Neighbourhood& neighbours) {
  const ViewIndex index(view, neighbours.n8());
  const auto inside = [&](std::size_t i) { return view[i].y > thresholds.tau_inside; };
  // An in-between reading next to (N4) an inside target is that target seen from its side; only
  // the others compete for an in-between target, so it cannot shadow a second target behind it.
  std::vector<bool> between(view.size(), false);
  for (std::size_t i = 0; i < view.size(); ++i) {
    if (!(view[i].y > thresholds.tau_between && view[i].y <= thresholds.tau_inside)) continue;
    between[i] = true;
    for (const std::size_t j : index.within(view[i].at, neighbours.n4()))
      if (j != i && inside(j)) between[i] = false;
  }
  std::vector<Attachment> out;
  for (std::size_t i = 0; i < view.size(); ++i) {
    if (inside(i)) {
      out.push_back({view[i].sensor, Kind::inside});
      continue;
    }
    if (!between[i]) continue;
    bool kept = true;
    for (const std::size_t j : index.within(view[i].at, neighbours.n8())) {
      // The strongest in-between reading of its N8 keeps the target; a tie goes to the lower id.
      if (j != i && between[j] &&
          (view[j].y > view[i].y || (view[j].y == view[i].y && view[j].sensor < view[i].sensor)))
        kept = false;
    }
    if (kept) out.push_back({view[i].sensor, Kind::between});
  }
  return out;
}

double logLikelihood(std::span<const Reading> view, std::span<const std::size_t> block,
                     std::span<const common::Vec2> targets, const PowerModel& model, double sigma_db) {
  const std::vector<double> none(block.size(), 0.0);
  return blockLogLikelihood(view, block, none, targets, model, sigma_db);
}

double viewReach(const MlmcSettings& settings) {
  const std::int32_t ranges = settings.joint ? 1 : std::max(0, settings.sweeps - 1);
  // The farthest target placed in sweep 1 reads the attachments within 2 n8() (whose block sensors
  // can be nearer to them), and their rules read n8() + n4() further.
  const double sweep_one = settings.joint ? settings.neighbours.n8() : 2.0 * settings.neighbours.n8();
  return ranges * settings.interaction_range + sweep_one + settings.neighbours.n8() + settings.neighbours.n4();
}

namespace {

/// One call of place(): the view and its attachments, with each attached sensor's block (the
/// view's readings within n8()) and others (the attached sensors within the interaction range)
/// found on demand and kept.
class Placer {
 public:
  Placer(std::span<const Reading> view, std::span<const Attachment> attachments, std::int32_t tick,
         const MlmcSettings& settings)
      : view_(view),
        attachments_(attachments),
        tick_(tick),
        settings_(settings),
        index_(view, settings.neighbours.n8()),
        sensor_at_(attachments.size()),
        blocks_(attachments.size()),
        others_(attachments.size()) {
    for (std::size_t a = 0; a < attachments.size(); ++a) sensor_at_[a] = view[indexOf(view, attachments[a].sensor)].at;
  }

  /// [A]'s eq. (15): P joint particles over the target and the targets around it.
  std::vector<Placement> joint(std::span<const std::size_t> attached) {
    std::vector<Placement> out;
    for (const std::size_t a : attached) {
      std::vector<std::size_t> group{a};
      for (const std::size_t b : others(a)) group.push_back(b);
      std::vector<std::size_t> block;
      for (const std::size_t g : group) {
        const auto& own = blockOf(g);
        block.insert(block.end(), own.begin(), own.end());
      }
      std::sort(block.begin(), block.end());
      block.erase(std::unique(block.begin(), block.end()), block.end());
      const std::vector<double> nothing(block.size(), 0.0);
      common::Stream draw(settings_.seed, common::Purpose::kMlmcParticles, attachments_[a].sensor,
                          streamKey(kJointStream));
      std::vector<std::vector<common::Vec2>> candidates(static_cast<std::size_t>(settings_.particles));
      std::vector<double> scores(candidates.size());
      for (std::size_t p = 0; p < candidates.size(); ++p) {
        for (const std::size_t g : group) candidates[p].push_back(drawAround(draw, g));
        scores[p] = blockLogLikelihood(view_, block, nothing, candidates[p], settings_.power, settings_.sigma_db);
      }
      out.push_back(best(a, candidates, scores));
    }
    return out;
  }

  /// Factorised: sweep s places each target on its own block with the others at sweep s - 1.
  std::vector<Placement> factorised(std::span<const std::size_t> attached) {
    const auto sweeps = static_cast<std::size_t>(settings_.sweeps);
    const std::vector<std::vector<bool>> needed = neededAtSweeps(attached);
    std::vector<Placement> previous(sensor_at_.size()), current(sensor_at_.size());
    for (std::size_t s = 1; s <= sweeps; ++s) {
      for (std::size_t a = 0; a < sensor_at_.size(); ++a)
        if (needed[s][a]) current[a] = placeAtSweep(a, static_cast<std::int32_t>(s), previous);
      std::swap(previous, current);
    }
    std::vector<Placement> out;
    for (const std::size_t a : attached) out.push_back(previous[a]);
    return out;
  }

 private:
  /// The targets each sweep needs (index 1..sweeps): the asked ones at the last, and the others of
  /// those a sweep earlier.
  std::vector<std::vector<bool>> neededAtSweeps(std::span<const std::size_t> attached) {
    const auto sweeps = static_cast<std::size_t>(settings_.sweeps);
    const std::size_t count = sensor_at_.size();
    std::vector<std::vector<bool>> needed(sweeps + 1, std::vector<bool>(count, false));
    for (const std::size_t a : attached) needed[sweeps][a] = true;
    for (std::size_t s = sweeps; s > 1; --s)
      for (std::size_t a = 0; a < count; ++a) {
        if (!needed[s][a]) continue;
        needed[s - 1][a] = true;  // its own last estimate is a candidate of sweep s
        for (const std::size_t b : others(a)) needed[s - 1][b] = true;
      }
    return needed;
  }

  /// Target a at sweep s, the others held at their estimates of sweep s - 1 (`previous`).
  Placement placeAtSweep(std::size_t a, std::int32_t s, const std::vector<Placement>& previous) {
    const std::vector<std::size_t> block = s == 1 ? ownShare(a) : blockOf(a);
    std::vector<double> fixed(block.size(), 0.0);
    if (s > 1)
      for (std::size_t k = 0; k < block.size(); ++k)
        for (const std::size_t b : others(a))
          fixed[k] += settings_.power.linearAt(common::distance(view_[block[k]].at, previous[b].at));
    common::Stream draw(settings_.seed, common::Purpose::kMlmcParticles, attachments_[a].sensor, streamKey(s));
    std::vector<std::vector<common::Vec2>> candidates;
    candidates.reserve(static_cast<std::size_t>(settings_.particles) + 1);
    for (std::int32_t p = 0; p < settings_.particles; ++p) candidates.push_back({drawAround(draw, a)});
    if (s > 1) candidates.push_back({previous[a].at});  // a later sweep never loses the best so far
    std::vector<double> scores(candidates.size());
    for (std::size_t p = 0; p < candidates.size(); ++p)
      scores[p] = blockLogLikelihood(view_, block, fixed, candidates[p], settings_.power, settings_.sigma_db);
    return best(a, candidates, scores);
  }

  /// Sweep 1 knows nothing of the others yet: it scores only the block sensors no nearer to another
  /// attached sensor than to its own, so that a neighbour's target does not pull it over.
  std::vector<std::size_t> ownShare(std::size_t a) {
    std::vector<std::size_t> share;
    for (const std::size_t m : blockOf(a)) {
      const double own = common::squaredDistance(view_[m].at, sensor_at_[a]);
      bool mine = true;
      for (const std::size_t b : others(a))
        if (common::squaredDistance(view_[m].at, sensor_at_[b]) < own) mine = false;
      if (mine) share.push_back(m);
    }
    return share;
  }

  const std::vector<std::size_t>& blockOf(std::size_t a) {
    if (!blocks_[a]) blocks_[a] = index_.within(sensor_at_[a], settings_.neighbours.n8());
    return *blocks_[a];
  }

  const std::vector<std::size_t>& others(std::size_t a) {
    if (!others_[a]) {
      std::vector<std::size_t> found;
      const double r2 = settings_.interaction_range * settings_.interaction_range;
      for (std::size_t b = 0; b < sensor_at_.size(); ++b)
        if (b != a && common::squaredDistance(sensor_at_[a], sensor_at_[b]) <= r2) found.push_back(b);
      others_[a] = std::move(found);
    }
    return *others_[a];
  }

  /// A particle for the target attached at a, uniform over its attachment's sampling disc.
  common::Vec2 drawAround(common::Stream& draw, std::size_t a) const {
    return uniformInDisc(draw, sensor_at_[a], samplingRadius(attachments_[a].kind, settings_.inside_radius));
  }

  /// The placement of the target attached at a by the best of `candidates` (its first component).
  Placement best(std::size_t a, const std::vector<std::vector<common::Vec2>>& candidates,
                 const std::vector<double>& scores) const {
    const Best b = bestOf(candidates, scores, 0, cloudResolution(attachments_[a].kind, settings_));
    return {attachments_[a], candidates[b.index][0], b.cov_xx, b.cov_xy, b.cov_yy, scores[b.index]};
  }

  std::int64_t streamKey(std::int32_t sweep) const {
    return static_cast<std::int64_t>(tick_) * kStreamsPerTick + sweep;
  }

  std::span<const Reading> view_;
  std::span<const Attachment> attachments_;
  std::int32_t tick_;
  const MlmcSettings& settings_;
  ViewIndex index_;
  std::vector<common::Vec2> sensor_at_;
  std::vector<std::optional<std::vector<std::size_t>>> blocks_;
  std::vector<std::optional<std::vector<std::size_t>>> others_;
};

}  // namespace

std::vector<Placement> place(std::span<const Reading> view, std::span<const Attachment> attachments,
                             std::span<const std::size_t> attached, std::int32_t tick, const MlmcSettings& settings) {
  if (settings.particles < 1) throw std::invalid_argument("adman place: particles must be >= 1");
  if (settings.sweeps < 1 || settings.sweeps > kMaxSweeps)
    throw std::invalid_argument("adman place: sweeps must be in [1, " + std::to_string(kMaxSweeps) + "]");
  Placer placer(view, attachments, tick, settings);
  return settings.joint ? placer.joint(attached) : placer.factorised(attached);
}

}  // namespace wsn::node::adman

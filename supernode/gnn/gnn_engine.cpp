#include "supernode/gnn/gnn_engine.hpp"

#include "common/track_id.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/assignment.hpp"
#include "common/shared_derivations.hpp"
#include "common/track_confirmation.hpp"

namespace wsn::supernode::gnn {
namespace {

using common::GaussianState;
using common::kVx;
using common::kVy;
using common::kX;
using common::kY;

bool byId(const GnnEngine::Track& a, const GnnEngine::Track& b) { return a.id < b.id; }

using common::Derived;
using common::shortNumber;
using Statistics = common::ObservationStatistics;
using Resolved = std::map<std::string, common::EngineParam>;

/// A target's track is confirmed within N ticks with this probability.
constexpr double kConfirmWithin = 0.95;
/// P(Binomial(n, p) >= k).
double atLeast(std::int32_t k, std::int32_t n, double p) {
  double total = 0.0;
  for (std::int32_t j = k; j <= n; ++j)
    total += std::exp(std::lgamma(n + 1.0) - std::lgamma(j + 1.0) - std::lgamma(n - j + 1.0)) * std::pow(p, j) *
             std::pow(1.0 - p, n - j);
  return total;
}

/// The shortest window in which a target's track, born at a report, collects m hits with
/// probability 0.95 at detection probability pd.
std::int32_t confirmationWindow(std::int32_t m, double pd) {
  std::int32_t n = m;
  while (n < 50 && atLeast(m - 1, n - 1, pd) < kConfirmWithin) ++n;
  return n;
}

/// M of M-of-N: the evidence that costs the fewest wrong track-ticks, weighing tentative
/// tracks of clutter (a chain of M false reports, each in its predecessor's gate, placed anywhere
/// within the N ticks of confirmationWindow(M)), each kept max_misses ticks, against the wait of
/// every true target.
std::int32_t confirmHits(const Statistics& s, const Resolved& r) {
  const double pd = s.detectionProbability();
  const double lambda_f = s.falseAlarmDensity();
  const double births = common::birthsPerTick(s.birth_density.value, s.region_area, s.run_ticks);
  const auto gates = common::newTrackGates(r.at("gate_chi2").value, r.at("measurement_sigma").value,
                                           r.at("initial_velocity_sigma").value, s.process_noise_sigma, s.delta);
  const auto false_tracks = [&](std::int32_t m) {
    const std::int32_t n = confirmationWindow(m, pd);
    const double placements =
        std::exp(std::lgamma(static_cast<double>(n)) - std::lgamma(static_cast<double>(m)) - std::lgamma(n - m + 1.0));
    return common::falseTrackRate(m, lambda_f, s.region_area, gates.first, gates.later) * placements;
  };
  return common::leastCostConfirmation(false_tracks, r.at("max_misses").value, births,
                                       [&](std::int32_t k) { return common::ticksForReports(k, pd); }, 1, 50);
}

std::string confirmationHow(const Statistics& s) {
  return "clutter " + shortNumber(s.falseAlarmDensity()) + " per area and tick over " + shortNumber(s.region_area) +
         " at pd " + shortNumber(s.detectionProbability()) + ": fewest wrong track-ticks, tentative tracks of clutter "
         "against the wait of every new target";
}

/// GNN's filter and track management follow the scenario (observation_model/ measures it).
std::map<std::string, common::ParamDerivation> derivations() {
  std::map<std::string, common::ParamDerivation> d;
  d["measurement_sigma"] = common::reportErrorDerivation();
  d["merge_radius"] = common::mergeRadiusDerivation();
  d["initial_velocity_sigma"] = common::newTrackVelocityDerivation();
  d["confirm_hits"] = {"hits that balance confirmed tracks of clutter against the wait of every new target",
                       [](const common::StatisticsSource& stats, const Resolved& r) {
                         const Statistics& s = stats();
                         return Derived{static_cast<double>(confirmHits(s, r)), confirmationHow(s)};
                       }};
  d["confirm_window"] = {"ticks in which a target's track collects confirm_hits with probability 0.95",
                         [](const common::StatisticsSource& stats, const Resolved& r) {
                           const Statistics& s = stats();
                           const auto m = static_cast<std::int32_t>(r.at("confirm_hits").value);
                           const double pd = s.detectionProbability();
                           return Derived{static_cast<double>(confirmationWindow(m, pd)),
                                          "shortest window with P(" + std::to_string(m) + " hits) >= 0.95 at pd " +
                                              shortNumber(pd)};
                         }};
  // A track is deleted at the newest tick, where the last ticks' reports may still be on their way
  // (judged by the in-window pd alone, max_misses was 1 at pte = 0, pde = 0.3, and every delay
  // deleted a track); the window replay gives the late ones their tick.
  d["max_misses"] = common::liveEdgeMissDerivation(1, 1000);
  return d;
}

}  // namespace

const config::FieldTable<GnnParams>& paramTable() {
  using config::integer;
  using config::real;
  static const config::FieldTable<GnnParams> table{
      "tracker.params (gnn)",
      {
          real<GnnParams>("measurement_sigma", &GnnParams::measurement_sigma, config::closed(1e-3, 100.0),
                          "separations",
                          "std. deviation of a fused observation's position error, R = sigma^2 I (sensor separations)"),
          real<GnnParams>("initial_velocity_sigma", &GnnParams::initial_velocity_sigma, config::closed(1e-3, 100.0),
                          "separations/tick",
                          "std. deviation of the unknown velocity of a new track (sensor separations per tick)"),
          real<GnnParams>("gate_chi2", &GnnParams::gate_chi2, config::closed(0.1, 1000.0), "",
                          "gate on the squared Mahalanobis distance of an observation (9.21: chi^2, 2 dof, 99%)"),
          integer<GnnParams>("max_misses", &GnnParams::max_misses, 1.0, 1000.0, "ticks",
                             "consecutive misses after which a confirmed track is deleted (ticks)"),
          integer<GnnParams>("confirm_hits", &GnnParams::confirm_hits, 1.0, 50.0, "observations",
                             "M of M-of-N confirmation: hits needed within the first confirm_window ticks of a track"),
          integer<GnnParams>("confirm_window", &GnnParams::confirm_window, 1.0, 50.0, "ticks",
                             "N of M-of-N confirmation (ticks); a value below confirm_hits acts as confirm_hits"),
          real<GnnParams>("merge_radius", &GnnParams::merge_radius, config::closed(0.0, 1e6), "separations",
                          common::kMergeRadiusMeaning),
      }};
  return table;
}

EngineSpec engineSpec() {
  EngineSpec spec;
  spec.name = "gnn";
  spec.description =
      "global nearest neighbour: constant-velocity Kalman filters (Oh eq. 8), optimal gated assignment, "
      "M-of-N confirmation; replays the window so delayed observations are used";
  spec.params = common::paramSpecs(paramTable(), derivations());
  spec.create = [](const EngineContext& context) -> std::unique_ptr<Engine> {
    return std::make_unique<GnnEngine>(context);
  };
  return spec;
}

GnnParams GnnParams::fromContext(const EngineContext& context) {
  return common::decodeParams(paramTable(), context.params);
}


GnnEngine::GnnEngine(const EngineContext& context)
    : supernode_(context.supernode),
      region_(context.region),
      detection_share_(detectionShare(context)),
      params_(GnnParams::fromContext(context)),
      unseen_tick_weight_(std::pow(common::kRareMissRun, 1.0 / params_.max_misses)),
      model_(context.dynamics.delta, context.dynamics.process_noise_sigma,
             params_.measurement_sigma),
      replay_(&Track::id, &byId) {}

bool GnnEngine::silenceIsRare(Track& track) const {
  // max_misses silent ticks are rare (common::kRareMissRun) for a live target on the field's
  // average, rho^max_misses with rho = kRareMissRun^(1 / max_misses) a tick. Where the sensors'
  // coverage is known a silent tick weighs what they would have seen at the track's position,
  // 1 - (1 - rho) share(x): a track left at a sensor its target has passed ends within a few ticks,
  // one in ground no sensor covers only after max_misses.
  if (detection_share_.uniform()) return false;
  const double share = detection_share_.at({track.state.x(kX), track.state.x(kY)});
  track.silence *= 1.0 - std::min(1.0, (1.0 - unseen_tick_weight_) * share);
  return track.silence <= common::kRareMissRun;
}

std::vector<int> GnnEngine::associate(const std::vector<Track>& tracks,
                                      std::span<const common::Observation> slot) const {
  const std::size_t rows = tracks.size();
  const std::size_t cols = slot.size();

  // Gate: pairs with d^2 <= gate_chi2. S depends only on the track, so it is factorised once per
  // track; the cost d^2 + ln det S is -2 log N(y; Hx, S) up to a constant, so the assignment
  // maximises the joint likelihood of the gated pairs. Pairs outside the gate are forbidden, so
  // the solver splits the scene into clusters that share a gate.
  std::vector<double> cost(rows * cols, common::kForbidden);
  for (std::size_t i = 0; i < rows; ++i) {
    const common::InnovationCovariance S(model_, tracks[i].state);
    if (!S.positiveDefinite()) continue;
    const double log_det = S.logDeterminant();
    const common::MeasurementVector predicted = model_.H * tracks[i].state.x;
    // d^2 >= |nu|^2 / lambda_max(S) >= |nu|^2 / trace(S): a cheap test before the solve.
    const double reach2 = params_.gate_chi2 * S.S().trace();
    for (std::size_t j = 0; j < cols; ++j) {
      const common::MeasurementVector nu = common::MeasurementVector(slot[j].x, slot[j].y) - predicted;
      if (nu.squaredNorm() > reach2) continue;
      const double d2 = S.mahalanobisSquared(nu);
      if (d2 <= params_.gate_chi2) cost[i * cols + j] = d2 + log_det;
    }
  }
  return common::solveAssignment(cost, rows, cols);
}

void GnnEngine::processTick(std::vector<Track>& tracks, std::int32_t tick,
                            std::span<const common::Observation> slot) const {
  // The replay put this tick's handoffs (state at tick - 1) into `tracks`: they are scanned like any other.

  // Oh et al., eq. (8): time update of every track.
  for (auto& track : tracks) track.state = common::predict(model_, track.state);

  const std::vector<int> assigned = associate(tracks, slot);
  const std::size_t rows = tracks.size();
  const std::size_t cols = slot.size();
  const std::int32_t confirm_window = std::max(params_.confirm_window, params_.confirm_hits);
  std::vector<bool> used(cols, false);
  std::vector<Track> next;
  next.reserve(rows + cols);
  for (std::size_t i = 0; i < rows; ++i) {
    Track track = tracks[i];
    bool hit = false;
    if (assigned[i] >= 0) {
      const auto j = static_cast<std::size_t>(assigned[i]);
      const auto updated =
          common::update(model_, track.state, common::MeasurementVector(slot[j].x, slot[j].y));
      if (updated) {
        track.state = *updated;
        used[j] = true;
        hit = true;
      }
    }
    if (hit) {
      ++track.hits;
      track.silence = 1.0;
      if (track.confirmed) {
        track.misses = 0;
      } else if (track.hits >= params_.confirm_hits) {
        track.confirmed = true;  // M hits within the first N ticks
        track.misses = 0;
      }
    } else {
      ++track.misses;
      // A tentative track of age hits + misses still has N - age ticks to collect M - hits
      // hits: it cannot make it once misses > N - M.
      const bool dead = track.confirmed ? track.misses >= params_.max_misses || silenceIsRare(track)
                                        : track.misses > confirm_window - params_.confirm_hits;
      // A track that coasted out of the region can never be observed again: it followed a
      // target that left, and keeping it for max_misses ticks only adds a false track.
      const bool left = !region_.contains({track.state.x(kX), track.state.x(kY)});
      if (dead || left) continue;
    }
    next.push_back(track);
  }

  // Every observation no track took starts a tentative track at its position, at rest.
  const double r2 = params_.measurement_sigma * params_.measurement_sigma;
  const double v2 = params_.initial_velocity_sigma * params_.initial_velocity_sigma;
  std::sort(next.begin(), next.end(), byId);
  const std::size_t survivors = next.size();
  for (std::size_t j = 0; j < cols; ++j) {
    if (used[j]) continue;
    Track born;
    born.id = common::track_id::birth(supernode_, tick, slot[j].sensor);
    // Two reports of one sensor in one tick would share an id: the first (canonical order) wins.
    const auto end = next.begin() + static_cast<std::ptrdiff_t>(survivors);
    if (std::binary_search(next.begin(), end, born, byId) ||
        std::any_of(end, next.end(), [&](const Track& t) { return t.id == born.id; }))
      continue;
    born.state.x << slot[j].x, slot[j].y, 0.0, 0.0;
    born.state.P.setZero();
    born.state.P(kX, kX) = r2;
    born.state.P(kY, kY) = r2;
    born.state.P(kVx, kVx) = v2;
    born.state.P(kVy, kVy) = v2;
    born.hits = 1;
    born.misses = 0;
    born.confirmed = params_.confirm_hits <= 1;
    next.push_back(born);
  }
  std::sort(next.begin(), next.end(), byId);
  tracks = std::move(next);
}

void GnnEngine::step(const ObservationWindow& window) {
  // Replay the window from the anchor: a late observation now sits in its own slot. A model that
  // reports every detecting sensor has each tick's reports merged first (merge_radius).
  std::optional<ObservationWindow> merged;
  if (params_.merge_radius > 0.0) merged = window.merged(params_.merge_radius);
  replay_.step(
      merged ? *merged : window,
      [this](std::vector<Track>& tracks, std::int32_t tick, std::span<const common::Observation> slot) {
        processTick(tracks, tick, slot);
      },
      // A handoff too old to enter at its own tick enters the anchor, predicted up to it.
      [this](Track& track, std::int32_t first_tick, std::int32_t anchor_tick) {
        for (std::int32_t t = first_tick; t <= anchor_tick; ++t) track.state = common::predict(model_, track.state);
      });
}

void GnnEngine::adopt(const common::TrackHandoff& handoff) {
  Track track;
  track.id = handoff.track;
  track.state.x = common::StateVector(handoff.state.data());
  track.state.P = common::fromRowMajor(handoff.covariance);
  track.state.P = 0.5 * (track.state.P + track.state.P.transpose());
  if (!track.state.x.allFinite() || !track.state.P.allFinite()) {
    ++rejected_handoffs_;
    return;
  }
  track.hits = handoff.hits;
  track.misses = handoff.misses;
  track.confirmed = handoff.confirmed;
  replay_.adopt(handoff.last_tick + 1, track);
}

std::vector<common::TrackEstimate> GnnEngine::confirmedTracks() const {
  std::vector<common::TrackEstimate> out;
  for (const auto& track : replay_.current()) {
    if (!track.confirmed) continue;
    const auto& x = track.state.x;
    out.push_back({track.id, x(kX), x(kY), x(kVx), x(kVy), common::toRowMajor(track.state.P), replay_.currentTick() - track.misses, {}, {}});
  }
  return out;
}

std::vector<TrackPrediction> GnnEngine::predictions() const {
  std::vector<TrackPrediction> out;
  out.reserve(replay_.current().size());
  for (const auto& track : replay_.current()) {
    const common::StateVector next = model_.F * track.state.x;
    out.push_back({track.id, {next(kX), next(kY)}});
  }
  return out;
}

common::TrackHandoff GnnEngine::release(common::TrackId track_id, std::uint32_t to_supernode) {
  const auto& tracks = replay_.current();
  const auto it = std::lower_bound(tracks.begin(), tracks.end(), Track{track_id, {}, 0, 0, false}, byId);
  if (it == tracks.end() || it->id != track_id)
    throw std::invalid_argument("gnn: release of unknown track " + std::to_string(track_id));
  common::TrackHandoff handoff;
  handoff.track = track_id;
  handoff.to_supernode = to_supernode;
  handoff.last_tick = replay_.currentTick();
  for (int r = 0; r < common::kStateDim; ++r) handoff.state[static_cast<std::size_t>(r)] = it->state.x(r);
  handoff.covariance = common::toRowMajor(it->state.P);
  handoff.hits = it->hits;
  handoff.misses = it->misses;
  handoff.confirmed = it->confirmed;
  replay_.release(track_id);
  return handoff;
}

}  // namespace wsn::supernode::gnn

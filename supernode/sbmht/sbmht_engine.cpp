#include "supernode/sbmht/sbmht_engine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "common/scenario_error.hpp"
#include "common/shared_derivations.hpp"
#include "common/track_confirmation.hpp"
#include "common/track_id.hpp"
#include "common/terrain.hpp"
#include "supernode/sbmht/measurement_models.hpp"
#include "supernode/sbmht/reach.hpp"
#include "supernode/sbmht/road.hpp"

namespace wsn::supernode::sbmht {
namespace {

using common::GaussianState;
using common::kVx;
using common::kVy;
using common::kX;
using common::kY;
using Leaf = SbmhtEngine::Leaf;

using common::Derived;
using common::shortNumber;
using Statistics = common::ObservationStatistics;
using Resolved = std::map<std::string, common::EngineParam>;

/// Two bearings whose lines of sight are within about 1 degree of parallel or of opposed (|sin gamma|
/// below this) start no tree: parallel rays cross far along both or nowhere, opposed ones (a target on
/// the line through both sensors) anywhere between them, and a fix so long and thin (its covariance
/// grows as 1 / sin^2 gamma) locates nothing the sensors' reach does not already bound.
constexpr double kMinBearingCrossingSine = 0.02;
/// Leaves with a posterior below this are pruned (docs/ONERA.md §3, B&P ch. 16).
constexpr double kMinTrackProbability = 1e-3;
/// Nodes the k-best search of one cluster may visit; beyond it the k best found so far are used
/// (counted in truncatedSearches()).
constexpr std::uint64_t kSearchBudget = 200000;

bool leafOrder(const Leaf& a, const Leaf& b) {
  if (a.tree != b.tree) return a.tree < b.tree;
  return SbmhtEngine::historyLess(a.history, b.history);
}

std::map<std::string, common::ParamDerivation> derivations() {
  std::map<std::string, common::ParamDerivation> d;
  d["measurement_sigma"] = common::reportErrorDerivation();
  d["merge_radius"] = common::mergeRadiusDerivation();
  d["initial_velocity_sigma"] = common::newTrackVelocityDerivation();
  d["birth_density"] = common::birthDensityDerivation();
  d["detection_probability"] = {
      "the sensor model's sensing probability x the network's delivery into the window",
      [](const common::StatisticsSource& stats, const Resolved&) {
        const Statistics& s = stats();
        return Derived{s.detectionProbability(), "sensing " + shortNumber(s.sensing_probability.value) +
                                                     " x delivery " + shortNumber(s.delivery_probability.value)};
      }};
  d["false_alarm_density"] = {
      "the sensor model's false reports x the network's delivery, at least one per 100 ticks over the region",
      [](const common::StatisticsSource& stats, const Resolved&) {
        const Statistics& s = stats();
        const double floor = 1.0 / (common::kClutterFloorTicks * std::max(s.region_area, 1e-12));
        return Derived{std::max(s.falseAlarmDensity(), floor),
                       "max(" + shortNumber(s.falseAlarmDensity()) + ", 1 / (100 x area " + shortNumber(s.region_area) +
                           "))"};
      }};
  d["max_misses"] = {"consecutive misses rarer than 1 % at the scenario's pd (sensed and delivered in the window), "
                     "at least 2",
                     [](const common::StatisticsSource& stats, const Resolved&) {
                       // At least 2: one target's report hides another's where they cross (one report for
                       // two targets), and the miss branch must outlive that tick to bridge it.
                       const double pd = stats().detectionProbability();
                       return Derived{static_cast<double>(std::max(2, common::rareMissRun(pd, 0.01, 1000))),
                                      "max(2, smallest k with (1 - pd)^k <= 0.01 at pd " + shortNumber(pd) + ")"};
                     }};
  d["confirm_reports"] = {
      "reports that balance chains of clutter against the wait of every new target (as MCMCDA's "
      "confirm_observations)",
      [](const common::StatisticsSource& stats, const Resolved& r) {
        // The SPRT's alpha is a design value: with alpha = 1e-3 a clutter-free scenario would wait
        // for a second report though a single one is decisive there. The count is derived from
        // the same false-track economics as the other engines' confirmation.
        return common::clutterConfirmation(stats(), r, "gate_chi2", "max_misses", 10);
      }};
  d["delivery_probability"] = {"the network's delivery into the window",
                                [](const common::StatisticsSource& stats, const Resolved&) {
                                  const Statistics& s = stats();
                                  return Derived{std::clamp(s.delivery_probability.value, 0.001, 1.0),
                                                 "delivery " + shortNumber(s.delivery_probability.value)};
                                }};
  d["cv_slow_sigma"] = {"the targets' process noise q (dynamics.process_noise_sigma)",
                        [](const common::StatisticsSource& stats, const Resolved&) {
                          return Derived{stats().process_noise_sigma, "q"};
                        }};
  // docs/ONERA.md §2 proposes sigma_d = 1.0 and sigma_n = 0.1 m/s^2 beside sigma_a = 0.3: a road lets a
  // target change speed along it more freely than a quiet CV model, and hardly leave it.
  d["road_along_sigma"] = {"10/3 x the targets' process noise q (docs/ONERA.md §2: 1.0 against 0.3 m/s^2)",
                           [](const common::StatisticsSource& stats, const Resolved&) {
                             return Derived{10.0 / 3.0 * stats().process_noise_sigma, "10/3 q"};
                           }};
  d["road_across_sigma"] = {"q / 3 (docs/ONERA.md §2: 0.1 against 0.3 m/s^2)",
                            [](const common::StatisticsSource& stats, const Resolved&) {
                              return Derived{stats().process_noise_sigma / 3.0, "q / 3"};
                            }};
  d["cv_fast_sigma"] = {"5 x the targets' process noise q (docs/ONERA.md §2: 1.5 against 0.3 m/s^2)",
                        [](const common::StatisticsSource& stats, const Resolved&) {
                          return Derived{5.0 * stats().process_noise_sigma, "5 q"};
                        }};
  return d;
}

/// The k best global hypotheses of one cluster: one leaf or none per tree, no report used twice,
/// the largest sums of leaf scores. Exact depth-first branch and bound (the bound: every later tree
/// adds at most its best positive score), within kSearchBudget nodes.
class HypothesisSearch {
 public:
  struct Hypothesis {
    double score = 0.0;
    std::vector<int> chosen;  ///< per tree: the cluster leaf, or -1 (the tree is absent)
  };

  HypothesisSearch(const std::vector<std::vector<int>>& options, const std::vector<double>& scores,
                   const std::vector<std::vector<int>>& reports, std::size_t report_count, std::size_t k)
      : options_(options), scores_(scores), reports_(reports), used_(report_count, 0), k_(k) {
    bound_.assign(options_.size() + 1, 0.0);
    for (std::size_t t = options_.size(); t-- > 0;) {
      double best = 0.0;
      for (int leaf : options_[t]) best = std::max(best, scores_[static_cast<std::size_t>(leaf)]);
      bound_[t] = bound_[t + 1] + best;
    }
    chosen_.assign(options_.size(), -1);
  }

  void run() { search(0, 0.0); }
  const std::vector<Hypothesis>& results() const { return results_; }
  bool truncated() const { return truncated_; }

 private:
  void search(std::size_t t, double score) {
    if (++nodes_ > kSearchBudget) {
      truncated_ = true;
      return;
    }
    if (results_.size() == k_ && score + bound_[t] <= results_.back().score) return;
    if (t == options_.size()) {
      // Insert after equal scores: the first found (better-ordered options) ranks first.
      const auto at = std::upper_bound(results_.begin(), results_.end(), score,
                                       [](double s, const Hypothesis& h) { return s > h.score; });
      results_.insert(at, Hypothesis{score, chosen_});
      if (results_.size() > k_) results_.pop_back();
      return;
    }
    // Options in order of score (sorted by the caller), the tree's absence where 0 falls.
    bool absent_tried = false;
    for (int leaf : options_[t]) {
      const double s = scores_[static_cast<std::size_t>(leaf)];
      if (!absent_tried && s <= 0.0) {
        absent_tried = true;
        chosen_[t] = -1;
        search(t + 1, score);
      }
      const auto& used = reports_[static_cast<std::size_t>(leaf)];
      if (std::any_of(used.begin(), used.end(), [&](int r) { return used_[static_cast<std::size_t>(r)] != 0; }))
        continue;
      for (int r : used) used_[static_cast<std::size_t>(r)] = 1;
      chosen_[t] = leaf;
      search(t + 1, score + s);
      for (int r : used) used_[static_cast<std::size_t>(r)] = 0;
    }
    if (!absent_tried) {
      chosen_[t] = -1;
      search(t + 1, score);
    }
    chosen_[t] = -1;
  }

  const std::vector<std::vector<int>>& options_;
  const std::vector<double>& scores_;
  const std::vector<std::vector<int>>& reports_;
  std::vector<char> used_;
  std::size_t k_;
  std::vector<double> bound_;
  std::vector<int> chosen_;
  std::vector<Hypothesis> results_;
  std::uint64_t nodes_ = 0;
  bool truncated_ = false;
};

/// Keeps the leaves whose flag is set, in order.
void keepMarked(std::vector<Leaf>& leaves, const std::vector<char>& keep) {
  std::vector<Leaf> kept;
  kept.reserve(leaves.size());
  for (std::size_t k = 0; k < leaves.size(); ++k)
    if (keep[k]) kept.push_back(std::move(leaves[k]));
  leaves = std::move(kept);
}

std::size_t findRoot(std::vector<std::size_t>& parent, std::size_t k) {
  while (parent[k] != k) k = parent[k] = parent[parent[k]];
  return k;
}

}  // namespace

/// One report as the scan uses it: its measurement function, value, noise and clutter density in
/// its own space, the gate for its dimension, and where it would start a track.
struct SbmhtEngine::ReportTerms {
  bool usable = false;
  /// A field-frame position: the cheap distance pre-check before the EKFs applies.
  bool position = false;
  MeasurementModel model;
  MeasurementVector z;
  MeasurementCovariance R;
  double clutter_density = 0.0;
  double gate = 0.0;
  std::optional<PositionFix> fix;
  /// Its class likelihoods c (eqs. 19-23), one per common::kClassCount class; empty when it
  /// carries none or a c the engine cannot use (another class count, a negative entry, all zero).
  std::span<const double> classes;
};

namespace {

using ReportTerms = SbmhtEngine::ReportTerms;

/// c of a measurement when it is one class likelihood per class, finite, non-negative and not all
/// zero (what common::updateClassVector takes); else empty: the report then says nothing about
/// class, as a radar's does.
std::span<const double> classLikelihoodsOf(const common::Measurement& m) {
  const auto& c = m.class_likelihoods;
  if (c.size() != common::kClassCount) return {};
  if (!std::all_of(c.begin(), c.end(), [](double v) { return std::isfinite(v) && v >= 0.0; })) return {};
  if (std::none_of(c.begin(), c.end(), [](double v) { return v > 0.0; })) return {};
  return c;
}

/// The terms of observation o. A plain position (the position engines' reports) has the engine's
/// own noise (measurement_sigma) and clutter density (per area). Any other measurement must carry
/// its R and its clutter density in its own space (common/measurement.hpp): a bearing's lambda per
/// radian cannot be made from a density per area; without them the report is not usable.
ReportTerms termsOf(const common::Observation& o, double r2, double lambda_fa, const std::array<double, 4>& gates) {
  ReportTerms t;
  if (!o.measurement) {
    t.z.resize(2);
    t.z << o.x, o.y;
    t.R = MeasurementCovariance::Identity(2, 2) * r2;
    t.clutter_density = lambda_fa;
  } else {
    const common::Measurement& m = *o.measurement;
    const auto model = modelOf(m);
    if (!model) return t;
    t.model = *model;
    t.z = valuesOf(m);
    const auto R = noiseOf(m);
    const bool position = m.kind == common::MeasurementKind::position;
    if (R)
      t.R = *R;
    else if (position)
      t.R = MeasurementCovariance::Identity(2, 2) * r2;
    else
      return t;
    t.clutter_density = m.clutter_density > 0.0 ? m.clutter_density : (position ? lambda_fa : 0.0);
    if (!(t.clutter_density > 0.0)) return t;
  }
  t.position = t.model.kind == common::MeasurementKind::position;
  t.gate = gates[static_cast<std::size_t>(t.model.dimension())];
  t.fix = positionFix(t.model, t.z, t.R);
  if (o.measurement) t.classes = classLikelihoodsOf(*o.measurement);
  t.usable = true;
  return t;
}

/// A bearing says nothing along its line, but its sensor sees no farther than its range: each
/// model's estimate is conditioned on the target lying within reach, and the report's likelihood
/// gains P(within reach) (reach.hpp). Without it a track fed bearings alone drifts along the line
/// of sight for as long as the bearings last (docs/ONERA.md §5). False when no model could be in
/// reach: the report is not this track's.
bool constrainToSensorReach(ImmUpdate& hit, const common::SensorCoverage& sensor) {
  ModeVector weights = hit.state.probabilities;
  for (std::size_t i = 0; i < hit.state.modes.size(); ++i) {
    const ReachUpdate r = constrainToReach(hit.state.modes[i], sensor.position, sensor.range);
    hit.state.modes[i] = r.state;
    weights(static_cast<Eigen::Index>(i)) *= r.probability;
  }
  const double within = weights.sum();
  if (!(within > 0.0)) return false;
  hit.state.probabilities = weights / within;
  hit.likelihood *= within;
  return true;
}

void unite(std::vector<std::size_t>& parent, std::size_t a, std::size_t b) {
  a = findRoot(parent, a);
  b = findRoot(parent, b);
  if (a != b) parent[std::max(a, b)] = std::min(a, b);
}

}  // namespace

const config::FieldTable<SbmhtParams>& paramTable() {
  using config::integer;
  using config::real;
  using P = SbmhtParams;
  static const config::FieldTable<SbmhtParams> table{
      "tracker.params (sbmht)",
      {
          real<P>("detection_probability", &P::detection_probability, config::closed(0.001, 0.999), "",
                  "PD: probability that a live target's report reaches the window at a tick (detection times delivery)"),
          real<P>("false_alarm_density", &P::false_alarm_density, config::closed(1e-12, 1.0), "1/(separation² tick)",
                  "lambda_fa of eq. (17): delivered false reports per unit area per tick"),
          real<P>("birth_density", &P::birth_density, config::closed(1e-12, 1.0), "1/(separation² tick)",
                  "lambda_nt of eq. (18): new targets per unit area per tick"),
          real<P>("measurement_sigma", &P::measurement_sigma, config::closed(1e-3, 100.0), "separations",
                  "std. deviation of a position report's error per axis, R = sigma^2 I"),
          real<P>("initial_velocity_sigma", &P::initial_velocity_sigma, config::closed(1e-3, 100.0), "separations/tick",
                  "prior std. deviation of a new track's velocity per axis (the track starts at rest)"),
          real<P>("gate_chi2", &P::gate_chi2, config::closed(0.1, 1000.0), "",
                  "gate on a report's squared Mahalanobis distance under the best moving model (9.21: chi^2, 2 dof, 99%)"),
          real<P>("sprt_alpha", &P::sprt_alpha, config::closed(1e-9, 0.5), "",
                  "SPRT alpha, P(confirming a false track): confirm at L >= ln((1 - beta) / alpha)"),
          real<P>("sprt_beta", &P::sprt_beta, config::closed(1e-9, 0.5), "",
                  "SPRT beta, P(deleting a true track): delete a tentative track at L <= ln(beta / (1 - alpha))"),
          real<P>("drop_score", &P::drop_score, config::closed(0.1, 1e6), "",
                  "T_drop: a confirmed track whose score falls this far below its best is deleted"),
          integer<P>("max_misses", &P::max_misses, 1.0, 1000.0, "ticks",
                     "without a sensor list: a leaf that missed this many consecutive ticks is deleted (the stop model "
                     "makes coasting cheap, so T_drop alone keeps a vanished target's track for about 100 scans); with "
                     "one, max_coast_ticks and T_drop end leaves instead"),
          integer<P>("n_scan", &P::n_scan, 0.0, 50.0, "scans",
                     "N of N-scan pruning: a tree keeps only the branches that agree with the best hypothesis N ticks "
                     "back; leaves that took the same reports in their last N ticks are merged"),
          integer<P>("hypotheses", &P::hypotheses, 1.0, 1000.0, "",
                     "N_Hypo: global hypotheses kept per cluster (the k best), over which track posteriors are computed"),
          integer<P>("initial_score", &P::initial_score, 0.0, 1.0, "",
                     "a new track's score: 0 blackman, ln(PD lambda_nt / lambda_fa); 1 paper, eq. (18) "
                     "ln(lambda_fa / (lambda_fa + lambda_nt))"),
          real<P>("stop_sigma", &P::stop_sigma, config::closed(1e-6, 100.0), "separations",
                  "stop model: the position wanders by this std. deviation per tick"),
          real<P>("cv_slow_sigma", &P::cv_slow_sigma, config::closed(1e-3, 100.0), "separations/tick²",
                  "acceleration std. deviation of the quiet constant-velocity model"),
          real<P>("cv_fast_sigma", &P::cv_fast_sigma, config::closed(1e-3, 100.0), "separations/tick²",
                  "acceleration std. deviation of the manoeuvring constant-velocity model"),
          real<P>("stop_time_constant", &P::stop_time_constant, config::closed(1e-3, 1e6), "ticks",
                  "mean sojourn in the stop model: p_00 = exp(-delta / tau)"),
          real<P>("slow_time_constant", &P::slow_time_constant, config::closed(1e-3, 1e6), "ticks",
                  "mean sojourn in the quiet constant-velocity model"),
          real<P>("fast_time_constant", &P::fast_time_constant, config::closed(1e-3, 1e6), "ticks",
                  "mean sojourn in the manoeuvring constant-velocity model"),
          real<P>("merge_radius", &P::merge_radius, config::closed(0.0, 1e6), "separations",
                  common::kMergeRadiusMeaning),
          integer<P>("confirm_reports", &P::confirm_reports, 1.0, 1000.0, "ticks",
                     "a tentative track that took reports at this many ticks is confirmed, even before its score reaches the "
                     "SPRT's threshold: the evidence the scenario's clutter makes decisive (1 without clutter)"),
          real<P>("delivery_probability", &P::delivery_probability, config::closed(0.001, 1.0), "",
                  "where sensors are listed: the share of a sensor's reports that reach the window; a sensor's PD "
                  "at a target it covers and sees is its type's PD times this"),
          integer<P>("max_coast_ticks", &P::max_coast_ticks, 1.0, 1e6, "ticks",
                     "where sensors are listed: a leaf that no sensor could see (behind a mask, in a gap between "
                     "sensor areas) for this many ticks running is deleted; a miss costs nothing there"),
          integer<P>("bearing_pair_births", &P::bearing_pair_births, 0.0, 1.0, "",
                     "1: two bearings of one tick from two listed sensors that no track took start a tentative track "
                     "where their rays cross within both sensors' sight (the composite report of Pannetier et al. "
                     "§II-C); 0: bearings only update tracks"),
          integer<P>("use_road_network", &P::use_road_network, 0.0, 1.0, "",
                     "1: algorithm 1 of Pannetier et al., where the scenario has roads: a road-constrained model in the "
                     "IMM near a road, its estimate projected onto the road, and N-scan pruning that keeps the best "
                     "branch per road section; 0: algorithm 2, the roads unused"),
          real<P>("road_along_sigma", &P::road_along_sigma, config::closed(1e-3, 100.0), "separations/tick²",
                  "road model (eq. 6): acceleration std. deviation along the road"),
          real<P>("road_across_sigma", &P::road_across_sigma, config::closed(1e-4, 100.0), "separations/tick²",
                  "road model (eq. 6): acceleration std. deviation across the road"),
          real<P>("road_location_sigma", &P::road_location_sigma, config::closed(0.0, 1e6), "separations",
                  "how well the scenario's road centre lines are known: added across the road to a projected "
                  "estimate's position variance"),
          real<P>("road_gate_distance", &P::road_gate_distance, config::closed(0.0, 1e6), "separations",
                  "the road model is active while a track's predicted position lies this close to a road section"),
          real<P>("road_time_constant", &P::road_time_constant, config::closed(1e-3, 1e6), "ticks",
                  "mean sojourn in the road model"),
          integer<P>("road_sections_kept", &P::road_sections_kept, 1.0, 100.0, "",
                     "Nk of algorithm 1: N-scan pruning keeps, beside the branches that agree with the best "
                     "hypothesis, the best branch on each other road section, up to this many sections a tree"),
      }};
  return table;
}

EngineSpec engineSpec() {
  EngineSpec spec;
  spec.name = "sbmht";
  spec.description =
      "ONERA structured-branching MHT (Pannetier et al. 2014): IMM (stop, two CV models and, near the "
      "scenario's roads, a road model), track trees with a "
      "miss branch, LLR scores and SPRT, k best hypotheses per cluster, N-scan pruning; replays the window";
  spec.params = common::paramSpecs(paramTable(), derivations());
  spec.create = [](const EngineContext& context) -> std::unique_ptr<Engine> {
    return std::make_unique<SbmhtEngine>(context);
  };
  // Presence and signal strength have no h(x) a filter can use (measurement_models.hpp).
  spec.accepts = {"position", "bearing", "range_bearing_rate", "azimuth_elevation"};
  return spec;
}

SbmhtParams SbmhtParams::fromContext(const EngineContext& context) {
  return common::decodeParams(paramTable(), context.params);
}

namespace {

/// Algorithm 2's models: stop, quiet CV and manoeuvring CV.
std::vector<MotionModel> algorithm2Models(const SbmhtParams& p, double delta) {
  return {stopModel(delta, p.stop_sigma), constantVelocityModel(delta, p.cv_slow_sigma),
          constantVelocityModel(delta, p.cv_fast_sigma)};
}

/// Algorithm 2's IMM. With roads (algorithm 1) the road model is appended, here as it is off
/// road: nothing switches into it (VS-IMM: the model set follows the roads), a track that leaves
/// the road hands its probability to the two CV models evenly, and it predicts as the manoeuvring
/// model does (the engine then copies that model's estimate).
Imm makeImm(const SbmhtParams& p, double delta, bool roads) {
  const std::array<double, 3> taus{p.stop_time_constant, p.slow_time_constant, p.fast_time_constant};
  std::vector<MotionModel> models = algorithm2Models(p, delta);
  TransitionMatrix pi = transitionMatrix(delta, taus);
  if (!roads) return Imm(std::move(models), std::move(pi));
  MotionModel off_road = constantVelocityModel(delta, p.cv_fast_sigma);
  off_road.kind = MotionKind::road;
  models.push_back(off_road);
  TransitionMatrix off_road_pi = TransitionMatrix::Zero(4, 4);
  off_road_pi.topLeftCorner(3, 3) = pi;
  off_road_pi(3, 1) = 0.5;
  off_road_pi(3, 2) = 0.5;
  return Imm(std::move(models), std::move(off_road_pi));
}

/// Algorithm 1's models on a road segment of direction `heading`: the three of algorithm 2 and the
/// road model of eq. 6, all four switching with p_ii = exp(-delta / tau_i).
Imm makeRoadImm(const SbmhtParams& p, double delta, double heading) {
  const std::array<double, 4> taus{p.stop_time_constant, p.slow_time_constant, p.fast_time_constant,
                                   p.road_time_constant};
  std::vector<MotionModel> models = algorithm2Models(p, delta);
  models.push_back(roadModel(delta, heading, p.road_along_sigma, p.road_across_sigma));
  return Imm(std::move(models), transitionMatrix(delta, taus));
}

/// The history up to and including `tick`'s kTickEnd (the whole history when it ends sooner).
std::span<const std::int32_t> historyThrough(const Leaf& leaf, std::int32_t tick) {
  std::int32_t t = leaf.first_tick;
  for (std::size_t k = 0; k < leaf.history.size(); ++k) {
    if (leaf.history[k] != SbmhtEngine::kTickEnd) continue;
    if (t == tick) return std::span(leaf.history).first(k + 1);
    ++t;
  }
  return leaf.history;
}

}  // namespace

SbmhtEngine::SbmhtEngine(const EngineContext& context)
    : supernode_(context.supernode),
      region_(context.region),
      coverage_(context.coverage),
      terrain_(context.terrain),
      params_(SbmhtParams::fromContext(context)),
      delta_(context.dynamics.delta),
      roads_(params_.use_road_network == 1 && context.terrain && !context.terrain->sections().empty()),
      imm_(makeImm(params_, context.dynamics.delta, roads_)),
      sprt_(SprtThresholds::fromErrorRates(params_.sprt_alpha, params_.sprt_beta, params_.drop_score)),
      initial_score_(initialScore(initialScoreRule(),
                                  params_.detection_probability, params_.false_alarm_density,
                                  params_.birth_density)),
      replay_(&Leaf::tree, &leafOrder) {
  birth_tick_sprt_ = sprt_;
  birth_tick_sprt_.delete_tentative = -std::numeric_limits<double>::infinity();
  // A report rules out the stop model (eq. 9): a new track moves, model unknown.
  initial_probabilities_ = ModeVector::Zero(static_cast<Eigen::Index>(imm_.size()));
  initial_probabilities_(1) = 0.5;
  initial_probabilities_(2) = 0.5;
  if (roads_) {
    for (const auto& section : terrain_->sections()) {
      road_imms_.emplace_back();
      for (std::size_t g = 0; g + 1 < section.points.size(); ++g) {
        const common::Vec2 a = section.points[g];
        const common::Vec2 b = section.points[g + 1];
        road_imms_.back().push_back(makeRoadImm(params_, delta_, std::atan2(b.y - a.y, b.x - a.x)));
      }
    }
  }
  gate_probability_ = 1.0 - std::exp(-params_.gate_chi2 / 2.0);
  for (int m = 0; m < static_cast<int>(gates_.size()); ++m)
    gates_[static_cast<std::size_t>(m)] = gateOfSameProbability(params_.gate_chi2, m);
  // Scans run in sensor-id order; a sensor listed twice would be two scans of one sensor.
  std::sort(coverage_.begin(), coverage_.end(),
            [](const common::SensorCoverage& a, const common::SensorCoverage& b) { return a.sensor < b.sensor; });
  for (std::size_t c = 1; c < coverage_.size(); ++c)
    if (coverage_[c].sensor == coverage_[c - 1].sensor)
      throw std::invalid_argument("sbmht: sensor " + std::to_string(coverage_[c].sensor) + " is listed twice in the coverage");
  for (std::size_t c = 0; c < coverage_.size(); ++c) {
    const common::SensorId id = coverage_[c].sensor;
    if (id >= coverage_of_sensor_.size()) coverage_of_sensor_.resize(id + 1, -1);
    coverage_of_sensor_[id] = static_cast<std::int32_t>(c);
  }
}

// Leaves of one tree agree on all but their last few ticks, so their histories share a prefix as
// long as the track is old; it is skipped in blocks with memcmp (equality only: memcmp's byte order
// is not the order of signed ints).
bool SbmhtEngine::historyLess(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b) {
  constexpr std::size_t kBlock = 64;
  const std::size_t n = std::min(a.size(), b.size());
  std::size_t i = 0;
  while (i + kBlock <= n && std::memcmp(a.data() + i, b.data() + i, kBlock * sizeof(std::int32_t)) == 0) i += kBlock;
  for (; i < n; ++i)
    if (a[i] != b[i]) return a[i] < b[i];
  return a.size() < b.size();
}

const Leaf* SbmhtEngine::representative(const std::vector<Leaf>& leaves, common::TrackId tree) {
  const Leaf* chosen = nullptr;
  for (const auto& leaf : leaves) {
    if (leaf.tree != tree) continue;
    if (leaf.best) return &leaf;
    if (!chosen || leaf.probability > chosen->probability ||
        (leaf.probability == chosen->probability && leaf.score.score > chosen->score.score))
      chosen = &leaf;
  }
  return chosen;
}

std::span<const std::int32_t> Leaf::reportsAt(std::int32_t tick) const {
  std::int32_t t = first_tick;
  std::size_t begin = 0;
  for (std::size_t k = 0; k < history.size(); ++k) {
    if (history[k] != kTickEnd) continue;
    if (t == tick) return std::span(history).subspan(begin, k - begin);
    ++t;
    begin = k + 1;
  }
  // The open entries of the tick whose scans are running.
  if (t == tick) return std::span(history).subspan(begin);
  return {};
}

namespace {

/// Where the last n ticks of a closed history start, or nullopt when it holds fewer ticks.
std::optional<std::size_t> lastTicksStart(const std::vector<std::int32_t>& history, std::size_t n) {
  std::size_t ends = 0;
  for (std::size_t k = history.size(); k-- > 0;) {
    if (history[k] != SbmhtEngine::kTickEnd) continue;
    if (ends == n) return k + 1;
    ++ends;
  }
  if (ends == n) return 0;
  return std::nullopt;
}

}  // namespace

std::vector<SbmhtEngine::Scan> SbmhtEngine::scansOf(std::span<const common::Observation> slot) const {
  std::vector<Scan> scans;
  if (coverage_.empty()) {
    scans.emplace_back();
    for (std::size_t j = 0; j < slot.size(); ++j) scans.back().reports.push_back(j);
    return scans;
  }
  // Every listed sensor is a scan, whether it reported or not: its silence is evidence where it looks.
  for (const auto& sensor : coverage_) scans.push_back(Scan{&sensor, {}});
  Scan unlisted;
  for (std::size_t j = 0; j < slot.size(); ++j) {
    const common::SensorId id = slot[j].sensor;
    if (id < coverage_of_sensor_.size() && coverage_of_sensor_[id] >= 0)
      scans[static_cast<std::size_t>(coverage_of_sensor_[id])].reports.push_back(j);
    else
      unlisted.reports.push_back(j);
  }
  if (!unlisted.reports.empty()) scans.push_back(std::move(unlisted));
  return scans;
}

Detectability SbmhtEngine::detectabilityOf(const Scan& scan, const ImmState& imm) const {
  if (scan.coverage == nullptr) {
    // A sensor the list does not hold, in a field that has one: nothing says where it looks, so
    // its silence is no evidence anywhere (Pe = 0); its reports still update and start tracks.
    if (!coverage_.empty())
      return Detectability{params_.detection_probability,
                           ModeVector::Zero(static_cast<Eigen::Index>(imm.modes.size()))};
    return Detectability::uniform(params_.detection_probability);
  }
  const common::SensorCoverage& sensor = *scan.coverage;
  Detectability d;
  d.detection_probability = sensor.detection_probability * params_.delivery_probability;
  d.perceivability = ModeVector(static_cast<Eigen::Index>(imm.modes.size()));
  for (std::size_t i = 0; i < imm.modes.size(); ++i) {
    const auto& x = imm.modes[i].x;
    // Pe of eq. 15 is 1 or 0: the sector and the masks are sharp.
    d.perceivability(static_cast<Eigen::Index>(i)) =
        common::detectionProbabilityAt(sensor, {x(kX), x(kY)}, terrain_.get()) > 0.0 ? 1.0 : 0.0;
  }
  return d;
}

void SbmhtEngine::runScan(std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot,
                          const std::vector<ReportTerms>& terms, const Scan& scan, std::vector<char>& gated) const {
  std::vector<Leaf> next;
  next.reserve(leaves.size() * 2 + scan.reports.size());
  for (Leaf& leaf : leaves) {
    const Detectability detectability = detectabilityOf(scan, leaf.imm);
    // Whether the sensor could have seen it: some moving model's prediction is in sight (the stop
    // model's Lambda^0 is 1 whatever its Pe, so its silence there is no evidence).
    bool perceivable = detectability.perceivability.size() == 0;
    for (std::size_t i = 0; i < imm_.size() && !perceivable; ++i)
      perceivable = imm_.models()[i].moving() && detectability.perceivabilityOf(i) > 0.0;
    leaf.perceivable = leaf.perceivable || perceivable;
    const SprtThresholds& sprt = leaf.born_this_tick ? birth_tick_sprt_ : sprt_;
    // A sensor that could not have seen the target and reported nothing leaves the leaf as it is.
    if (!perceivable && scan.reports.empty()) {
      next.push_back(std::move(leaf));
      continue;
    }
    // The time update ran at the tick's start: each scan updates the estimate in place.
    const ImmPrediction prediction{leaf.imm.modes, leaf.imm.probabilities};
    // A report proves the sensor could see the target (Pe = 1 where the report puts it), though a
    // lagging prediction may still lie behind the mask it came out of: Pe weighs misses only.
    const Detectability seen = Detectability::uniform(detectability.detection_probability);
    for (const std::size_t j : scan.reports) {
      const ReportTerms& t = terms[j];
      if (!t.usable) continue;
      if (t.position) {
        // d^2 >= |nu|^2 / trace(S) for each moving model: skip the EKFs of a report far from all.
        const double r_trace = t.R(0, 0) + t.R(1, 1);
        bool near = false;
        for (std::size_t i = 0; i < imm_.size() && !near; ++i) {
          if (!imm_.models()[i].moving()) continue;
          const auto& m = prediction.modes[i];
          const double dx = t.z(0) - m.x(kX);
          const double dy = t.z(1) - m.x(kY);
          near = dx * dx + dy * dy <= t.gate * (m.P(kX, kX) + m.P(kY, kY) + r_trace);
        }
        if (!near) continue;
      }
      ImmUpdate hit = imm_.report(prediction, t.model, t.z, t.R, seen);
      if (!(hit.likelihood > 0.0) || !(hit.gate_distance <= t.gate)) continue;
      if (t.model.kind == common::MeasurementKind::bearing && scan.coverage != nullptr &&
          scan.coverage->range > 0.0 && !constrainToSensorReach(hit, *scan.coverage))
        continue;
      // Eqs. 19 and 23: a report whose class the track cannot be (c'beta = 0, Delta L^c = -inf)
      // is not this track's, whatever its kinematics, and makes no branch.
      std::optional<common::ClassUpdate> classified;
      if (!t.classes.empty()) {
        classified = common::updateClassVector(leaf.classes, t.classes);
        if (std::isinf(classified->score_increment) && classified->score_increment < 0.0) continue;
      }
      Leaf child;
      child.tree = leaf.tree;
      child.first_tick = leaf.first_tick;
      child.history = leaf.history;
      child.history.push_back(static_cast<std::int32_t>(j));
      gated[j] = 1;
      child.imm = std::move(hit.state);
      child.road_section = leaf.road_section;
      projectRoadMode(child, true);
      // Eqs. 21-22: L = L + Delta L + Delta L^c (Delta L^c = 0 for a report without c).
      const double class_increment = classified ? classified->score_increment : 0.0;
      child.score = leaf.score.after(reportScoreIncrement(hit.likelihood, t.clutter_density) + class_increment, sprt);
      child.classes = classified ? ClassVector(classified->beta) : leaf.classes;
      child.last_seen_tick = tick;
      // Ticks with a report, as confirm_reports and max_misses count them: k sensors that see the
      // target in one tick are one tick of evidence for the count (their scores all add).
      child.hits = leaf.last_seen_tick == tick ? leaf.hits : leaf.hits + 1;
      child.born_this_tick = leaf.born_this_tick;
      confirmByCount(child);
      child.misses = leaf.misses;
      child.unseen_ticks = leaf.unseen_ticks;
      child.perceivable = true;
      if (child.score.status != TrackStatus::deleted) next.push_back(std::move(child));
    }
    // The miss branch last: the leaf itself becomes it. Where the sensor could not see it the miss
    // is no evidence (Lambda = 1) and the leaf stays exactly as it was.
    if (perceivable) {
      // A target that was detected but whose report fell outside the gate looks like a miss too:
      // the miss has probability 1 - PD P_G (Blackman and Popoli), so even a sensor of PD 1 leaves
      // a track alive after a report in the gate's 1 - P_G tail.
      Detectability missed = detectability;
      missed.detection_probability *= gate_probability_;
      ImmUpdate miss = imm_.miss(prediction, missed);
      leaf.imm = std::move(miss.state);
      leaf.score = leaf.score.after(missScoreIncrement(miss.likelihood), sprt);
    }
    if (leaf.score.status != TrackStatus::deleted) next.push_back(std::move(leaf));
  }

  // A report that locates a target (not a bearing) also starts a new tentative tree there, at
  // rest but for a radar's range rate: every such report of a sensor that no existing leaf gated
  // (a target no track explains), or, when the leaves gated all of them, the sensor's first (a
  // new target may cross a track). A radar or camera that sees several new targets in one tick
  // starts them all at once, up to kMaxBirthsPerSensorTick; the birth id's index tells them apart.
  // A presence sensor's report places the target at the sensor and says nothing of its motion: a
  // tree started there at rest would stay at the sensor after the target left, its silence
  // explained by the stop model. ONERA's volume reports update tracks only.
  const bool starts_trees = scan.coverage == nullptr || !scan.coverage->presence;
  std::map<common::SensorId, std::vector<std::size_t>> fixes_of_sensor;
  for (const std::size_t j : scan.reports) {
    if (!starts_trees) break;
    if (terms[j].usable && terms[j].fix) fixes_of_sensor[slot[j].sensor].push_back(j);
  }
  std::vector<std::pair<std::size_t, std::uint32_t>> births;  // (report, its index among the sensor's births)
  for (const auto& [sensor, fixes] : fixes_of_sensor) {
    std::uint32_t index = 0;
    for (const std::size_t j : fixes)
      if (!gated[j] && index < common::track_id::kMaxBirthsPerSensorTick) births.emplace_back(j, index++);
    if (index == 0) births.emplace_back(fixes.front(), 0);
  }
  std::sort(births.begin(), births.end());  // canonical order, as the slot
  for (const auto& [j, index] : births) {
    const PositionFix& fix = *terms[j].fix;
    const common::TrackId id = common::track_id::birth(supernode_, tick, slot[j].sensor, index);
    // A handed-over tree may already carry this id.
    if (std::any_of(next.begin(), next.end(), [&](const Leaf& l) { return l.tree == id; })) continue;
    // eq. 20: its class vector from the report's c, uniform without one.
    next.push_back(newTree(id, tick, {static_cast<std::int32_t>(j)}, fix, initial_score_,
                           ClassVector(common::initialClassVector(terms[j].classes))));
  }
  std::sort(next.begin(), next.end(), leafOrder);
  leaves = std::move(next);
}

SbmhtEngine::Leaf SbmhtEngine::newTree(common::TrackId id, std::int32_t tick, std::vector<std::int32_t> reports,
                                       const PositionFix& fix, double score, const ClassVector& classes) const {
  GaussianState start;
  start.x << fix.position(0), fix.position(1), 0.0, 0.0;
  start.P.setZero();
  start.P.topLeftCorner<2, 2>() = fix.covariance;
  const double v2 = params_.initial_velocity_sigma * params_.initial_velocity_sigma;
  Eigen::Matrix2d velocity = Eigen::Matrix2d::Identity() * v2;
  if (fix.line_of_sight) {
    // The radar measured the speed along u: v = rho_dot u, with the prior left across it.
    const Eigen::Vector2d& u = *fix.line_of_sight;
    start.x.segment<2>(kVx) = fix.range_rate * u;
    velocity = v2 * (Eigen::Matrix2d::Identity() - u * u.transpose()) + fix.range_rate_variance * u * u.transpose();
  }
  start.P.block<2, 2>(kVx, kVx) = velocity;
  Leaf leaf;
  leaf.tree = id;
  leaf.first_tick = tick;
  leaf.history = std::move(reports);
  leaf.imm = ImmState::startAt(start, initial_probabilities_);
  leaf.score = TrackScore::start(score);
  leaf.classes = classes;
  leaf.last_seen_tick = tick;
  leaf.hits = 1;
  leaf.born_this_tick = true;
  confirmByCount(leaf);
  return leaf;
}

void SbmhtEngine::startBearingPairTrees(std::vector<Leaf>& leaves, std::int32_t tick,
                                        std::span<const common::Observation> slot,
                                        const std::vector<ReportTerms>& terms, const Scan& scan,
                                        const std::vector<char>& gated, std::vector<FreeBearing>& earlier) const {
  // This scan's bearings that no leaf took, from a listed sensor that starts trees (alone a bearing starts none).
  const common::SensorCoverage* sensor = scan.coverage;
  if (sensor == nullptr || sensor->presence) return;
  std::vector<std::size_t> latest;
  for (const std::size_t j : scan.reports)
    if (terms[j].usable && terms[j].model.kind == common::MeasurementKind::bearing && !gated[j]) latest.push_back(j);
  if (latest.empty()) return;
  const common::SensorCoverage& sensor_b = *sensor;
  std::vector<Leaf> born;
  std::uint32_t index = 0;  // births named after this scan's sensor, which starts no tree alone
  for (const auto& [a, sensor_of_a] : earlier) {
    if (index >= common::track_id::kMaxBirthsPerSensorTick) break;
    const common::SensorCoverage& sensor_a = *sensor_of_a;
    for (const std::size_t b : latest) {
      if (index >= common::track_id::kMaxBirthsPerSensorTick) break;
      const ReportTerms& ta = terms[a];
      const ReportTerms& tb = terms[b];
      const auto pair = bearingPairFix(ta.model, ta.z, ta.R, tb.model, tb.z, tb.R, kMinBearingCrossingSine);
      if (!pair) continue;
      // Both sensors must be able to see a target there: in range, field of view and sight.
      const common::Vec2 at{pair->fix.position(0), pair->fix.position(1)};
      if (!(common::detectionProbabilityAt(sensor_a, at, terrain_.get()) > 0.0) ||
          !(common::detectionProbabilityAt(sensor_b, at, terrain_.get()) > 0.0))
        continue;
      // Eq. 20 from a's c, then eq. 19 with b's: a pair whose classes exclude each other is no target.
      ClassVector classes(common::initialClassVector(ta.classes));
      double class_increment = 0.0;
      if (!tb.classes.empty()) {
        const common::ClassUpdate update = common::updateClassVector(classes, tb.classes);
        if (std::isinf(update.score_increment) && update.score_increment < 0.0) continue;
        classes = ClassVector(update.beta);
        class_increment = update.score_increment;
      }
      // The pair's likelihood ratio: a new target (density lambda_nt over the field, seen and
      // delivered by both) against two false bearings, lambda_a lambda_b per rad^2, that is
      // lambda_a lambda_b |det J| per m^2 in the field. The initial-score rule then applies as to
      // any fix. Two reports' evidence: it starts well above a one-report birth.
      const double pd = sensor_a.detection_probability * sensor_b.detection_probability *
                        params_.delivery_probability * params_.delivery_probability;
      const double clutter = ta.clutter_density * tb.clutter_density * pair->jacobian_determinant;
      const double score =
          initialScore(initialScoreRule(), pd, clutter, params_.birth_density) +
          class_increment;
      const common::TrackId id = common::track_id::birth(supernode_, tick, slot[b].sensor, index++);
      if (std::any_of(leaves.begin(), leaves.end(), [&](const Leaf& l) { return l.tree == id; })) continue;
      // a's scan ran first: its entry comes first, as in a leaf that took both through the scans.
      born.push_back(newTree(id, tick, {static_cast<std::int32_t>(a), static_cast<std::int32_t>(b)}, pair->fix,
                             score, classes));
    }
  }
  for (const std::size_t b : latest) earlier.push_back({b, sensor});
  if (born.empty()) return;
  for (Leaf& leaf : born) leaves.push_back(std::move(leaf));
  std::sort(leaves.begin(), leaves.end(), leafOrder);
}

void SbmhtEngine::endTick(std::vector<Leaf>& leaves, std::int32_t tick) const {
  // Without coverage every tick is a scan of the whole field at PD, and a run of max_misses misses
  // is rarer than 1 % (derived). With coverage a miss is weighed where it happens, and a stopped
  // target (below every sensor's minimum speed) is expected to be silent: the stop model explains
  // its misses and T_drop ends its track (§2 of docs/ONERA.md, about 136 silent ticks), as the
  // paper's does; only a leaf no sensor could see is ended by a count, max_coast_ticks.
  std::vector<char> keep(leaves.size(), 1);
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    Leaf& leaf = leaves[k];
    leaf.history.push_back(kTickEnd);
    leaf.born_this_tick = false;
    if (leaf.last_seen_tick == tick) {
      leaf.misses = 0;
      leaf.unseen_ticks = 0;
      continue;
    }
    ++leaf.misses;
    leaf.unseen_ticks = leaf.perceivable ? 0 : leaf.unseen_ticks + 1;
    const GaussianState c = leaf.imm.combined();
    const bool too_many =
        coverage_.empty() ? leaf.misses >= params_.max_misses : leaf.unseen_ticks >= params_.max_coast_ticks;
    // A leaf that coasted out of the region followed a target that left: no sensor sees it again.
    if (too_many || !region_.contains({c.x(kX), c.x(kY)})) keep[k] = 0;
  }
  keepMarked(leaves, keep);
}

void SbmhtEngine::mergeDuplicates(std::vector<Leaf>& leaves) const {
  const auto n = static_cast<std::size_t>(params_.n_scan);
  if (n < 1) return;
  struct Candidate {
    std::size_t leaf;
    std::size_t tail;  // where its last n ticks start in its history
  };
  std::vector<Candidate> candidates;
  const auto tail = [&](const Candidate& c) { return std::span(leaves[c.leaf].history).subspan(c.tail); };
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    const auto start = lastTicksStart(leaves[k].history, n);
    if (!start) continue;
    // Only leaves that took a report at each of those ticks: no tick entry is kTickEnd alone.
    const auto last = std::span(leaves[k].history).subspan(*start);
    bool every_tick = true;
    for (std::size_t e = 0; e < last.size() && every_tick; ++e)
      every_tick = last[e] != kTickEnd || (e > 0 && last[e - 1] != kTickEnd);
    if (every_tick) candidates.push_back({k, *start});
  }
  std::sort(candidates.begin(), candidates.end(), [&](const Candidate& a, const Candidate& b) {
    const auto ta = tail(a);
    const auto tb = tail(b);
    if (!std::equal(ta.begin(), ta.end(), tb.begin(), tb.end()))
      return std::lexicographical_compare(ta.begin(), ta.end(), tb.begin(), tb.end());
    if (leaves[a.leaf].score.score != leaves[b.leaf].score.score)
      return leaves[a.leaf].score.score > leaves[b.leaf].score.score;
    return leafOrder(leaves[a.leaf], leaves[b.leaf]);
  });
  std::vector<char> keep(leaves.size(), 1);
  for (std::size_t c = 1; c < candidates.size(); ++c) {
    const auto prev = tail(candidates[c - 1]);
    const auto here = tail(candidates[c]);
    if (std::equal(prev.begin(), prev.end(), here.begin(), here.end())) keep[candidates[c].leaf] = 0;
  }
  keepMarked(leaves, keep);
}

void SbmhtEngine::timeUpdate(Leaf& leaf) const {
  const Imm* imm = &imm_;
  leaf.road_section = -1;
  if (roads_) {
    // The section is chosen where the target will be: the combined estimate one tick ahead.
    const GaussianState c = leaf.imm.combined();
    const common::Vec2 ahead{c.x(kX) + delta_ * c.x(kVx), c.x(kY) + delta_ * c.x(kVy)};
    const auto near = terrain_->project(ahead);
    // Past a dead end the target has left the road, however near its end it still is.
    if (near && !near->past_dead_end && near->distance <= params_.road_gate_distance) {
      leaf.road_section = static_cast<std::int32_t>(near->section);
      imm = &road_imms_[near->section][near->segment];
    }
  }
  ImmPrediction p = imm->predict(leaf.imm);
  leaf.imm.modes = std::move(p.modes);
  leaf.imm.probabilities = std::move(p.probabilities);
  if (!roads_) return;
  if (leaf.road_section < 0)
    // Off road the road model holds no probability; a copy of a moving model's estimate keeps its
    // gate and its Pe where the other models' are, rather than wherever it left the road.
    leaf.imm.modes[kRoadMode] = leaf.imm.modes[kFastMode];
  else
    // The prediction's mean follows the road round a bend; its covariance keeps eq. 6's
    // across-road noise until a report's update is projected.
    projectRoadMode(leaf, false);
}

void SbmhtEngine::projectRoadMode(Leaf& leaf, bool with_covariance) const {
  if (!roads_ || leaf.road_section < 0) return;
  GaussianState& mode = leaf.imm.modes[kRoadMode];
  const auto& section = terrain_->sections()[static_cast<std::size_t>(leaf.road_section)];
  const auto foot = common::footPoint(section.points, {mode.x(kX), mode.x(kY)});
  if (!foot) return;
  mode = with_covariance ? projectOntoRoad(mode, *foot, params_.road_location_sigma) : moveOntoRoad(mode, *foot);
}

void SbmhtEngine::processTick(std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot) {
  const double r2 = params_.measurement_sigma * params_.measurement_sigma;
  std::vector<ReportTerms> terms;
  terms.reserve(slot.size());
  for (const auto& o : slot) {
    terms.push_back(termsOf(o, r2, params_.false_alarm_density, gates_));
    if (!terms.back().usable) ++unusable_reports_;
  }

  // The time update, once per tick: mixing and each model's prediction (mu becomes cbar).
  for (Leaf& leaf : leaves) {
    leaf.perceivable = false;
    timeUpdate(leaf);
  }

  const std::vector<Scan> scans = scansOf(slot);
  std::vector<char> gated(slot.size(), 0);  // a report some leaf took in its scan
  std::vector<FreeBearing> free_bearings;   // of the scans so far, for pair births
  for (std::size_t s = 0; s < scans.size(); ++s) {
    runScan(leaves, tick, slot, terms, scans[s], gated);
    // A pair tree started here meets the later sensors' scans of the tick: a third bearing of its
    // target joins it rather than pairing anew, and a sensor that could see it and did not weighs it.
    if (params_.bearing_pair_births == 1) startBearingPairTrees(leaves, tick, slot, terms, scans[s], gated, free_bearings);
    // Between one sensor's scan and the next, the hypotheses the reports made unlikely go, or the
    // leaves would multiply by two per sensor that saw the target.
    if (s + 1 < scans.size() && !scans[s].reports.empty()) manageHypotheses(leaves, tick, false);
  }
  endTick(leaves, tick);
  mergeDuplicates(leaves);
  std::sort(leaves.begin(), leaves.end(), leafOrder);
  manageHypotheses(leaves, tick, true);
}

void SbmhtEngine::manageHypotheses(std::vector<Leaf>& leaves, std::int32_t tick, bool n_scan_pruning) {
  const std::size_t count = leaves.size();
  if (count == 0) return;

  // Clusters: a tree's leaves exclude one another, and so do leaves that share a report.
  std::vector<std::size_t> parent(count);
  for (std::size_t k = 0; k < count; ++k) parent[k] = k;
  for (std::size_t k = 1; k < count; ++k)
    if (leaves[k].tree == leaves[k - 1].tree) unite(parent, k, k - 1);
  // Each report (tick, index) any leaf took: the first leaf that took it, found by a table per
  // tick rather than a sort of every entry, which cost more than the rest of the engine. Only a
  // report taken by leaves of two trees can conflict in the search (one tree contributes one leaf),
  // so only those get a compact id; the search depends on which reports conflict, not on their ids.
  std::int32_t first_tick = leaves.front().first_tick;
  for (const auto& leaf : leaves) first_tick = std::min(first_tick, leaf.first_tick);
  constexpr int kNone = -1;
  struct Taken {
    int first_leaf = kNone;
    bool shared = false;  ///< by leaves of two trees
    int id = kNone;       ///< compact id, set when shared
  };
  std::vector<std::vector<Taken>> taken;  // by tick - first_tick, then report index
  const auto forEachReport = [&](std::size_t k, auto&& visit) {
    std::int32_t t = leaves[k].first_tick;
    for (const std::int32_t e : leaves[k].history) {
      if (e == SbmhtEngine::kTickEnd) {
        ++t;
        continue;
      }
      const auto row = static_cast<std::size_t>(t - first_tick);
      if (row >= taken.size()) taken.resize(row + 1);
      if (static_cast<std::size_t>(e) >= taken[row].size()) taken[row].resize(static_cast<std::size_t>(e) + 1);
      visit(taken[row][static_cast<std::size_t>(e)]);
    }
  };
  for (std::size_t k = 0; k < count; ++k)
    forEachReport(k, [&](Taken& slot) {
      if (slot.first_leaf == kNone) {
        slot.first_leaf = static_cast<int>(k);
        return;
      }
      unite(parent, static_cast<std::size_t>(slot.first_leaf), k);
      if (leaves[static_cast<std::size_t>(slot.first_leaf)].tree != leaves[k].tree) slot.shared = true;
    });
  std::vector<std::vector<int>> reports(count);  // each leaf's reports shared with another tree, as compact ids
  int report_count_int = 0;
  for (std::size_t k = 0; k < count; ++k)
    forEachReport(k, [&](Taken& slot) {
      if (!slot.shared) return;
      if (slot.id == kNone) slot.id = report_count_int++;
      reports[k].push_back(slot.id);
    });
  const auto report_count = static_cast<std::size_t>(report_count_int);

  std::vector<std::vector<std::size_t>> clusters(count);
  for (std::size_t k = 0; k < count; ++k) clusters[findRoot(parent, k)].push_back(k);

  std::vector<double> scores(count);
  for (std::size_t k = 0; k < count; ++k) {
    scores[k] = leaves[k].score.score;
    leaves[k].probability = 0.0;
    leaves[k].best = false;
  }
  for (const auto& members : clusters) {
    if (members.empty()) continue;
    // Trees in order, each tree's leaves by score (ties: leaf order): the search tries good options first.
    std::vector<std::vector<int>> options;
    for (std::size_t m = 0; m < members.size(); ++m) {
      if (m == 0 || leaves[members[m]].tree != leaves[members[m - 1]].tree) options.emplace_back();
      options.back().push_back(static_cast<int>(members[m]));
    }
    for (auto& tree : options)
      std::stable_sort(tree.begin(), tree.end(), [&](int a, int b) {
        return scores[static_cast<std::size_t>(a)] > scores[static_cast<std::size_t>(b)];
      });
    HypothesisSearch search(options, scores, reports, report_count, static_cast<std::size_t>(params_.hypotheses));
    search.run();
    if (search.truncated()) ++truncated_searches_;
    const auto& found = search.results();
    if (found.empty()) continue;
    // P(T) = sum over the k best H containing T of e^{L_H}, normalised.
    double total = 0.0;
    for (const auto& h : found) total += std::exp(h.score - found.front().score);
    for (const auto& h : found) {
      const double weight = std::exp(h.score - found.front().score) / total;
      for (int leaf : h.chosen)
        if (leaf >= 0) leaves[static_cast<std::size_t>(leaf)].probability += weight;
    }
    for (int leaf : found.front().chosen)
      if (leaf >= 0) leaves[static_cast<std::size_t>(leaf)].best = true;
  }

  // Hypothesis pruning (P(T) below 1e-3), then N-scan pruning: a tree keeps the branches that agree,
  // through the tick N scans back, with its leaf in the best hypothesis (or its most probable leaf
  // when it has none). Algorithm 1 also keeps, of the branches that do not, the best-scoring one on
  // each other road section, up to road_sections_kept sections a tree (Pannetier et al., Fig. 2
  // step 5): branches that took different reports near a junction and so follow different roads
  // both stay until the reports decide (C7). A leaf is not split per road: its road model follows
  // the section nearest its prediction.
  std::erase_if(leaves, [](const Leaf& l) { return !l.best && l.probability < kMinTrackProbability; });
  if (!n_scan_pruning) return;
  std::vector<char> keep(leaves.size(), 1);
  for (std::size_t begin = 0; begin < leaves.size();) {
    std::size_t end = begin;
    while (end < leaves.size() && leaves[end].tree == leaves[begin].tree) ++end;
    std::size_t ref = begin;
    for (std::size_t k = begin; k < end; ++k) {
      if (leaves[k].best) {
        ref = k;
        break;
      }
      if (leaves[k].probability > leaves[ref].probability ||
          (leaves[k].probability == leaves[ref].probability && leaves[k].score.score > leaves[ref].score.score))
        ref = k;
    }
    const std::int32_t back = tick - params_.n_scan;
    if (back >= leaves[ref].first_tick) {
      const auto agreed = historyThrough(leaves[ref], back);
      for (std::size_t k = begin; k < end; ++k) {
        const auto here = historyThrough(leaves[k], back);
        keep[k] = std::equal(here.begin(), here.end(), agreed.begin(), agreed.end());
      }
      if (roads_) keepOtherSections(leaves, begin, end, keep);
    }
    begin = end;
  }
  keepMarked(leaves, keep);
}

void SbmhtEngine::keepOtherSections(const std::vector<Leaf>& leaves, std::size_t begin, std::size_t end,
                                    std::vector<char>& keep) const {
  std::vector<std::int32_t> sections;  // the sections the tree keeps a branch on
  for (std::size_t k = begin; k < end; ++k)
    if (keep[k] && leaves[k].road_section >= 0) sections.push_back(leaves[k].road_section);
  std::vector<std::size_t> others;
  for (std::size_t k = begin; k < end; ++k)
    if (!keep[k] && leaves[k].road_section >= 0) others.push_back(k);
  std::stable_sort(others.begin(), others.end(), [&](std::size_t a, std::size_t b) {
    return leaves[a].score.score > leaves[b].score.score;
  });
  // The agreeing branches count as the sections they are on, and as one when they are off road.
  std::sort(sections.begin(), sections.end());
  sections.erase(std::unique(sections.begin(), sections.end()), sections.end());
  std::size_t kept = std::max<std::size_t>(1, sections.size());
  for (const std::size_t k : others) {
    if (kept >= static_cast<std::size_t>(params_.road_sections_kept)) break;
    if (std::find(sections.begin(), sections.end(), leaves[k].road_section) != sections.end()) continue;
    keep[k] = 1;
    sections.push_back(leaves[k].road_section);
    ++kept;
  }
}

void SbmhtEngine::confirmByCount(Leaf& leaf) const {
  if (leaf.score.status == TrackStatus::tentative && leaf.hits >= params_.confirm_reports)
    leaf.score.status = TrackStatus::confirmed;
}

void SbmhtEngine::catchUp(Leaf& leaf, std::int32_t first_tick, std::int32_t anchor_tick) const {
  for (std::int32_t t = first_tick; t <= anchor_tick; ++t) timeUpdate(leaf);
  leaf.first_tick = anchor_tick + 1;
}

void SbmhtEngine::step(const ObservationWindow& window) {
  std::optional<ObservationWindow> merged;
  // With coverage each sensor is a scan of its own: merging two sensors' reports into one would
  // leave the other sensor silent where it saw the target.
  if (params_.merge_radius > 0.0 && coverage_.empty()) merged = window.merged(params_.merge_radius);
  replay_.step(
      merged ? *merged : window,
      [this](std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot) {
        processTick(leaves, tick, slot);
      },
      [this](Leaf& leaf, std::int32_t first_tick, std::int32_t anchor_tick) { catchUp(leaf, first_tick, anchor_tick); });
}

void SbmhtEngine::adopt(const common::TrackHandoff& handoff) {
  GaussianState state;
  state.x = common::StateVector(handoff.state.data());
  state.P = common::fromRowMajor(handoff.covariance);
  state.P = 0.5 * (state.P + state.P.transpose());
  if (!state.x.allFinite() || !state.P.allFinite()) {
    ++rejected_handoffs_;
    return;
  }
  Leaf leaf;
  leaf.tree = handoff.track;
  leaf.first_tick = handoff.last_tick + 1;
  leaf.imm = ImmState::startAt(state, initial_probabilities_);
  // The class evidence travels with the track; a handoff without a usable class vector (another
  // engine's, or malformed) starts from no evidence rather than being refused.
  if (auto beta = common::receivedClassVector(handoff.class_probabilities)) leaf.classes = std::move(*beta);
  // A confirmed track arrives confirmed, T_drop above the confirmation threshold; a tentative one
  // starts over at L(1).
  if (handoff.confirmed) {
    const double high = sprt_.confirm + sprt_.drop_confirmed;
    leaf.score = TrackScore{high, high, TrackStatus::confirmed};
  } else {
    leaf.score = TrackScore::start(initial_score_);
  }
  leaf.hits = handoff.hits;
  leaf.misses = handoff.misses;
  leaf.last_seen_tick = handoff.last_tick - handoff.misses;
  replay_.adopt(handoff.last_tick + 1, std::move(leaf));
}

std::vector<common::TrackEstimate> SbmhtEngine::confirmedTracks() const {
  std::vector<common::TrackEstimate> out;
  for (const auto& leaf : replay_.current()) {
    if (!leaf.best || leaf.score.status != TrackStatus::confirmed) continue;
    const GaussianState s = leaf.imm.combined();
    out.push_back({leaf.tree, s.x(kX), s.x(kY), s.x(kVx), s.x(kVy), common::toRowMajor(s.P), leaf.last_seen_tick,
                   {leaf.classes.begin(), leaf.classes.end()},
                   leaf.imm.probabilities(static_cast<Eigen::Index>(kStopMode))});
  }
  return out;
}

std::vector<TrackClass> SbmhtEngine::confirmedClasses() const {
  std::vector<TrackClass> out;
  for (const auto& track : confirmedTracks()) {
    const common::DeclaredClass declared = common::declaredTrackClass(track.class_probabilities);
    out.push_back({track.track, declared.target_class, declared.probability});
  }
  return out;
}

std::vector<TrackPrediction> SbmhtEngine::predictions() const {
  std::vector<TrackPrediction> out;
  const std::vector<Leaf>& leaves = replay_.current();
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    if (k > 0 && leaves[k].tree == leaves[k - 1].tree) continue;
    const Leaf* leaf = representative(leaves, leaves[k].tree);
    const GaussianState s = leaf->imm.combined();
    out.push_back({leaf->tree, {s.x(kX) + delta_ * s.x(kVx), s.x(kY) + delta_ * s.x(kVy)}});
  }
  return out;
}

common::TrackHandoff SbmhtEngine::release(common::TrackId track_id, std::uint32_t to_supernode) {
  const Leaf* leaf = representative(replay_.current(), track_id);
  if (!leaf) throw std::invalid_argument("sbmht: release of unknown track " + std::to_string(track_id));
  const GaussianState s = leaf->imm.combined();
  common::TrackHandoff handoff;
  handoff.track = track_id;
  handoff.to_supernode = to_supernode;
  handoff.last_tick = replay_.currentTick();
  for (int r = 0; r < common::kStateDim; ++r) handoff.state[static_cast<std::size_t>(r)] = s.x(r);
  handoff.covariance = common::toRowMajor(s.P);
  handoff.hits = leaf->hits;
  handoff.misses = leaf->misses;
  handoff.confirmed = leaf->score.status == TrackStatus::confirmed;
  handoff.class_probabilities.assign(leaf->classes.begin(), leaf->classes.end());
  replay_.release(track_id);
  return handoff;
}

}  // namespace wsn::supernode::sbmht

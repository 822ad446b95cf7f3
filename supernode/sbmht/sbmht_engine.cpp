#include "supernode/sbmht/sbmht_engine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/terrain.hpp"
#include "supernode/sbmht/hypotheses.hpp"
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

}  // namespace

EngineSpec engineSpec() {
  EngineSpec spec;
  spec.name = "sbmht";
  spec.description =
      "ONERA structured-branching MHT (Pannetier et al. 2014): IMM (stop, two CV models and, near the "
      "scenario's roads, a road model), track trees with a "
      "miss branch, LLR scores and SPRT, k best hypotheses per cluster, N-scan pruning; replays the window";
  spec.params = common::paramSpecs(paramTable(), paramDerivations());
  spec.create = [](const EngineContext& context) -> std::unique_ptr<Engine> {
    return std::make_unique<SbmhtEngine>(context);
  };
  // Presence and signal strength have no h(x) a filter can use (measurement_models.hpp).
  spec.accepts = {"position", "bearing", "range_bearing_rate", "azimuth_elevation"};
  return spec;
}

SbmhtEngine::SbmhtEngine(const EngineContext& context)
    : region_(context.region),
      coverage_(context.coverage),
      terrain_(context.terrain),
      params_(SbmhtParams::fromContext(context)),
      delta_(context.dynamics.delta),
      roads_(params_.use_road_network == 1 && context.terrain && !context.terrain->sections().empty()),
      imm_(makeImm(params_, context.dynamics.delta, roads_)),
      sprt_(SprtThresholds::fromErrorRates(params_.sprt_alpha, params_.sprt_beta, params_.drop_score)),
      births_(context.supernode, params_, imm_.size(), context.terrain) {
  birth_tick_sprt_ = sprt_;
  birth_tick_sprt_.delete_tentative = -std::numeric_limits<double>::infinity();
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

bool SbmhtEngine::perceivable(const Detectability& detectability) const {
  bool seen = detectability.perceivability.size() == 0;
  for (std::size_t i = 0; i < imm_.size() && !seen; ++i)
    seen = imm_.models()[i].moving() && detectability.perceivabilityOf(i) > 0.0;
  return seen;
}

std::optional<ImmUpdate> SbmhtEngine::gatedUpdate(const ImmPrediction& prediction, const ReportTerms& t,
                                                  const Scan& scan, const Detectability& seen) const {
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
    if (!near) return std::nullopt;
  }
  ImmUpdate hit = imm_.report(prediction, t.model, t.z, t.R, seen);
  if (!(hit.likelihood > 0.0) || !(hit.gate_distance <= t.gate)) return std::nullopt;
  if (t.model.kind == common::MeasurementKind::bearing && scan.coverage != nullptr && scan.coverage->range > 0.0 &&
      !constrainToSensorReach(hit, *scan.coverage))
    return std::nullopt;
  return hit;
}

Leaf SbmhtEngine::reportBranch(const Leaf& leaf, std::int32_t tick, std::size_t report, ImmUpdate hit,
                               const ReportTerms& t, const std::optional<common::ClassUpdate>& classified,
                               const SprtThresholds& sprt) const {
  Leaf child;
  child.tree = leaf.tree;
  child.first_tick = leaf.first_tick;
  child.history = leaf.history;
  child.history.push_back(static_cast<std::int32_t>(report));
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
  confirmByCount(child, params_.confirm_reports);
  child.misses = leaf.misses;
  child.unseen_ticks = leaf.unseen_ticks;
  child.perceivable = true;
  return child;
}

void SbmhtEngine::branchLeaf(Leaf& leaf, std::int32_t tick, const std::vector<ReportTerms>& terms, const Scan& scan,
                             std::vector<char>& gated, std::vector<Leaf>& next) const {
  const Detectability detectability = detectabilityOf(scan, leaf.imm);
  const bool could_see = perceivable(detectability);
  leaf.perceivable = leaf.perceivable || could_see;
  const SprtThresholds& sprt = leaf.born_this_tick ? birth_tick_sprt_ : sprt_;
  // A sensor that could not have seen the target and reported nothing leaves the leaf as it is.
  if (!could_see && scan.reports.empty()) {
    next.push_back(std::move(leaf));
    return;
  }
  // The time update ran at the tick's start: each scan updates the estimate in place.
  const ImmPrediction prediction{leaf.imm.modes, leaf.imm.probabilities};
  // A report proves the sensor could see the target (Pe = 1 where the report puts it), though a
  // lagging prediction may still lie behind the mask it came out of: Pe weighs misses only.
  const Detectability seen = Detectability::uniform(detectability.detection_probability);
  for (const std::size_t j : scan.reports) {
    const ReportTerms& t = terms[j];
    if (!t.usable) continue;
    std::optional<ImmUpdate> hit = gatedUpdate(prediction, t, scan, seen);
    if (!hit) continue;
    // Eqs. 19 and 23: a report whose class the track cannot be (c'beta = 0, Delta L^c = -inf)
    // is not this track's, whatever its kinematics, and makes no branch.
    std::optional<common::ClassUpdate> classified;
    if (!t.classes.empty()) {
      classified = common::updateClassVector(leaf.classes, t.classes);
      if (std::isinf(classified->score_increment) && classified->score_increment < 0.0) continue;
    }
    gated[j] = 1;
    Leaf child = reportBranch(leaf, tick, j, std::move(*hit), t, classified, sprt);
    if (child.score.status != TrackStatus::deleted) next.push_back(std::move(child));
  }
  // The miss branch last: the leaf itself becomes it. Where the sensor could not see it the miss
  // is no evidence (Lambda = 1) and the leaf stays exactly as it was.
  if (could_see) {
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

void SbmhtEngine::runScan(std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot,
                          const std::vector<ReportTerms>& terms, const Scan& scan, std::vector<char>& gated) const {
  std::vector<Leaf> next;
  next.reserve(leaves.size() * 2 + scan.reports.size());
  for (Leaf& leaf : leaves) branchLeaf(leaf, tick, terms, scan, gated, next);
  births_.startLocatedTrees(next, tick, slot, terms, scan, gated);
  std::sort(next.begin(), next.end(), leafOrder);
  leaves = std::move(next);
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

std::vector<ReportTerms> SbmhtEngine::termsOfSlot(std::span<const common::Observation> slot) {
  const double r2 = params_.measurement_sigma * params_.measurement_sigma;
  std::vector<ReportTerms> terms;
  terms.reserve(slot.size());
  for (const auto& o : slot) {
    terms.push_back(termsOf(o, r2, params_.false_alarm_density, gates_));
    if (!terms.back().usable) ++unusable_reports_;
  }
  return terms;
}

void SbmhtEngine::processTick(std::vector<Leaf>& leaves, std::int32_t tick, std::span<const common::Observation> slot) {
  const std::vector<ReportTerms> terms = termsOfSlot(slot);

  // The time update, once per tick: mixing and each model's prediction (mu becomes cbar).
  for (Leaf& leaf : leaves) {
    leaf.perceivable = false;
    timeUpdate(leaf);
  }

  const std::vector<Scan> scans = scansOf(slot, coverage_, coverage_of_sensor_);
  std::vector<char> gated(slot.size(), 0);  // a report some leaf took in its scan
  std::vector<FreeBearing> free_bearings;   // of the scans so far, for pair births
  for (std::size_t s = 0; s < scans.size(); ++s) {
    runScan(leaves, tick, slot, terms, scans[s], gated);
    // A pair tree started here meets the later sensors' scans of the tick: a third bearing of its
    // target joins it rather than pairing anew, and a sensor that could see it and did not weighs it.
    if (params_.bearing_pair_births == 1)
      births_.startBearingPairTrees(leaves, tick, slot, terms, scans[s], gated, free_bearings);
    // Between one sensor's scan and the next, the hypotheses the reports made unlikely go, or the
    // leaves would multiply by two per sensor that saw the target.
    if (s + 1 < scans.size() && !scans[s].reports.empty()) manageHypotheses(leaves, tick, false);
  }
  endTick(leaves, tick);
  mergeDuplicates(leaves, params_.n_scan);
  std::sort(leaves.begin(), leaves.end(), leafOrder);
  manageHypotheses(leaves, tick, true);
}

void SbmhtEngine::manageHypotheses(std::vector<Leaf>& leaves, std::int32_t tick, bool n_scan_pruning) {
  truncated_searches_ += weighHypotheses(leaves, static_cast<std::size_t>(params_.hypotheses));
  pruneUnlikelyLeaves(leaves);
  if (n_scan_pruning) pruneNScan(leaves, tick, NScanRule{params_.n_scan, roads_, params_.road_sections_kept});
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
  leaf.imm = ImmState::startAt(state, births_.initialModeProbabilities());
  // The class evidence travels with the track; a handoff without a usable class vector (another
  // engine's, or malformed) starts from no evidence rather than being refused.
  if (auto beta = common::receivedClassVector(handoff.class_probabilities)) leaf.classes = std::move(*beta);
  // A confirmed track arrives confirmed, T_drop above the confirmation threshold; a tentative one
  // starts over at L(1).
  if (handoff.confirmed) {
    const double high = sprt_.confirm + sprt_.drop_confirmed;
    leaf.score = TrackScore{high, high, TrackStatus::confirmed};
  } else {
    leaf.score = TrackScore::start(births_.initialScore());
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
    const Leaf* leaf = representative(leavesOfTree(leaves, leaves[k].tree));
    const GaussianState s = leaf->imm.combined();
    out.push_back({leaf->tree, {s.x(kX) + delta_ * s.x(kVx), s.x(kY) + delta_ * s.x(kVy)}});
  }
  return out;
}

common::TrackHandoff SbmhtEngine::release(common::TrackId track_id, std::uint32_t to_supernode) {
  const Leaf* leaf = representative(leavesOfTree(replay_.current(), track_id));
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

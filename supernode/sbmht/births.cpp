#include "supernode/sbmht/births.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "common/class_evidence.hpp"
#include "common/track_id.hpp"

namespace wsn::supernode::sbmht {
namespace {

using common::kVx;

/// Two bearings whose lines of sight are within about 1 degree of parallel or of opposed (|sin gamma|
/// below this) start no tree: parallel rays cross far along both or nowhere, opposed ones (a target on
/// the line through both sensors) anywhere between them, and a fix so long and thin (its covariance
/// grows as 1 / sin^2 gamma) locates nothing the sensors' reach does not already bound.
constexpr double kMinBearingCrossingSine = 0.02;

InitialScore scoreRuleOf(const SbmhtParams& params) {
  return params.initial_score == 1 ? InitialScore::paper : InitialScore::blackman;
}

}  // namespace

TreeBirths::TreeBirths(std::uint32_t supernode, const SbmhtParams& params, std::size_t model_count,
                       std::shared_ptr<const common::Terrain> terrain)
    : supernode_(supernode),
      params_(params),
      score_rule_(scoreRuleOf(params)),
      initial_score_(sbmht::initialScore(score_rule_, params.detection_probability, params.false_alarm_density,
                                         params.birth_density)),
      initial_probabilities_(ModeVector::Zero(static_cast<Eigen::Index>(model_count))),
      terrain_(std::move(terrain)) {
  initial_probabilities_(1) = 0.5;
  initial_probabilities_(2) = 0.5;
}

Leaf TreeBirths::newTree(common::TrackId id, std::int32_t tick, std::vector<std::int32_t> reports,
                         const PositionFix& fix, double score, const ClassVector& classes) const {
  common::GaussianState start;
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
  confirmByCount(leaf, params_.confirm_reports);
  return leaf;
}

// A report that locates a target (not a bearing) starts a new tentative tree there, at rest but for
// a radar's range rate: every such report of a sensor that no existing leaf gated (a target no track
// explains), or, when the leaves gated all of them, the sensor's first (a new target may cross a
// track). A radar or camera that sees several new targets in one tick starts them all at once, up to
// kMaxBirthsPerSensorTick; the birth id's index tells them apart. A presence sensor's report places
// the target at the sensor and says nothing of its motion: a tree started there at rest would stay at
// the sensor after the target left, its silence explained by the stop model. ONERA's volume reports
// update tracks only.
void TreeBirths::startLocatedTrees(std::vector<Leaf>& leaves, std::int32_t tick,
                                   std::span<const common::Observation> slot, const std::vector<ReportTerms>& terms,
                                   const Scan& scan, const std::vector<char>& gated) const {
  if (scan.coverage != nullptr && scan.coverage->presence) return;
  std::map<common::SensorId, std::vector<std::size_t>> fixes_of_sensor;
  for (const std::size_t j : scan.reports)
    if (terms[j].usable && terms[j].fix) fixes_of_sensor[slot[j].sensor].push_back(j);
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
    if (std::any_of(leaves.begin(), leaves.end(), [&](const Leaf& l) { return l.tree == id; })) continue;
    // eq. 20: its class vector from the report's c, uniform without one.
    leaves.push_back(newTree(id, tick, {static_cast<std::int32_t>(j)}, fix, initial_score_,
                             ClassVector(common::initialClassVector(terms[j].classes))));
  }
}

std::optional<TreeBirths::PairBirth> TreeBirths::pairBirth(const ReportTerms& a, const common::SensorCoverage& sensor_a,
                                                           const ReportTerms& b,
                                                           const common::SensorCoverage& sensor_b) const {
  const auto pair = bearingPairFix(a.model, a.z, a.R, b.model, b.z, b.R, kMinBearingCrossingSine);
  if (!pair) return std::nullopt;
  // Both sensors must be able to see a target there: in range, field of view and sight.
  const common::Vec2 at{pair->fix.position(0), pair->fix.position(1)};
  if (!(common::detectionProbabilityAt(sensor_a, at, terrain_.get()) > 0.0) ||
      !(common::detectionProbabilityAt(sensor_b, at, terrain_.get()) > 0.0))
    return std::nullopt;
  // Eq. 20 from a's c, then eq. 19 with b's: a pair whose classes exclude each other is no target.
  ClassVector classes(common::initialClassVector(a.classes));
  double class_increment = 0.0;
  if (!b.classes.empty()) {
    const common::ClassUpdate update = common::updateClassVector(classes, b.classes);
    if (std::isinf(update.score_increment) && update.score_increment < 0.0) return std::nullopt;
    classes = ClassVector(update.beta);
    class_increment = update.score_increment;
  }
  // The pair's likelihood ratio: a new target (density lambda_nt over the field, seen and
  // delivered by both) against two false bearings, lambda_a lambda_b per rad^2, that is
  // lambda_a lambda_b |det J| per m^2 in the field. The initial-score rule then applies as to
  // any fix. Two reports' evidence: it starts well above a one-report birth.
  const double pd = sensor_a.detection_probability * sensor_b.detection_probability * params_.delivery_probability *
                    params_.delivery_probability;
  const double clutter = a.clutter_density * b.clutter_density * pair->jacobian_determinant;
  const double score = sbmht::initialScore(score_rule_, pd, clutter, params_.birth_density) + class_increment;
  return PairBirth{pair->fix, score, classes};
}

void TreeBirths::startBearingPairTrees(std::vector<Leaf>& leaves, std::int32_t tick,
                                       std::span<const common::Observation> slot, const std::vector<ReportTerms>& terms,
                                       const Scan& scan, const std::vector<char>& gated,
                                       std::vector<FreeBearing>& earlier) const {
  // This scan's bearings that no leaf took, from a listed sensor that starts trees (alone a bearing starts none).
  const common::SensorCoverage* sensor = scan.coverage;
  if (sensor == nullptr || sensor->presence) return;
  std::vector<std::size_t> latest;
  for (const std::size_t j : scan.reports)
    if (terms[j].usable && terms[j].model.kind == common::MeasurementKind::bearing && !gated[j]) latest.push_back(j);
  if (latest.empty()) return;
  std::vector<Leaf> born;
  std::uint32_t index = 0;  // births named after this scan's sensor, which starts no tree alone
  for (const auto& [a, sensor_of_a] : earlier) {
    if (index >= common::track_id::kMaxBirthsPerSensorTick) break;
    for (const std::size_t b : latest) {
      if (index >= common::track_id::kMaxBirthsPerSensorTick) break;
      const auto birth = pairBirth(terms[a], *sensor_of_a, terms[b], *sensor);
      if (!birth) continue;
      const common::TrackId id = common::track_id::birth(supernode_, tick, slot[b].sensor, index++);
      if (std::any_of(leaves.begin(), leaves.end(), [&](const Leaf& l) { return l.tree == id; })) continue;
      // a's scan ran first: its entry comes first, as in a leaf that took both through the scans.
      born.push_back(newTree(id, tick, {static_cast<std::int32_t>(a), static_cast<std::int32_t>(b)}, birth->fix,
                             birth->score, birth->classes));
    }
  }
  for (const std::size_t b : latest) earlier.push_back({b, sensor});
  if (born.empty()) return;
  for (Leaf& leaf : born) leaves.push_back(std::move(leaf));
  std::sort(leaves.begin(), leaves.end(), leafOrder);
}

}  // namespace wsn::supernode::sbmht

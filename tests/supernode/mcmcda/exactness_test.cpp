// The oracle for the MCMCDA chain: on problems small enough to enumerate every partition in
// Omega, the chain's empirical distribution must match the exact posterior of eq. (3), and the best
// state it keeps must be the brute-force MAP.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <vector>

#include <catch2/catch.hpp>

#include "common/rng.hpp"
#include "supernode/mcmcda/problem.hpp"
#include "supernode/mcmcda/sampler.hpp"

namespace wsn::supernode::mcmcda {
namespace {

/// Every member of Omega, built observation by observation: each one is a false alarm, starts a
/// track, or joins a track whose last observation it is a candidate successor of.
void enumerate(const Problem& problem, std::int32_t next, Partition& open, std::vector<Partition>& out) {
  if (next == problem.size()) {
    if (std::all_of(open.begin(), open.end(), [](const auto& t) { return t.size() >= 2; })) {
      Partition p = open;
      canonicalise(p);
      out.push_back(p);
    }
    return;
  }
  enumerate(problem, next + 1, open, out);  // false alarm
  open.push_back({next});                   // a new track
  enumerate(problem, next + 1, open, out);
  open.pop_back();
  for (std::size_t k = 0; k < open.size(); ++k) {
    if (!problem.linked(open[k].back(), next)) continue;
    open[k].push_back(next);
    enumerate(problem, next + 1, open, out);
    open[k].pop_back();
  }
}

/// Labels of a partition as Sampler::labels gives them: first observation of the track, or -1.
std::vector<std::int32_t> labelsOf(const Problem& problem, const Partition& partition) {
  std::vector<std::int32_t> labels(static_cast<std::size_t>(problem.size()), -1);
  for (const auto& track : partition)
    for (const auto i : track) labels[static_cast<std::size_t>(i)] = track.front();
  return labels;
}

struct Exact {
  std::vector<Partition> partitions;
  std::map<std::vector<std::int32_t>, std::size_t> index;  // labels -> partition
  std::vector<double> probability;
};

Exact exactPosterior(const Problem& problem) {
  Exact e;
  Partition open;
  enumerate(problem, 0, open, e.partitions);
  std::vector<double> log_p;
  for (std::size_t k = 0; k < e.partitions.size(); ++k) {
    e.index[labelsOf(problem, e.partitions[k])] = k;
    log_p.push_back(logPosterior(problem, e.partitions[k]));
  }
  const double top = *std::max_element(log_p.begin(), log_p.end());
  double sum = 0.0;
  for (const double l : log_p) sum += std::exp(l - top);
  for (const double l : log_p) e.probability.push_back(std::exp(l - top) / sum);
  return e;
}

/// Two targets crossing over four ticks, with a clutter point: 9 observations, with the sigmas wide enough that many partitions carry real mass.
std::vector<ProblemObservation> crossingObservations() {
  return {
      {1, 0.0, 0.0, false, {}}, {1, 0.0, 4.0, false, {}},                            // both targets
      {2, 1.1, 1.0, false, {}}, {2, 0.9, 3.1, false, {}}, {2, 3.5, 0.5, false, {}},  // + clutter
      {3, 2.1, 1.9, false, {}}, {3, 1.9, 2.2, false, {}},                            // the crossing
      {4, 3.0, 3.1, false, {}}, {4, 3.2, 0.9, false, {}},                            // both targets
  };
}

ModelParams ambiguousParams() {
  ModelParams p;
  p.detection_probability = 0.8;
  p.termination_probability = 0.1;
  p.birth_density = 0.02;
  p.false_alarm_density = 0.05;
  p.measurement_sigma = 0.6;
  p.process_noise_sigma = 0.4;
  p.initial_velocity_sigma = 1.5;
  p.max_speed = 1.6;
  p.max_gap = 2;
  p.stop_probability = 0.3;
  return p;
}

struct ChainResult {
  std::vector<double> frequency;        // per enumerated partition
  std::vector<std::vector<double>> batch;  // per batch, per partition
  Partition best;
  MoveStats stats;
  std::uint64_t outside = 0;  // visits to states the enumeration does not know (must be 0)
};

ChainResult runChain(const Problem& problem, const Exact& exact, std::int64_t iterations, std::int32_t batches,
                     std::uint64_t seed) {
  Sampler sampler(problem);
  common::Stream rng(seed, common::Purpose::kTracker, 0, 0);
  ChainResult r;
  r.frequency.assign(exact.partitions.size(), 0.0);
  r.batch.assign(static_cast<std::size_t>(batches), std::vector<double>(exact.partitions.size(), 0.0));
  std::vector<std::int32_t> labels;
  const std::int64_t per_batch = iterations / batches;
  sampler.run(1000, rng);  // burn-in
  for (std::int64_t n = 0; n < per_batch * batches; ++n) {
    sampler.step(rng);
    sampler.labels(labels);
    const auto it = exact.index.find(labels);
    if (it == exact.index.end()) {
      ++r.outside;
      continue;
    }
    r.frequency[it->second] += 1.0;
    r.batch[static_cast<std::size_t>(n / per_batch)][it->second] += 1.0;
  }
  for (auto& f : r.frequency) f /= static_cast<double>(per_batch * batches);
  for (auto& b : r.batch)
    for (auto& f : b) f /= static_cast<double>(per_batch);
  r.best = sampler.bestState();
  r.stats = sampler.stats();
  return r;
}

double totalVariation(const std::vector<double>& p, const std::vector<double>& q) {
  double sum = 0.0;
  for (std::size_t k = 0; k < p.size(); ++k) sum += std::abs(p[k] - q[k]);
  return 0.5 * sum;
}

/// The TV distance a correct chain is expected to show from sampling noise alone: with batch
/// means, se_k = sd over batches of the batch frequency / sqrt(B) is the standard error of
/// partition k's frequency *including* the chain's autocorrelation, and E|N(0, se^2)| =
/// se sqrt(2 / pi). The bound is four times the expected noise: a correct chain stays under it
/// with overwhelming probability, while a kernel that is wrong by a few percent of mass does not.
/// Standard error of each partition's frequency by batch means (autocorrelation included).
std::vector<double> standardErrors(const ChainResult& r) {
  const auto batches = static_cast<double>(r.batch.size());
  std::vector<double> se(r.frequency.size(), 0.0);
  for (std::size_t k = 0; k < r.frequency.size(); ++k) {
    double var = 0.0;
    for (const auto& b : r.batch) var += (b[k] - r.frequency[k]) * (b[k] - r.frequency[k]);
    se[k] = std::sqrt(var / (batches - 1.0) / batches);
  }
  return se;
}

double noiseBound(const std::vector<double>& se) {
  double expected = 0.0;
  for (const double s : se) expected += s * std::sqrt(2.0 / std::numbers::pi);
  return 4.0 * 0.5 * expected;
}

/// TV sums absolute errors and so forgives a bias that is small next to the noise of the many
/// rare partitions. The chi-square statistic sum (f_k - p_k)^2 / se_k^2 over the partitions with
/// p_k > 1e-3 weighs each error by its own noise instead; for a correct chain it is about
/// chi^2 with m degrees of freedom.
struct ChiSquare {
  double statistic = 0.0;
  std::int32_t states = 0;
  /// Wilson-Hilferty's 99.9 % quantile of chi^2(m), times 1.25 because se is estimated from 50
  /// batches rather than known.
  double bound() const {
    const double m = states;
    const double z = 3.09;
    return 1.25 * m * std::pow(1.0 - 2.0 / (9.0 * m) + z * std::sqrt(2.0 / (9.0 * m)), 3.0);
  }
};

ChiSquare chiSquare(const std::vector<double>& frequency, const std::vector<double>& exact,
                    const std::vector<double>& se) {
  ChiSquare c;
  for (std::size_t k = 0; k < exact.size(); ++k) {
    if (exact[k] <= 1e-3 || se[k] <= 0.0) continue;
    c.statistic += (frequency[k] - exact[k]) * (frequency[k] - exact[k]) / (se[k] * se[k]);
    ++c.states;
  }
  return c;
}

void checkExactness(const Problem& problem, std::uint64_t seed, std::int64_t samples = 8'000'000) {
  const Exact exact = exactPosterior(problem);
  INFO("partitions in Omega: " << exact.partitions.size());
  REQUIRE(exact.partitions.size() > 50);
  const ChainResult r = runChain(problem, exact, samples, 50, seed);
  REQUIRE(r.outside == 0);

  const double tv = totalVariation(r.frequency, exact.probability);
  const auto se = standardErrors(r);
  const double bound = noiseBound(se);
  INFO("TV = " << tv << ", bound = " << bound);
  CHECK(tv < bound);
  CHECK(bound < 0.05);  // the run is long enough for the test to have teeth
  const ChiSquare chi2 = chiSquare(r.frequency, exact.probability, se);
  INFO("chi2 = " << chi2.statistic << " over " << chi2.states << " partitions, bound = " << chi2.bound());
  CHECK(chi2.states >= 20);
  CHECK(chi2.statistic < chi2.bound());

  // Negative control: the same samples against the posterior of a different model (pd times 0.75)
  // are far outside both bounds, so the comparison can tell a wrong stationary distribution.
  ModelParams other = problem.params();
  other.detection_probability *= 0.75;
  std::vector<ProblemObservation> obs;
  for (std::int32_t i = 0; i < problem.size(); ++i) obs.push_back(problem.observation(i));
  const Problem perturbed(other, obs, problem.lastTick());
  Exact wrong = exactPosterior(perturbed);
  std::vector<double> aligned(exact.partitions.size(), 0.0);
  for (std::size_t k = 0; k < exact.partitions.size(); ++k)
    aligned[k] = wrong.probability[wrong.index.at(labelsOf(problem, exact.partitions[k]))];
  const double tv_wrong = totalVariation(r.frequency, aligned);
  INFO("TV against the perturbed posterior = " << tv_wrong);
  CHECK(tv_wrong > 3.0 * bound);
  CHECK(chiSquare(r.frequency, aligned, se).statistic > 10.0 * chi2.bound());

  // Every move was accepted (for update: a proposal that changed the state).
  for (int m = 0; m < kMoveCount; ++m) {
    INFO("move " << moveName(static_cast<Move>(m)));
    CHECK(r.stats.accepted[static_cast<std::size_t>(m)] > 100);
  }

  // The best state kept is the brute-force MAP.
  const auto map = std::max_element(exact.probability.begin(), exact.probability.end()) - exact.probability.begin();
  CHECK(r.best == exact.partitions[static_cast<std::size_t>(map)]);
}

}  // namespace

TEST_CASE("mcmcda chain samples the exact posterior of two crossing targets with clutter", "[mcmcda]") {
  const Problem problem(ambiguousParams(), crossingObservations(), 4);
  checkExactness(problem, 7);
}

TEST_CASE("mcmcda chain is exact with an anchored track in the problem", "[mcmcda]") {
  auto obs = crossingObservations();
  ProblemObservation anchor;
  anchor.tick = 0;
  anchor.x = -1.0;
  anchor.y = -1.0;
  anchor.anchor = true;
  anchor.prior.tick = 0;
  anchor.prior.x = -1.0;
  anchor.prior.y = -1.0;
  anchor.prior.vx = 1.0;
  anchor.prior.vy = 1.0;
  anchor.prior.cov = {0.3, 0.05, 0.2};
  obs.insert(obs.begin(), anchor);
  obs.erase(obs.begin() + 5);  // the clutter point: keeps Omega about as large as without the anchor
  const Problem problem(ambiguousParams(), obs, 4);
  checkExactness(problem, 11);
}

TEST_CASE("mcmcda chain is exact on six ticks with two anchors and long tracks", "[mcmcda]") {
  // Longer tracks exercise split and merge at many cut points and update at many keep lengths;
  // two anchors at tick 0 compete for the same continuations; d-bar = 3 allows gaps.
  ModelParams p = ambiguousParams();
  p.detection_probability = 0.7;
  p.max_gap = 3;
  std::vector<ProblemObservation> obs;
  for (const double y : {0.0, 3.0}) {
    ProblemObservation anchor{0, -1.0, y, true, {}};
    anchor.prior = TrackState{0, -1.0, y, 1.0, 0.0, {0.3, 0.05, 0.2}};
    obs.push_back(anchor);
  }
  const double a[7][2] = {{0, 0}, {1.0, 0.2}, {2.1, 0.1}, {3.0, 0.4}, {3.9, 0.3}, {5.1, 0.0}, {6.0, 0.2}};
  const double b[7][2] = {{0, 3}, {1.1, 2.6}, {0, 0}, {3.0, 2.0}, {4.0, 1.5}, {0, 0}, {6.1, 1.0}};
  for (std::int32_t t = 1; t <= 6; ++t) {
    obs.push_back({t, a[t][0], a[t][1], false, {}});
    if (t != 2 && t != 5) obs.push_back({t, b[t][0], b[t][1], false, {}});  // the second target missed twice
  }
  // Since a track's silence sums "ended" and "still there, unseen" its noise bound after 8,000,000
  // samples was 0.0501: a longer run keeps it under 0.05.
  checkExactness(Problem(p, obs, 6), 13, 10'000'000);
}

TEST_CASE("mcmcda enumeration and validation agree on what Omega is", "[mcmcda]") {
  const Problem problem(ambiguousParams(), crossingObservations(), 4);
  const Exact exact = exactPosterior(problem);
  for (const auto& p : exact.partitions) REQUIRE(validatePartition(problem, p).empty());
  CHECK_FALSE(validatePartition(problem, {{0}}).empty());          // one observation
  CHECK_FALSE(validatePartition(problem, {{0, 1}}).empty());       // same tick
  CHECK_FALSE(validatePartition(problem, {{0, 2}, {2, 5}}).empty());  // shared observation
  CHECK_FALSE(validatePartition(problem, {{0, 9}}).empty());       // gap 3 > d-bar
}

}  // namespace wsn::supernode::mcmcda

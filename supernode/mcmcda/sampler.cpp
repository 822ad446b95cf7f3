#include "supernode/mcmcda/sampler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace wsn::supernode::mcmcda {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

double logSumExp(double a, double b) {
  if (a == kNegInf) return b;
  if (b == kNegInf) return a;
  const double hi = std::max(a, b);
  return hi + std::log1p(std::exp(std::min(a, b) - hi));
}

}  // namespace

std::string_view moveName(Move move) {
  switch (move) {
    case Move::kBirth: return "birth";
    case Move::kDeath: return "death";
    case Move::kSplit: return "split";
    case Move::kMerge: return "merge";
    case Move::kExtension: return "extension";
    case Move::kReduction: return "reduction";
    case Move::kUpdate: return "update";
    case Move::kSwitch: return "switch";
  }
  return "?";
}

void canonicalise(Partition& partition) {
  std::sort(partition.begin(), partition.end(),
            [](const auto& a, const auto& b) { return a.front() < b.front(); });
}

std::string validatePartition(const Problem& problem, const Partition& partition) {
  std::vector<bool> used(static_cast<std::size_t>(problem.size()), false);
  for (std::size_t k = 0; k < partition.size(); ++k) {
    const auto& track = partition[k];
    const std::string which = "track " + std::to_string(k);
    if (track.size() < 2) return which + " has fewer than two observations";
    for (std::size_t m = 0; m < track.size(); ++m) {
      const std::int32_t i = track[m];
      if (i < 0 || i >= problem.size()) return which + " names observation " + std::to_string(i) + ", out of range";
      if (used[static_cast<std::size_t>(i)]) return "observation " + std::to_string(i) + " is in two tracks";
      used[static_cast<std::size_t>(i)] = true;
      if (m > 0 && !problem.linked(track[m - 1], i))
        return which + ": observation " + std::to_string(i) + " is not a candidate successor of " +
               std::to_string(track[m - 1]);
    }
  }
  return {};
}

double logPosterior(const Problem& problem, const Partition& partition) {
  double sum = 0.0;
  for (const auto& track : partition) sum += problem.trackScore(track);
  return sum;
}

Sampler::Sampler(const Problem& problem, ProposalSets sets)
    : problem_(problem),
      keep_sets_(sets == ProposalSets::kKept ||
                 (sets == ProposalSets::kBySize && problem.size() >= kKeepProposalSetsFrom)) {
  const auto n = static_cast<std::size_t>(problem.size());
  track_of_.assign(n, -1);
  position_.assign(n, -1);
  best_track_of_ = track_of_;
  // Every track holds at least two observations, so at most n / 2 are live; each can hold at most
  // one observation per tick.
  std::size_t longest = n == 0 ? 0 : 1;
  for (std::size_t i = 1; i < n; ++i)
    if (problem.tick(static_cast<std::int32_t>(i)) != problem.tick(static_cast<std::int32_t>(i - 1))) ++longest;
  tracks_.resize(n / 2 + 1);
  for (auto& track : tracks_) track.obs.reserve(longest);
  std::size_t links = 0;
  for (std::int32_t i = 0; i < problem.size(); ++i) links += problem.successors(i).size();
  counts_.assign(static_cast<std::size_t>(problem.params().max_gap) + 1, 0);
  // Every count a proposal divides by (observations, tracks, merge pairs, switch cuts) is below
  // this size, so logCount never calls log() in the loop.
  log_count_.resize(std::max({n, links, longest * longest}) + 2);
  log_count_[0] = kNegInf;  // no count a proposal divides by is 0; make a slip loud
  for (std::size_t k = 1; k < log_count_.size(); ++k) log_count_[k] = std::log(static_cast<double>(k));
  log_stop_ = std::log(problem.params().stop_probability);
  log_go_on_ = std::log1p(-problem.params().stop_probability);
  for (auto* buffer : {&tail_, &target_a_, &target_b_, &backup_a_, &backup_b_}) buffer->reserve(longest);
  step_cost_.reserve(longest);
  step_feasible_.reserve(longest);
  if (!keep_sets_) {
    rescanned_starts_.reserve(n);
    rescanned_pairs_.reserve(links);
    return;
  }
  pred_start_.assign(n + 1, 0);
  for (std::int32_t i = 0; i < problem.size(); ++i)
    for (const std::int32_t j : problem.successors(i)) ++pred_start_[static_cast<std::size_t>(j) + 1];
  for (std::size_t j = 0; j < n; ++j) pred_start_[j + 1] += pred_start_[j];
  pred_.resize(links);
  {
    std::vector<std::int32_t> fill(pred_start_.begin(), pred_start_.end() - 1);
    for (std::int32_t i = 0; i < problem.size(); ++i)
      for (const std::int32_t j : problem.successors(i)) pred_[static_cast<std::size_t>(fill[static_cast<std::size_t>(j)]++)] = i;
  }
  // Every observation unassigned: each successor is free, and each observation with one starts.
  free_successors_.resize(n);
  std::vector<std::int32_t> starts(n);
  for (std::size_t i = 0; i < n; ++i) {
    free_successors_[i] = static_cast<std::int32_t>(problem.successors(static_cast<std::int32_t>(i)).size());
    starts[i] = free_successors_[i] > 0 ? 1 : 0;
  }
  birth_starts_.reset(static_cast<std::int32_t>(n));
  birth_starts_.assign(starts);
  merge_pairs_.reset(static_cast<std::int32_t>(tracks_.size()));
  pairs_of_slot_.assign(tracks_.size(), 0);
  // A refresh visits each changed track's end and each changed first element's predecessors:
  // past n / (1 + mean predecessors) changes, rebuilding (one pass over the window) costs less.
  change_capacity_ = std::max<std::size_t>(16, n / (1 + links / std::max<std::size_t>(n, 1)));
  changed_slots_.reserve(change_capacity_);
  changed_firsts_.reserve(change_capacity_);
}

void Sampler::setState(const Partition& partition) {
  const std::string error = validatePartition(problem_, partition);
  if (!error.empty()) throw std::invalid_argument("mcmcda: invalid initial partition: " + error);
  while (track_count_ > 0) removeTrack(track_count_ - 1);
  log_posterior_ = 0.0;
  for (const auto& track : partition) addTrack(track, problem_.trackScore(track));
  best_track_of_ = track_of_;
  best_log_posterior_ = log_posterior_;
}

Partition Sampler::state() const { return partitionOf(track_of_); }

Partition Sampler::bestState() const { return partitionOf(best_track_of_); }

Partition Sampler::partitionOf(const std::vector<std::int32_t>& track_of) const {
  Partition out;
  std::vector<std::int32_t> index_of_slot(tracks_.size(), -1);
  for (std::int32_t i = 0; i < problem_.size(); ++i) {  // indices ascend with tick: track order
    const std::int32_t slot = track_of[static_cast<std::size_t>(i)];
    if (slot < 0) continue;
    auto& index = index_of_slot[static_cast<std::size_t>(slot)];
    if (index < 0) {
      index = static_cast<std::int32_t>(out.size());
      out.emplace_back();
    }
    out[static_cast<std::size_t>(index)].push_back(i);
  }
  canonicalise(out);
  return out;
}

void Sampler::labels(std::vector<std::int32_t>& out) const {
  out.assign(static_cast<std::size_t>(problem_.size()), -1);
  for (std::int32_t k = 0; k < track_count_; ++k) {
    const auto& obs = tracks_[static_cast<std::size_t>(k)].obs;
    for (const std::int32_t i : obs) out[static_cast<std::size_t>(i)] = obs.front();
  }
}

// ---- state changes --------------------------------------------------------------------------

std::int32_t Sampler::addTrack(std::span<const std::int32_t> obs, double score) {
  const std::int32_t slot = track_count_++;
  auto& track = tracks_[static_cast<std::size_t>(slot)];
  track.obs.assign(obs.begin(), obs.end());
  track.score = score;
  noteChange(changed_firsts_, obs.front());
  noteChange(changed_slots_, slot);
  for (std::size_t m = 0; m < obs.size(); ++m) {
    track_of_[static_cast<std::size_t>(obs[m])] = slot;
    position_[static_cast<std::size_t>(obs[m])] = static_cast<std::int32_t>(m);
    taken(obs[m]);
  }
  log_posterior_ += score;
  return slot;
}

void Sampler::removeTrack(std::int32_t slot) {
  auto& track = tracks_[static_cast<std::size_t>(slot)];
  noteChange(changed_firsts_, track.obs.front());
  noteChange(changed_slots_, slot);
  noteChange(changed_slots_, track_count_ - 1);  // its track moves into `slot`
  for (const std::int32_t i : track.obs) {
    track_of_[static_cast<std::size_t>(i)] = -1;
    position_[static_cast<std::size_t>(i)] = -1;
    released(i);
  }
  log_posterior_ -= track.score;
  const std::int32_t last = track_count_ - 1;
  if (slot != last) {
    std::swap(tracks_[static_cast<std::size_t>(slot)], tracks_[static_cast<std::size_t>(last)]);
    for (const std::int32_t i : tracks_[static_cast<std::size_t>(slot)].obs) track_of_[static_cast<std::size_t>(i)] = slot;
  }
  tracks_[static_cast<std::size_t>(last)].obs.clear();
  --track_count_;
}

void Sampler::setTrack(std::int32_t slot, std::span<const std::int32_t> obs, double score) {
  auto& track = tracks_[static_cast<std::size_t>(slot)];
  if (track.obs.front() != obs.front()) {
    noteChange(changed_firsts_, track.obs.front());
    noteChange(changed_firsts_, obs.front());
  }
  noteChange(changed_slots_, slot);
  // Observations in both the old and the new track stay taken throughout, so that the birth
  // starting points follow only the observations that really changed hands: the old track's are
  // marked as leaving first, and released only if the new track does not take them back. Only
  // observations still marked as this track's: in a switch, the first setTrack has already
  // handed the other track's tail over.
  for (const std::int32_t i : track.obs)
    if (track_of_[static_cast<std::size_t>(i)] == slot) track_of_[static_cast<std::size_t>(i)] = kLeaving;
  for (std::size_t m = 0; m < obs.size(); ++m) {
    const std::int32_t was = track_of_[static_cast<std::size_t>(obs[m])];
    track_of_[static_cast<std::size_t>(obs[m])] = slot;
    position_[static_cast<std::size_t>(obs[m])] = static_cast<std::int32_t>(m);
    if (was == kUnassigned) taken(obs[m]);
  }
  for (const std::int32_t i : track.obs)
    if (track_of_[static_cast<std::size_t>(i)] == kLeaving) {
      track_of_[static_cast<std::size_t>(i)] = kUnassigned;
      position_[static_cast<std::size_t>(i)] = -1;
      released(i);
    }
  track.obs.assign(obs.begin(), obs.end());
  log_posterior_ += score - track.score;
  track.score = score;
}

void Sampler::noteBest() {
  if (log_posterior_ > best_log_posterior_) {
    best_track_of_ = track_of_;  // same size: copies in place
    best_log_posterior_ = log_posterior_;
  }
}

// ---- proposal machinery ---------------------------------------------------------------------

double Sampler::logMoveProbability(Move move, std::int32_t tracks) const {
  // Oh et al. (TAC 2009): birth only when K = 0; with K = 1 the six moves that need one track,
  // uniformly; with K >= 2 all eight, uniformly.
  if (tracks == 0) return move == Move::kBirth ? 0.0 : kNegInf;
  static const double kLogSixth = -std::log(6.0);
  static const double kLogEighth = -std::log(8.0);
  if (tracks == 1) return (move == Move::kMerge || move == Move::kSwitch) ? kNegInf : kLogSixth;
  return kLogEighth;
}

bool Sampler::accept(double log_ratio, common::Stream& rng) {
  // One uniform per proposal, accepted or not, so the stream's use does not depend on the ratio.
  return std::log(rng.uniformPositive()) < log_ratio;  // false for NaN
}

template <class Free>
std::int32_t Sampler::freeGaps(std::int32_t from, const Free& free) const {
  std::int32_t nonempty = 0;
  for (std::int32_t d = 1; d <= problem_.params().max_gap; ++d) {
    std::int32_t count = 0;
    for (const std::int32_t j : problem_.successors(from, d))
      if (free(j)) ++count;
    counts_[static_cast<std::size_t>(d)] = count;
    if (count > 0) ++nonempty;
  }
  return nonempty;
}

template <class Free>
double Sampler::sampleExtension(std::int32_t from, bool forced, const Free& free, common::Stream& rng,
                                std::vector<std::int32_t>& tail) const {
  const double gamma = problem_.params().stop_probability;
  tail.clear();
  double log_q = 0.0;
  std::int32_t current = from;
  for (bool first = true;; first = false) {
    const std::int32_t gaps = freeGaps(current, free);
    const bool may_stop = !(forced && first);
    if (gaps == 0) {
      if (!may_stop) return std::numeric_limits<double>::quiet_NaN();
      break;  // nothing to extend to: the process stops with probability 1
    }
    if (may_stop) {
      if (rng.uniform() < gamma) {
        log_q += log_stop_;
        break;
      }
      log_q += log_go_on_;
    }
    auto which_gap = static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(gaps)));
    std::int32_t gap = 1;
    for (;; ++gap)
      if (counts_[static_cast<std::size_t>(gap)] > 0 && which_gap-- == 0) break;
    const std::int32_t candidates = counts_[static_cast<std::size_t>(gap)];
    auto which = static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(candidates)));
    std::int32_t next = -1;
    for (const std::int32_t j : problem_.successors(current, gap))
      if (free(j) && which-- == 0) {
        next = j;
        break;
      }
    log_q -= logCount(gaps) + logCount(candidates);
    tail.push_back(next);
    current = next;
  }
  return log_q;
}

template <class Free>
double Sampler::logExtension(std::int32_t from, std::span<const std::int32_t> tail, bool forced,
                             const Free& free) const {
  if (forced && tail.empty()) return kNegInf;
  double log_q = 0.0;
  std::int32_t current = from;
  for (std::size_t k = 0; k < tail.size(); ++k) {
    const std::int32_t next = tail[k];
    if (!free(next) || !problem_.linked(current, next)) return kNegInf;
    const std::int32_t gaps = freeGaps(current, free);
    const std::int32_t gap = problem_.tick(next) - problem_.tick(current);
    if (!(forced && k == 0)) log_q += log_go_on_;
    log_q -= logCount(gaps) + logCount(counts_[static_cast<std::size_t>(gap)]);
    current = next;
  }
  if (freeGaps(current, free) > 0) log_q += log_stop_;  // else the stop was certain
  return log_q;
}

std::int32_t Sampler::countTracksAtLeast(std::size_t length) const {
  std::int32_t count = 0;
  for (std::int32_t k = 0; k < track_count_; ++k)
    if (tracks_[static_cast<std::size_t>(k)].obs.size() >= length) ++count;
  return count;
}

std::int32_t Sampler::switchPoints(std::int32_t a, std::int32_t b, std::int32_t k,
                                   std::array<std::int32_t, 2>* pick) const {
  // Swap the tails after a's p-th and b's q-th observation: a' = a[0, p) + b[q, nb),
  // b' = b[0, q) + a[p, na). Both tails empty would change nothing; each new track needs two
  // observations and a valid link where the tails join.
  const auto& A = tracks_[static_cast<std::size_t>(a)].obs;
  const auto& B = tracks_[static_cast<std::size_t>(b)].obs;
  const auto na = static_cast<std::int32_t>(A.size());
  const auto nb = static_cast<std::int32_t>(B.size());
  std::int32_t count = 0;
  for (std::int32_t p = 1; p <= na; ++p)
    for (std::int32_t q = 1; q <= nb; ++q) {
      if (p == na && q == nb) continue;
      if (p + nb - q < 2 || q + na - p < 2) continue;
      if (q < nb && !problem_.linked(A[static_cast<std::size_t>(p - 1)], B[static_cast<std::size_t>(q)])) continue;
      if (p < na && !problem_.linked(B[static_cast<std::size_t>(q - 1)], A[static_cast<std::size_t>(p)])) continue;
      if (count == k && pick != nullptr) *pick = {p, q};
      ++count;
    }
  return count;
}

// ---- the moves ------------------------------------------------------------------------------

void Sampler::step(common::Stream& rng) {
  static constexpr Move kOneTrackMoves[] = {Move::kBirth,     Move::kDeath,     Move::kSplit,
                                            Move::kExtension, Move::kReduction, Move::kUpdate};
  Move move = Move::kBirth;
  if (track_count_ == 1)
    move = kOneTrackMoves[rng.below(6)];
  else if (track_count_ >= 2)
    move = static_cast<Move>(rng.below(kMoveCount));
  ++stats_.proposed[static_cast<std::size_t>(move)];
  switch (move) {
    case Move::kBirth: birth(rng); break;
    case Move::kDeath: death(rng); break;
    case Move::kSplit: split(rng); break;
    case Move::kMerge: merge(rng); break;
    case Move::kExtension: extension(rng); break;
    case Move::kReduction: reduction(rng); break;
    case Move::kUpdate: update(rng); break;
    case Move::kSwitch: trackSwitch(rng); break;
  }
  noteBest();
}

void Sampler::birth(common::Stream& rng) {
  // Oh (TAC 2009): a new track starts at an unassigned observation that has an unassigned
  // candidate successor and grows by the extension process (at least one step).
  const std::int32_t K = track_count_;
  const std::int32_t starts = birthStartCount();
  if (starts == 0) return;
  const std::int32_t first = pickBirthStart(static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(starts))));
  const auto unassigned = [this](std::int32_t j) { return track_of_[static_cast<std::size_t>(j)] < 0; };
  const double log_path = sampleExtension(first, true, unassigned, rng, tail_);
  target_a_.clear();
  target_a_.push_back(first);
  target_a_.insert(target_a_.end(), tail_.begin(), tail_.end());
  const double score = problem_.trackScore(target_a_);
  const double log_forward = logMoveProbability(Move::kBirth, K) - logCount(starts) + log_path;
  const double log_reverse = logMoveProbability(Move::kDeath, K + 1) - logCount(K + 1);
  if (accept(score + log_reverse - log_forward, rng)) {
    addTrack(target_a_, score);
    ++stats_.accepted[static_cast<std::size_t>(Move::kBirth)];
  }
}

void Sampler::death(common::Stream& rng) {
  const std::int32_t K = track_count_;
  const auto slot = static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(K)));
  const auto& track = tracks_[static_cast<std::size_t>(slot)];
  backup_a_.assign(track.obs.begin(), track.obs.end());
  const double score = track.score;
  const double log_forward = logMoveProbability(Move::kDeath, K) - logCount(K);
  removeTrack(slot);
  const auto unassigned = [this](std::int32_t j) { return track_of_[static_cast<std::size_t>(j)] < 0; };
  const std::int32_t starts = birthStartCount();
  const double log_reverse = logMoveProbability(Move::kBirth, K - 1) - logCount(starts) +
                             logExtension(backup_a_.front(), std::span(backup_a_).subspan(1), true, unassigned);
  if (accept(-score + log_reverse - log_forward, rng))
    ++stats_.accepted[static_cast<std::size_t>(Move::kDeath)];
  else
    addTrack(backup_a_, score);
}

void Sampler::split(common::Stream& rng) {
  const std::int32_t K = track_count_;
  const std::int32_t eligible = countTracksAtLeast(4);
  if (eligible == 0) return;
  auto which = static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(eligible)));
  std::int32_t slot = 0;
  for (;; ++slot)
    if (tracks_[static_cast<std::size_t>(slot)].obs.size() >= 4 && which-- == 0) break;
  const auto& track = tracks_[static_cast<std::size_t>(slot)];
  const auto n = static_cast<std::int32_t>(track.obs.size());
  const auto cut = 2 + static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(n - 3)));  // 2 .. n-2
  backup_a_.assign(track.obs.begin(), track.obs.end());
  const double old_score = track.score;
  target_a_.assign(backup_a_.begin(), backup_a_.begin() + cut);
  target_b_.assign(backup_a_.begin() + cut, backup_a_.end());
  const double score_a = problem_.trackScore(target_a_);
  const double score_b = problem_.trackScore(target_b_);
  const double log_forward = logMoveProbability(Move::kSplit, K) - logCount(eligible) - logCount(n - 3);
  setTrack(slot, target_a_, score_a);
  const std::int32_t added = addTrack(target_b_, score_b);
  const double log_reverse = logMoveProbability(Move::kMerge, K + 1) - logCount(mergePairCount());
  if (accept(score_a + score_b - old_score + log_reverse - log_forward, rng)) {
    ++stats_.accepted[static_cast<std::size_t>(Move::kSplit)];
  } else {
    removeTrack(added);
    setTrack(slot, backup_a_, old_score);
  }
}

void Sampler::merge(common::Stream& rng) {
  const std::int32_t K = track_count_;
  const std::int32_t pairs = mergePairCount();
  if (pairs == 0) return;
  const auto [u, v] = pickMergePair(static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(pairs))));
  const auto& first = tracks_[static_cast<std::size_t>(u)];
  const auto& second = tracks_[static_cast<std::size_t>(v)];
  backup_a_.assign(first.obs.begin(), first.obs.end());
  backup_b_.assign(second.obs.begin(), second.obs.end());
  const double score_a = first.score;
  const double score_b = second.score;
  target_a_.assign(backup_a_.begin(), backup_a_.end());
  target_a_.insert(target_a_.end(), backup_b_.begin(), backup_b_.end());
  const double score = problem_.trackScore(target_a_);
  const double log_forward = logMoveProbability(Move::kMerge, K) - logCount(pairs);
  // removeTrack(v) moves the last slot into v: u moves with it when it was last.
  const std::int32_t merged = (u == K - 1) ? v : u;
  removeTrack(v);
  setTrack(merged, target_a_, score);
  const auto n = static_cast<std::int32_t>(target_a_.size());
  const double log_reverse =
      logMoveProbability(Move::kSplit, K - 1) - logCount(countTracksAtLeast(4)) - logCount(n - 3);
  if (accept(score - score_a - score_b + log_reverse - log_forward, rng)) {
    ++stats_.accepted[static_cast<std::size_t>(Move::kMerge)];
  } else {
    setTrack(merged, backup_a_, score_a);
    addTrack(backup_b_, score_b);
  }
}

void Sampler::extension(common::Stream& rng) {
  const auto slot = static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(track_count_)));
  const auto& obs = tracks_[static_cast<std::size_t>(slot)].obs;
  const auto unassigned = [this](std::int32_t j) { return track_of_[static_cast<std::size_t>(j)] < 0; };
  if (std::isnan(sampleExtension(obs.back(), true, unassigned, rng, tail_))) return;
  target_a_.assign(obs.begin(), obs.end());
  target_a_.insert(target_a_.end(), tail_.begin(), tail_.end());
  proposeSingleTrack(Move::kExtension, slot, target_a_, logSingleTrackProposal(slot, target_a_), rng);
}

void Sampler::reduction(common::Stream& rng) {
  const std::int32_t eligible = countTracksAtLeast(3);
  if (eligible == 0) return;
  auto which = static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(eligible)));
  std::int32_t slot = 0;
  for (;; ++slot)
    if (tracks_[static_cast<std::size_t>(slot)].obs.size() >= 3 && which-- == 0) break;
  const auto& obs = tracks_[static_cast<std::size_t>(slot)].obs;
  const auto n = static_cast<std::int32_t>(obs.size());
  const auto keep = 2 + static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(n - 2)));  // 2 .. n-1
  target_a_.assign(obs.begin(), obs.begin() + keep);
  proposeSingleTrack(Move::kReduction, slot, target_a_, logSingleTrackProposal(slot, target_a_), rng);
}

void Sampler::update(common::Stream& rng) {
  const auto slot = static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(track_count_)));
  const auto& obs = tracks_[static_cast<std::size_t>(slot)].obs;
  const auto n = static_cast<std::int32_t>(obs.size());
  const auto keep = 1 + static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(n - 1)));  // 1 .. n-1
  // The discarded tail is free for the re-extension (it may pick the same observations again).
  const auto free = [this, slot, keep](std::int32_t j) {
    const std::int32_t owner = track_of_[static_cast<std::size_t>(j)];
    return owner < 0 || (owner == slot && position_[static_cast<std::size_t>(j)] >= keep);
  };
  if (std::isnan(sampleExtension(obs[static_cast<std::size_t>(keep - 1)], true, free, rng, tail_))) return;
  target_a_.assign(obs.begin(), obs.begin() + keep);
  target_a_.insert(target_a_.end(), tail_.begin(), tail_.end());
  // omega' = omega: accepted trivially, and not counted, so that "accepted" means "changed".
  if (std::equal(target_a_.begin(), target_a_.end(), obs.begin(), obs.end())) return;
  proposeSingleTrack(Move::kUpdate, slot, target_a_, logSingleTrackProposal(slot, target_a_), rng);
}

double Sampler::logSingleTrackProposal(std::int32_t slot, std::span<const std::int32_t> target) const {
  // Extension, reduction and update all turn one track into another with the same first
  // observation, and update can produce what the other two produce (and the same result from
  // several cut points), so q(omega, omega') is the sum over every such way.
  const std::int32_t K = track_count_;
  const auto& current = tracks_[static_cast<std::size_t>(slot)].obs;
  const auto n = static_cast<std::int32_t>(current.size());
  const auto n_target = static_cast<std::int32_t>(target.size());
  std::int32_t common = 0;
  while (common < std::min(n, n_target) &&
         current[static_cast<std::size_t>(common)] == target[static_cast<std::size_t>(common)])
    ++common;
  double total = kNegInf;
  if (common == 0) return total;
  const auto unassigned = [this](std::int32_t j) { return track_of_[static_cast<std::size_t>(j)] < 0; };
  if (common == n && n_target > n)
    total = logSumExp(total, logMoveProbability(Move::kExtension, K) - logCount(K) +
                                 logExtension(current.back(), target.subspan(static_cast<std::size_t>(n)), true,
                                              unassigned));
  if (common == n_target && n_target < n && n_target >= 2)
    total = logSumExp(total, logMoveProbability(Move::kReduction, K) - logCount(countTracksAtLeast(3)) -
                                 logCount(n - 2));
  // Update from cut `keep` re-extends current[keep - 1] = target[keep - 1] along target[keep..]:
  // every cut's path is a suffix of target. Its free set (unassigned, or this track's own
  // observations from position keep on) is the same for every cut on the candidates it looks at,
  // which all come after current[keep - 1] in time and so, if this track's, at position >= keep:
  // unassigned or this track's. So each step's terms are computed once, and each cut sums its
  // suffix in the order logExtension would, giving the same value bit for bit.
  const std::int32_t last_keep = std::min({common, n - 1, n_target - 1});
  if (last_keep < 1) return total;
  const auto free = [this, slot](std::int32_t j) {
    const std::int32_t owner = track_of_[static_cast<std::size_t>(j)];
    return owner < 0 || owner == slot;
  };
  const auto steps = static_cast<std::size_t>(n_target - 1);  // step m goes target[m] -> target[m + 1]
  step_cost_.resize(steps);
  step_feasible_.resize(steps);
  for (std::size_t m = 0; m < steps; ++m) {
    const std::int32_t from = target[m];
    const std::int32_t next = target[m + 1];
    step_feasible_[m] = free(next) && problem_.linked(from, next);
    if (!step_feasible_[m]) continue;
    const std::int32_t gaps = freeGaps(from, free);
    step_cost_[m] = logCount(gaps) + logCount(counts_[static_cast<std::size_t>(problem_.tick(next) - problem_.tick(from))]);
  }
  const double stop = freeGaps(target.back(), free) > 0 ? log_stop_ : 0.0;
  const double log_cut = logMoveProbability(Move::kUpdate, K) - logCount(K) - logCount(n - 1);
  // Cuts whose path has an infeasible step add nothing: from the last infeasible step back.
  std::int32_t first_feasible_keep = 1;
  for (std::size_t m = 0; m < steps; ++m)
    if (!step_feasible_[m]) first_feasible_keep = static_cast<std::int32_t>(m) + 2;
  for (std::int32_t keep = first_feasible_keep; keep <= last_keep; ++keep) {
    double log_q = 0.0;
    for (auto m = static_cast<std::size_t>(keep - 1); m < steps; ++m) {
      if (m != static_cast<std::size_t>(keep - 1)) log_q += log_go_on_;
      log_q -= step_cost_[m];
    }
    total = logSumExp(total, log_cut + (log_q + stop));
  }
  return total;
}

void Sampler::proposeSingleTrack(Move move, std::int32_t slot, std::span<const std::int32_t> target,
                                 double log_q_forward, common::Stream& rng) {
  const auto& track = tracks_[static_cast<std::size_t>(slot)];
  backup_a_.assign(track.obs.begin(), track.obs.end());
  const double old_score = track.score;
  const double score = problem_.trackScore(target);
  setTrack(slot, target, score);
  const double log_q_reverse = logSingleTrackProposal(slot, backup_a_);
  if (accept(score - old_score + log_q_reverse - log_q_forward, rng))
    ++stats_.accepted[static_cast<std::size_t>(move)];
  else
    setTrack(slot, backup_a_, old_score);
}

void Sampler::trackSwitch(common::Stream& rng) {
  const std::int32_t K = track_count_;
  const auto a = static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(K)));
  auto b = static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(K - 1)));
  if (b >= a) ++b;
  const std::int32_t points = switchPoints(a, b, -1, nullptr);
  if (points == 0) return;
  std::array<std::int32_t, 2> cut{};
  switchPoints(a, b, static_cast<std::int32_t>(rng.below(static_cast<std::uint64_t>(points))), &cut);
  const auto [p, q] = cut;
  const auto& A = tracks_[static_cast<std::size_t>(a)];
  const auto& B = tracks_[static_cast<std::size_t>(b)];
  backup_a_.assign(A.obs.begin(), A.obs.end());
  backup_b_.assign(B.obs.begin(), B.obs.end());
  const double old_a = A.score;
  const double old_b = B.score;
  target_a_.assign(backup_a_.begin(), backup_a_.begin() + p);
  target_a_.insert(target_a_.end(), backup_b_.begin() + q, backup_b_.end());
  target_b_.assign(backup_b_.begin(), backup_b_.begin() + q);
  target_b_.insert(target_b_.end(), backup_a_.begin() + p, backup_a_.end());
  const double score_a = problem_.trackScore(target_a_);
  const double score_b = problem_.trackScore(target_b_);
  // The pair is drawn in either order with the same result ((a, b, p, q) and (b, a, q, p)), and the
  // reverse switch uses the same pair at the same K: the pair's probability cancels in the ratio.
  const double log_forward = -logCount(points);
  setTrack(a, target_a_, score_a);
  setTrack(b, target_b_, score_b);
  const double log_reverse = -logCount(switchPoints(a, b, -1, nullptr));
  if (accept(score_a + score_b - old_a - old_b + log_reverse - log_forward, rng)) {
    ++stats_.accepted[static_cast<std::size_t>(Move::kSwitch)];
  } else {
    setTrack(a, backup_a_, old_a);
    setTrack(b, backup_b_, old_b);
  }
}

}  // namespace wsn::supernode::mcmcda

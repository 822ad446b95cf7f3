// The MCMCDA Markov chain (Oh et al. Algorithm 1; moves of Oh, Russell & Sastry, IEEE TAC 2009):
// Metropolis-Hastings over partitions of a Problem's observations, with exact proposal
// probabilities so that its stationary distribution is the posterior of eq. (3).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "common/rng.hpp"
#include "supernode/mcmcda/count_tree.hpp"
#include "supernode/mcmcda/problem.hpp"

namespace wsn::supernode::mcmcda {

/// The eight moves: five pairs (birth/death, split/merge, extension/reduction, and the two
/// self-reverse moves update and switch).
enum class Move : int { kBirth, kDeath, kSplit, kMerge, kExtension, kReduction, kUpdate, kSwitch };
inline constexpr int kMoveCount = 8;
std::string_view moveName(Move move);

/// A partition omega: tracks as observation indices in tick order; every index not in a track is a
/// false alarm (or, for an anchor, a track that ended).
using Partition = std::vector<std::vector<std::int32_t>>;

/// Sorts tracks by first observation: one canonical form per partition.
void canonicalise(Partition& partition);

/// Empty string when `partition` is a member of Omega for `problem` (§III-B: disjoint tracks of at
/// least two observations, one per tick, consecutive ones linked, anchors only first), else what
/// is wrong.
std::string validatePartition(const Problem& problem, const Partition& partition);

/// log pi(omega) up to the constant of eq. (3): the sum of the tracks' Problem::trackScore.
double logPosterior(const Problem& problem, const Partition& partition);

/// Proposed and accepted counts per move.
struct MoveStats {
  std::array<std::uint64_t, kMoveCount> proposed{};
  std::array<std::uint64_t, kMoveCount> accepted{};
};

/// How the sampler finds birth's starting points and merge's pairs. Both ways give the same sets
/// in the same order, so the chain is the same; only the cost differs. A rescan of the window
/// costs O(window) for each birth, death, split and merge; kept sets cost O(log window) for each
/// observation that changes hands, in every move. Kept sets win on large windows (the
/// aggregator's, 4,500 observations at 10^6 sensors); on a supernode's (~100) neither does.
enum class ProposalSets { kBySize, kRescan, kKept };

/// Windows of at least this many observations keep their proposal sets (ProposalSets::kBySize).
/// wsn_mcmcda_bench's samplerChain measures both ways by load (medians of 3, nmc = 1000): rescans
/// 20-35 % faster at 20-82 observations (a supernode's), 12 % at 324; kept sets 16 % faster at 1,303.
inline constexpr std::int32_t kKeepProposalSetsFrom = 512;

class Sampler {
 public:
  /// The problem must outlive the sampler. Starts from the empty partition (all false alarms).
  explicit Sampler(const Problem& problem, ProposalSets sets = ProposalSets::kBySize);

  /// Sets the chain's state (and the best state) to `partition`; throws std::invalid_argument when
  /// it is not a member of Omega.
  void setState(const Partition& partition);

  /// One Metropolis-Hastings iteration; keeps the best state seen.
  void step(common::Stream& rng);
  void run(std::int64_t iterations, common::Stream& rng) {
    for (std::int64_t n = 0; n < iterations; ++n) step(rng);
  }

  double logPosterior() const { return log_posterior_; }
  double bestLogPosterior() const { return best_log_posterior_; }
  /// The current / best state, canonical.
  Partition state() const;
  Partition bestState() const;
  /// Label of every observation in the current state: the index of the first observation of its
  /// track, or -1. Equal labels <=> equal partitions; for histograms (no allocation).
  void labels(std::vector<std::int32_t>& out) const;
  std::int32_t trackCount() const { return track_count_; }
  const MoveStats& stats() const { return stats_; }

  /// Birth's starting points (unassigned observations with an unassigned candidate successor) in
  /// index order, and merge's pairs as (last observation of the first track, first observation of
  /// the second), a candidate successor of it, in the order the moves draw them. For tests;
  /// allocates.
  std::vector<std::int32_t> birthStarts();
  std::vector<std::array<std::int32_t, 2>> mergePairs();

 private:
  struct Track {
    std::vector<std::int32_t> obs;
    double score = 0.0;
  };
  // Move proposals. Each computes the forward proposal probability in the current state, applies
  // the change, computes the reverse probability in the new state, and keeps or undoes it.
  void birth(common::Stream& rng);
  void death(common::Stream& rng);
  void split(common::Stream& rng);
  void merge(common::Stream& rng);
  void extension(common::Stream& rng);
  void reduction(common::Stream& rng);
  void update(common::Stream& rng);
  void trackSwitch(common::Stream& rng);

  /// Replaces track `slot`'s observations by `target` (same first observation) through the
  /// single-track family (extension, reduction, update), accepting or undoing.
  void proposeSingleTrack(Move move, std::int32_t slot, std::span<const std::int32_t> target, double log_q_forward,
                          common::Stream& rng);
  /// log of the probability that extension, reduction or update of track `slot` (in the current
  /// state) proposes `target` — the sum over every way they can produce it.
  double logSingleTrackProposal(std::int32_t slot, std::span<const std::int32_t> target) const;

  /// Samples the extension process from `from` into `tail` (cleared first): stop with gamma (never
  /// before the first step when `forced`), else a gap uniform among those with a free candidate,
  /// then a free candidate uniformly. Returns log q of the path, or NaN when forced but impossible.
  template <class Free>
  double sampleExtension(std::int32_t from, bool forced, const Free& free, common::Stream& rng,
                         std::vector<std::int32_t>& tail) const;
  /// log q of the extension process producing exactly `tail` from `from`; -inf if it cannot.
  template <class Free>
  double logExtension(std::int32_t from, std::span<const std::int32_t> tail, bool forced, const Free& free) const;
  /// Free candidates of `from` per gap into counts_ (index = gap); returns how many gaps have one.
  template <class Free>
  std::int32_t freeGaps(std::int32_t from, const Free& free) const;

  // Birth's starting points and merge's pairs (proposal_sets.cpp): on a large window they live in
  // counting trees (a count per observation, per track slot), so that a move draws from them
  // without rescanning the window: the rescans for births, deaths, splits and merges were a fifth
  // of the aggregator's time at 10^6 sensors (about 5,000 observations). The starting points
  // follow each observation that changes between unassigned and taken; merge's pairs are brought
  // up to date when a move needs them, from the tracks whose ends changed since (rebuilt when more
  // changed than a rescan costs).
  std::int32_t birthStartCount();
  std::int32_t pickBirthStart(std::int32_t k);
  std::int32_t mergePairCount();
  std::array<std::int32_t, 2> pickMergePair(std::int32_t k);
  std::int32_t mergePairsFrom(std::int32_t slot) const;
  void refreshMergePairs();
  /// Observation j went from unassigned to a track / from a track to unassigned.
  void taken(std::int32_t j);
  void released(std::int32_t j);
  /// Notes a first element that came or went (changed_firsts_) or a slot whose track changed
  /// (changed_slots_), for the next refresh of merge's pairs.
  void noteChange(std::vector<std::int32_t>& changes, std::int32_t item);
  /// Whether observation j is the first of a track: the second half of a merge pair.
  bool startsTrack(std::int32_t j) const {
    return track_of_[static_cast<std::size_t>(j)] >= 0 && position_[static_cast<std::size_t>(j)] == 0;
  }
  std::span<const std::int32_t> predecessors(std::int32_t j) const {
    return {pred_.data() + pred_start_[static_cast<std::size_t>(j)],
            static_cast<std::size_t>(pred_start_[static_cast<std::size_t>(j) + 1] - pred_start_[static_cast<std::size_t>(j)])};
  }
  std::int32_t countTracksAtLeast(std::size_t length) const;
  /// Valid (p, q) cut points of a switch between tracks a and b; the k-th one into *pick when k >= 0.
  std::int32_t switchPoints(std::int32_t a, std::int32_t b, std::int32_t k, std::array<std::int32_t, 2>* pick) const;
  double logMoveProbability(Move move, std::int32_t tracks) const;
  double logCount(std::int64_t n) const {
    return static_cast<std::size_t>(n) < log_count_.size() ? log_count_[static_cast<std::size_t>(n)]
                                                           : std::log(static_cast<double>(n));
  }
  bool accept(double log_ratio, common::Stream& rng);

  std::int32_t addTrack(std::span<const std::int32_t> obs, double score);
  void removeTrack(std::int32_t slot);
  void setTrack(std::int32_t slot, std::span<const std::int32_t> obs, double score);
  void noteBest();
  /// The canonical partition an assignment array (slot of each observation, -1) describes.
  Partition partitionOf(const std::vector<std::int32_t>& track_of) const;

  const Problem& problem_;
  std::vector<Track> tracks_;  // [0, track_count_) are live; later slots keep their capacity
  std::int32_t track_count_ = 0;
  std::vector<std::int32_t> track_of_;  // slot of each observation's track, -1 when unassigned
  std::vector<std::int32_t> position_;  // index of each assigned observation within its track
  double log_posterior_ = 0.0;
  std::vector<std::int32_t> best_track_of_;
  double best_log_posterior_ = 0.0;
  MoveStats stats_;
  std::vector<double> log_count_;  // log(k), k < size
  double log_stop_ = 0.0;           // log gamma
  double log_go_on_ = 0.0;          // log(1 - gamma)
  std::vector<std::int32_t> pred_start_;  // candidate predecessors in CSR form, in index order
  std::vector<std::int32_t> pred_;
  bool keep_sets_ = false;
  static constexpr std::int32_t kUnassigned = -1;
  static constexpr std::int32_t kLeaving = -2;  // within setTrack only: taken, maybe to be released
  std::vector<std::int32_t> free_successors_;  // unassigned candidate successors of each observation
  CountTree birth_starts_;                     // 1 per unassigned observation with a free successor
  CountTree merge_pairs_;                 // per slot, the merge pairs it is the first track of
  std::vector<std::int32_t> pairs_of_slot_;
  std::vector<std::int32_t> changed_slots_;  // slots whose track changed since the refresh
  std::vector<std::int32_t> changed_firsts_;  // observations that were or became a first element
  bool rebuild_merge_pairs_ = true;
  std::size_t change_capacity_ = 0;  // beyond this many changes a rebuild is cheaper
  // Scratch, sized once in the constructor so that no iteration allocates.
  mutable std::vector<std::int32_t> counts_;
  mutable std::vector<double> step_cost_;  // logSingleTrackProposal: per step of the target
  mutable std::vector<char> step_feasible_;
  std::vector<std::int32_t> rescanned_starts_;  // by rescan: the starting points, the merge pairs
  std::vector<std::array<std::int32_t, 2>> rescanned_pairs_;
  std::vector<std::int32_t> tail_;
  std::vector<std::int32_t> target_a_;
  std::vector<std::int32_t> target_b_;
  std::vector<std::int32_t> backup_a_;
  std::vector<std::int32_t> backup_b_;
};

}  // namespace wsn::supernode::mcmcda

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

class Sampler {
 public:
  /// The problem must outlive the sampler. Starts from the empty partition (all false alarms).
  explicit Sampler(const Problem& problem);

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

  /// Unassigned observations with an unassigned successor (birth's starting points).
  std::int32_t collectBirthStarts(std::vector<std::int32_t>* out) const;
  /// Ordered pairs (u, v) of tracks with v's first observation a successor of u's last.
  std::int32_t collectMergePairs(std::vector<std::array<std::int32_t, 2>>* out) const;
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
  // Scratch, sized once in the constructor so that no iteration allocates.
  mutable std::vector<std::int32_t> counts_;
  mutable std::vector<std::int32_t> scratch_list_;
  mutable std::vector<std::array<std::int32_t, 2>> scratch_pairs_;
  std::vector<std::int32_t> tail_;
  std::vector<std::int32_t> target_a_;
  std::vector<std::int32_t> target_b_;
  std::vector<std::int32_t> backup_a_;
  std::vector<std::int32_t> backup_b_;
};

}  // namespace wsn::supernode::mcmcda

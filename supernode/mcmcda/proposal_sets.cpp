// Birth's starting points and merge's pairs, the two sets the sampler's moves draw from: kept
// in counting trees on large windows, found by a rescan of the state on small ones (sampler.hpp,
// ProposalSets). Either way, the same sets in the same order.
#include <stdexcept>

#include "supernode/mcmcda/sampler.hpp"

namespace wsn::supernode::mcmcda {

void Sampler::noteChange(std::vector<std::int32_t>& changes, std::int32_t item) {
  if (!keep_sets_ || rebuild_merge_pairs_) return;
  if (changes.size() == change_capacity_) rebuild_merge_pairs_ = true;
  else changes.push_back(item);
}

void Sampler::taken(std::int32_t j) {
  if (!keep_sets_) return;
  // j was unassigned: a starting point iff it had a free successor; and it is no longer a free
  // successor of its predecessors.
  if (free_successors_[static_cast<std::size_t>(j)] > 0) birth_starts_.add(j, -1);
  for (const std::int32_t i : predecessors(j))
    if (--free_successors_[static_cast<std::size_t>(i)] == 0 && track_of_[static_cast<std::size_t>(i)] == kUnassigned)
      birth_starts_.add(i, -1);
}

void Sampler::released(std::int32_t j) {
  if (!keep_sets_) return;
  if (free_successors_[static_cast<std::size_t>(j)] > 0) birth_starts_.add(j, 1);
  for (const std::int32_t i : predecessors(j))
    if (free_successors_[static_cast<std::size_t>(i)]++ == 0 && track_of_[static_cast<std::size_t>(i)] == kUnassigned)
      birth_starts_.add(i, 1);
}

std::int32_t Sampler::birthStartCount() {
  if (keep_sets_) return birth_starts_.total();
  rescanned_starts_.clear();
  for (std::int32_t i = 0; i < problem_.size(); ++i) {
    if (track_of_[static_cast<std::size_t>(i)] >= 0) continue;
    for (const std::int32_t j : problem_.successors(i))
      if (track_of_[static_cast<std::size_t>(j)] < 0) {
        rescanned_starts_.push_back(i);
        break;
      }
  }
  return static_cast<std::int32_t>(rescanned_starts_.size());
}

std::int32_t Sampler::pickBirthStart(std::int32_t k) {
  return keep_sets_ ? birth_starts_.select(k).index : rescanned_starts_[static_cast<std::size_t>(k)];
}

std::int32_t Sampler::mergePairsFrom(std::int32_t slot) const {
  if (slot >= track_count_) return 0;
  std::int32_t count = 0;
  for (const std::int32_t j : problem_.successors(tracks_[static_cast<std::size_t>(slot)].obs.back()))
    if (startsTrack(j)) ++count;
  return count;
}

void Sampler::refreshMergePairs() {
  const auto update = [this](std::int32_t slot) {
    const std::int32_t now = mergePairsFrom(slot);
    auto& was = pairs_of_slot_[static_cast<std::size_t>(slot)];
    if (now != was) merge_pairs_.add(slot, now - was);
    was = now;
  };
  if (rebuild_merge_pairs_) {
    for (std::int32_t slot = 0; slot < merge_pairs_.size(); ++slot)
      pairs_of_slot_[static_cast<std::size_t>(slot)] = mergePairsFrom(slot);
    merge_pairs_.assign(pairs_of_slot_);
    rebuild_merge_pairs_ = false;
  } else {
    // A slot's pairs depend on its last element and on which of that element's successors are
    // first elements: a track whose end changed is a changed slot; one whose end stayed has its
    // end among the predecessors of a first element that came or went.
    for (const std::int32_t slot : changed_slots_) update(slot);
    for (const std::int32_t first : changed_firsts_)
      for (const std::int32_t p : predecessors(first)) {
        const std::int32_t slot = track_of_[static_cast<std::size_t>(p)];
        if (slot >= 0 && tracks_[static_cast<std::size_t>(slot)].obs.back() == p) update(slot);
      }
  }
  changed_slots_.clear();
  changed_firsts_.clear();
}

std::int32_t Sampler::mergePairCount() {
  if (keep_sets_) {
    refreshMergePairs();
    return merge_pairs_.total();
  }
  rescanned_pairs_.clear();
  for (std::int32_t u = 0; u < track_count_; ++u)
    for (const std::int32_t j : problem_.successors(tracks_[static_cast<std::size_t>(u)].obs.back()))
      if (startsTrack(j)) rescanned_pairs_.push_back({u, track_of_[static_cast<std::size_t>(j)]});
  return static_cast<std::int32_t>(rescanned_pairs_.size());
}

std::array<std::int32_t, 2> Sampler::pickMergePair(std::int32_t k) {
  if (!keep_sets_) return rescanned_pairs_[static_cast<std::size_t>(k)];
  const auto [u, offset] = merge_pairs_.select(k);
  std::int32_t left = offset;
  for (const std::int32_t j : problem_.successors(tracks_[static_cast<std::size_t>(u)].obs.back()))
    if (startsTrack(j) && left-- == 0)
      return {u, track_of_[static_cast<std::size_t>(j)]};
  throw std::logic_error("mcmcda: merge pair count out of step with the state");
}

std::vector<std::int32_t> Sampler::birthStarts() {
  std::vector<std::int32_t> out;
  const std::int32_t count = birthStartCount();
  for (std::int32_t k = 0; k < count; ++k) out.push_back(pickBirthStart(k));
  return out;
}

std::vector<std::array<std::int32_t, 2>> Sampler::mergePairs() {
  std::vector<std::array<std::int32_t, 2>> out;
  const std::int32_t count = mergePairCount();
  for (std::int32_t k = 0; k < count; ++k) {
    const auto [u, v] = pickMergePair(k);
    out.push_back({tracks_[static_cast<std::size_t>(u)].obs.back(), tracks_[static_cast<std::size_t>(v)].obs.front()});
  }
  return out;
}

}  // namespace wsn::supernode::mcmcda

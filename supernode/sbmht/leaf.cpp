#include "supernode/sbmht/leaf.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

namespace wsn::supernode::sbmht {

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

// Leaves of one tree agree on all but their last few ticks, so their histories share a prefix as
// long as the track is old; it is skipped in blocks with memcmp (equality only: memcmp's byte order
// is not the order of signed ints).
bool historyLess(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b) {
  constexpr std::size_t kBlock = 64;
  const std::size_t n = std::min(a.size(), b.size());
  std::size_t i = 0;
  while (i + kBlock <= n && std::memcmp(a.data() + i, b.data() + i, kBlock * sizeof(std::int32_t)) == 0) i += kBlock;
  for (; i < n; ++i)
    if (a[i] != b[i]) return a[i] < b[i];
  return a.size() < b.size();
}

bool leafOrder(const Leaf& a, const Leaf& b) {
  if (a.tree != b.tree) return a.tree < b.tree;
  return historyLess(a.history, b.history);
}

std::span<const std::int32_t> historyThrough(const Leaf& leaf, std::int32_t tick) {
  std::int32_t t = leaf.first_tick;
  for (std::size_t k = 0; k < leaf.history.size(); ++k) {
    if (leaf.history[k] != kTickEnd) continue;
    if (t == tick) return std::span(leaf.history).first(k + 1);
    ++t;
  }
  return leaf.history;
}

void keepMarked(std::vector<Leaf>& leaves, const std::vector<char>& keep) {
  std::vector<Leaf> kept;
  kept.reserve(leaves.size());
  for (std::size_t k = 0; k < leaves.size(); ++k)
    if (keep[k]) kept.push_back(std::move(leaves[k]));
  leaves = std::move(kept);
}

std::span<const Leaf> leavesOfTree(std::span<const Leaf> leaves, common::TrackId tree) {
  const auto first = std::partition_point(leaves.begin(), leaves.end(), [&](const Leaf& l) { return l.tree < tree; });
  const auto last = std::partition_point(first, leaves.end(), [&](const Leaf& l) { return l.tree == tree; });
  return {first, last};
}

const Leaf* representative(std::span<const Leaf> tree) {
  const Leaf* chosen = nullptr;
  for (const auto& leaf : tree) {
    if (leaf.best) return &leaf;
    if (!chosen || leaf.probability > chosen->probability ||
        (leaf.probability == chosen->probability && leaf.score.score > chosen->score.score))
      chosen = &leaf;
  }
  return chosen;
}

void confirmByCount(Leaf& leaf, std::int32_t confirm_reports) {
  if (leaf.score.status == TrackStatus::tentative && leaf.hits >= confirm_reports)
    leaf.score.status = TrackStatus::confirmed;
}

}  // namespace wsn::supernode::sbmht

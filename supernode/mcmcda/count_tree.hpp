// A counting (Fenwick) tree: a count per index with O(log n) updates, the total in O(1) and the
// index holding the k-th unit in O(log n). The sampler keeps its proposal sets in these so that
// a move draws from them without rescanning the window.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace wsn::supernode::mcmcda {

class CountTree {
 public:
  /// Where the k-th unit lies: the index, and k's offset among that index's units.
  struct Pick {
    std::int32_t index = 0;
    std::int32_t offset = 0;
  };

  /// n indices, every count 0.
  explicit CountTree(std::int32_t n = 0) { reset(n); }

  void reset(std::int32_t n) {
    tree_.assign(static_cast<std::size_t>(n) + 1, 0);
    total_ = 0;
    high_bit_ = 1;
    while (high_bit_ * 2 <= n) high_bit_ *= 2;
  }

  /// Replaces every count at once, in O(n): counts.size() must equal size().
  void assign(std::span<const std::int32_t> counts) {
    const auto n = tree_.size() - 1;
    total_ = 0;
    for (std::size_t i = 1; i <= n; ++i) {
      tree_[i] = counts[i - 1];
      total_ += counts[i - 1];
    }
    for (std::size_t i = 1; i <= n; ++i)
      if (const std::size_t parent = i + (i & (~i + 1)); parent <= n) tree_[parent] += tree_[i];
  }

  void add(std::int32_t index, std::int32_t delta) {
    total_ += delta;
    for (auto i = static_cast<std::size_t>(index) + 1; i < tree_.size(); i += i & (~i + 1)) tree_[i] += delta;
  }

  std::int32_t total() const { return total_; }
  std::int32_t size() const { return static_cast<std::int32_t>(tree_.size()) - 1; }

  /// The index whose units hold the k-th one (0 <= k < total()), counting units in index order.
  Pick select(std::int32_t k) const {
    std::size_t at = 0;
    for (std::size_t step = static_cast<std::size_t>(high_bit_); step > 0; step /= 2)
      if (at + step < tree_.size() && tree_[at + step] <= k) {
        at += step;
        k -= tree_[at];
      }
    return {static_cast<std::int32_t>(at), k};
  }

 private:
  std::vector<std::int32_t> tree_;  // 1-based: tree_[i] sums the counts of (i - lowbit(i), i]
  std::int32_t total_ = 0;
  std::int32_t high_bit_ = 1;
};

}  // namespace wsn::supernode::mcmcda

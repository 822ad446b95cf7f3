// A vector of at most N elements stored inline: a measurement's values, noise and class
// likelihoods travel with every report and observation, and a heap allocation per copy made the
// tracking engines up to 3x slower (bench/rulebased_bench). Only what those members need.
#pragma once

#include <algorithm>
#include <array>
#include <compare>
#include <cstddef>
#include <initializer_list>
#include <stdexcept>
#include <string>

namespace wsn::common {

template <typename T, std::size_t N>
class InlineVector {
 public:
  InlineVector() = default;
  /// Throws std::length_error for more than N elements.
  InlineVector(std::initializer_list<T> items) { assign(items.begin(), items.end()); }

  template <typename It>
  void assign(It first, It last) {
    const auto n = static_cast<std::size_t>(std::distance(first, last));
    if (n > N) throw std::length_error("InlineVector: " + std::to_string(n) + " elements, room for " + std::to_string(N));
    std::copy(first, last, items_.begin());
    size_ = n;
  }
  /// `n` copies of `value`; throws std::length_error for n > N.
  void assign(std::size_t n, const T& value) {
    if (n > N) throw std::length_error("InlineVector: " + std::to_string(n) + " elements, room for " + std::to_string(N));
    std::fill_n(items_.begin(), n, value);
    size_ = n;
  }
  void push_back(const T& value) {
    if (size_ == N) throw std::length_error("InlineVector: full at " + std::to_string(N) + " elements");
    items_[size_++] = value;
  }
  void clear() { size_ = 0; }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  static constexpr std::size_t capacity() { return N; }
  const T* data() const { return items_.data(); }
  T& operator[](std::size_t i) { return items_[i]; }
  const T& operator[](std::size_t i) const { return items_[i]; }
  T* begin() { return items_.data(); }
  T* end() { return items_.data() + size_; }
  const T* begin() const { return items_.data(); }
  const T* end() const { return items_.data() + size_; }

  friend bool operator==(const InlineVector& a, const InlineVector& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end());
  }
  friend auto operator<=>(const InlineVector& a, const InlineVector& b) {
    return std::lexicographical_compare_three_way(a.begin(), a.end(), b.begin(), b.end());
  }

 private:
  std::array<T, N> items_{};
  std::size_t size_ = 0;
};

}  // namespace wsn::common

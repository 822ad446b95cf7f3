// The counting tree behind MCMCDA's kept proposal sets: totals and the k-th unit, by hand.
#include "supernode/mcmcda/count_tree.hpp"

#include <catch2/catch.hpp>
#include <vector>

using wsn::supernode::mcmcda::CountTree;

TEST_CASE("count tree finds the index holding the k-th unit and its offset there", "[mcmcda]") {
  // Counts 2, 0, 3, 1 at indices 0..3: units 0-1 at index 0, 2-4 at index 2, 5 at index 3.
  CountTree tree(4);
  const std::vector<std::int32_t> counts{2, 0, 3, 1};
  tree.assign(counts);
  CHECK(tree.total() == 6);
  const std::vector<std::pair<std::int32_t, std::int32_t>> expected{{0, 0}, {0, 1}, {2, 0}, {2, 1}, {2, 2}, {3, 0}};
  for (std::int32_t k = 0; k < 6; ++k) {
    INFO("unit " << k);
    CHECK(tree.select(k).index == expected[static_cast<std::size_t>(k)].first);
    CHECK(tree.select(k).offset == expected[static_cast<std::size_t>(k)].second);
  }
}

TEST_CASE("count tree updates agree with a tree assigned the same counts", "[mcmcda]") {
  // 13 indices (not a power of two), changed one by one, against assign() of the same counts.
  std::vector<std::int32_t> counts(13, 0);
  CountTree added(13);
  for (std::int32_t step = 0; step < 60; ++step) {
    const std::int32_t i = (step * 7) % 13;
    const std::int32_t delta = counts[static_cast<std::size_t>(i)] > 0 && step % 3 == 0 ? -1 : 1;
    counts[static_cast<std::size_t>(i)] += delta;
    added.add(i, delta);
    CountTree assigned(13);
    assigned.assign(counts);
    INFO("step " << step);
    REQUIRE(added.total() == assigned.total());
    std::int32_t unit = 0;
    for (std::int32_t index = 0; index < 13; ++index)
      for (std::int32_t offset = 0; offset < counts[static_cast<std::size_t>(index)]; ++offset, ++unit) {
        CHECK(added.select(unit).index == index);
        CHECK(added.select(unit).offset == offset);
        CHECK(assigned.select(unit).index == index);
      }
    CHECK(unit == added.total());
  }
}

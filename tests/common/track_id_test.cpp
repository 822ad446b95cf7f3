#include "common/track_id.hpp"

#include <catch2/catch.hpp>
#include <stdexcept>

namespace wsn::common::track_id {
namespace {

TEST_CASE("a supernode serial puts the supernode plus one above bit 48") {
  // Supernode 2, serial 5: (2 + 1) * 2^48 + 5 = 844424930131973.
  const TrackId id = supernodeSerial(2, 5);
  CHECK(id == 844424930131973ULL);
  CHECK(ownedBySupernode(id));
  CHECK(supernodeOf(id) == 2);
  CHECK(serialOf(id) == 5);
  CHECK_FALSE(isBirth(id));
  CHECK(label(id) == "2:5");
}

TEST_CASE("a birth id names the tick and sensor of the report that started the track") {
  // Supernode 0, tick 7, sensor 42: serial 7 * 2^24 + 42 = 117440554, plus 1 * 2^48.
  const TrackId id = birth(0, 7, 42);
  CHECK(id == (1ULL << 48) + 117440554ULL);
  CHECK(isBirth(id));
  CHECK(birthTick(id) == 7);
  CHECK(birthSensor(id) == 42);
  CHECK(label(id) == "0:t7s42");
  CHECK_THROWS_AS(birth(0, 1 << 24, 0), std::out_of_range);
  CHECK_THROWS_AS(birth(0, 1, 1u << 24), std::out_of_range);
}

TEST_CASE("an id space mints a supernode's serials or the aggregator's global ids") {
  CHECK(Space::ofSupernode(3).mint(9) == supernodeSerial(3, 9));
  CHECK(label(Space::ofSupernode(3).mint(9)) == "3:9");
  // The aggregator's ids are the bare serial, below 2^48, shown as gN: both track associations
  // (gated merge and MCMCDA) mint in this one space.
  const Space aggregator = Space::ofAggregator();
  CHECK(aggregator.isAggregator());
  CHECK_FALSE(Space::ofSupernode(0).isAggregator());
  CHECK(aggregator.mint(7) == 7);
  CHECK_FALSE(ownedBySupernode(aggregator.mint(7)));
  CHECK(label(aggregator.mint(7)) == "g7");
  CHECK_THROWS_AS(aggregator.mint(kSerialLimit), std::out_of_range);
  CHECK_THROWS_AS(Space::ofSupernode(0).mint(kSerialLimit), std::out_of_range);
}

}  // namespace
}  // namespace wsn::common::track_id

#include "supernode/window_replay.hpp"

#include <catch2/catch.hpp>
#include <cstdint>
#include <vector>

#include "tests/supernode/test_support.hpp"

namespace wsn::supernode {
namespace {

using test::observation;

/// An engine's item that writes down every tick it went through: 10 t + the slot's size for a tick
/// t it was processed at, -t for a tick it was caught up over.
struct Tally {
  common::TrackId id = 0;
  std::vector<std::int32_t> seen;
};

bool byId(const Tally& a, const Tally& b) { return a.id < b.id; }

void tallyTick(std::vector<Tally>& items, std::int32_t tick, std::span<const common::Observation> slot) {
  for (auto& item : items) item.seen.push_back(10 * tick + static_cast<std::int32_t>(slot.size()));
}

void tallyCatchUp(Tally& item, std::int32_t first_tick, std::int32_t anchor_tick) {
  for (std::int32_t t = first_tick; t <= anchor_tick; ++t) item.seen.push_back(-t);
}

void step(WindowReplay<Tally>& replay, const ObservationWindow& window) {
  replay.step(window, tallyTick, tallyCatchUp);
}

TEST_CASE("the window replay processes every tick once with its final contents, handoffs at their ticks",
          "[window_replay]") {
  ObservationWindow window(2);
  WindowReplay<Tally> replay(&Tally::id, &byId);
  replay.adopt(1, Tally{7, {}});

  window.advanceTo(1);  // window 1..1
  window.insert(observation(1, 1, 1.0, 1.0));
  step(replay, window);
  REQUIRE(replay.current().size() == 1);
  CHECK(replay.current()[0].seen == std::vector<std::int32_t>{11});  // tick 1, one report

  window.advanceTo(2);  // window 1..2
  window.insert(observation(2, 2, 1.0, 1.0));
  window.insert(observation(2, 2, 5.0, 5.0));
  step(replay, window);
  CHECK(replay.current()[0].seen == std::vector<std::int32_t>{11, 22});  // replayed from the anchor at 0

  window.advanceTo(3);  // window 2..3: tick 1 is folded into the anchor as last seen (one report)
  window.insert(observation(2, 3, 9.0, 9.0));  // late: it joins tick 2's slot
  step(replay, window);
  CHECK(replay.current()[0].seen == std::vector<std::int32_t>{11, 23, 30});
  CHECK(replay.currentTick() == 3);

  replay.release(7);  // gone now, and from every replay after tick 3
  CHECK(replay.current().empty());
  replay.adopt(2, Tally{9, {}});  // the anchor (tick 1) has not passed tick 2: it joins the fold
  replay.adopt(1, Tally{5, {}});  // the anchor passed tick 1: caught up over it first

  window.advanceTo(4);  // window 3..4: tick 2 is folded with its final three reports
  window.insert(observation(4, 4, 1.0, 1.0));
  step(replay, window);
  // 5: caught up over tick 1, then ticks 2 (3 reports), 3 (none) and 4 (one). 7 took part in tick 3
  // and left after it. 9: from tick 2 on.
  const auto& items = replay.current();
  REQUIRE(items.size() == 2);
  CHECK(items[0].id == 5);
  CHECK(items[0].seen == std::vector<std::int32_t>{-1, 23, 30, 41});
  CHECK(items[1].id == 9);
  CHECK(items[1].seen == std::vector<std::int32_t>{23, 30, 41});
  CHECK(replay.currentTick() == 4);
}

TEST_CASE("an adopted item replaces what the replay held of its track", "[window_replay]") {
  ObservationWindow window(3);
  WindowReplay<Tally> replay(&Tally::id, &byId);
  replay.adopt(1, Tally{4, {}});
  replay.adopt(1, Tally{2, {}});
  window.advanceTo(1);
  step(replay, window);
  replay.adopt(2, Tally{4, {100}});  // a newer handoff of track 4, its state at tick 1

  window.advanceTo(2);
  step(replay, window);
  const auto& items = replay.current();
  REQUIRE(items.size() == 2);  // in the engine's order (by id)
  CHECK(items[0].id == 2);
  CHECK(items[0].seen == std::vector<std::int32_t>{10, 20});
  CHECK(items[1].id == 4);
  CHECK(items[1].seen == std::vector<std::int32_t>{100, 20});  // tick 1 as the handoff brought it
}

TEST_CASE("the window replay does nothing before the window holds a tick", "[window_replay]") {
  ObservationWindow window(2);
  WindowReplay<Tally> replay(&Tally::id, &byId);
  replay.adopt(1, Tally{3, {}});
  step(replay, window);
  CHECK(replay.current().empty());
  CHECK(replay.currentTick() == 0);
}

}  // namespace
}  // namespace wsn::supernode

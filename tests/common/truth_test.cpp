#include "common/truth.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <set>

namespace wsn::common {
namespace {

/// Random births and deaths over [0, 100]^2: birth_rate 5e-4 * 10^4 = 5 births per tick.
Scenario randomScenario(std::uint64_t seed) {
  Scenario s;
  s.run.ticks = 40;
  s.run.seed = seed;
  s.targets.birth_rate = 5e-4;
  s.targets.death_probability = 0.05;
  return s;
}

TargetSpec scripted(std::int32_t appear, std::int32_t disappear, Vec2 position, Vec2 velocity) {
  TargetSpec t;
  t.appear_tick = appear;
  t.disappear_tick = disappear;
  t.position = position;
  t.velocity = velocity;
  return t;
}

/// The scripted target with `id` at `tick`, or nullptr when it is not alive then.
const TargetState* find(const Truth& truth, std::int32_t tick, TargetId id) {
  for (const auto& target : truth.at(tick))
    if (target.id == id) return &target;
  return nullptr;
}

TEST_CASE("truth is a pure function of scenario and seed", "[truth]") {
  const Truth a(truthConfig(randomScenario(7)));
  const Truth b(truthConfig(randomScenario(7)));
  REQUIRE(a.ticks() == 40);
  REQUIRE(a.targetCount() == b.targetCount());
  // 5 births per tick on average over 40 ticks: about 200 targets; zero would mean no births at all.
  CHECK(a.targetCount() > 100);
  for (std::int32_t t = 1; t <= a.ticks(); ++t) CHECK(a.at(t) == b.at(t));
}

TEST_CASE("another seed gives other targets", "[truth]") {
  const Truth a(truthConfig(randomScenario(7)));
  const Truth b(truthConfig(randomScenario(8)));
  bool differs = a.targetCount() != b.targetCount();
  for (std::int32_t t = 1; t <= a.ticks() && !differs; ++t) differs = a.at(t) != b.at(t);
  CHECK(differs);
}

TEST_CASE("targets are listed sorted by id, and nothing exists outside 1..T", "[truth]") {
  const Truth truth(truthConfig(randomScenario(3)));
  for (std::int32_t t = 1; t <= truth.ticks(); ++t) {
    const auto& now = truth.at(t);
    for (std::size_t i = 1; i < now.size(); ++i) CHECK(now[i - 1].id < now[i].id);
    for (const auto& target : now) CHECK(Rect{0, 0, 100, 100}.contains({target.x, target.y}));
  }
  CHECK(truth.at(0).empty());
  CHECK(truth.at(truth.ticks() + 1).empty());
  CHECK(truth.at(-5).empty());
}

TEST_CASE("scripted targets are alive from appear_tick up to but not including disappear_tick", "[truth]") {
  Scenario s;
  s.run.ticks = 20;
  s.dynamics.process_noise_sigma = 0.0;
  s.targets.scripted = {scripted(3, 7, {10, 10}, {1, 0}),   // id 0: ticks 3, 4, 5, 6
                        scripted(1, 0, {50, 50}, {0, 0}),   // id 1: every tick (0 = until T)
                        scripted(20, 0, {80, 80}, {0, 0})}; // id 2: the last tick only
  const Truth truth(truthConfig(s));
  CHECK(truth.targetCount() == 3);  // scripted targets take ids 0..n-1 in file order
  for (std::int32_t t = 1; t <= 20; ++t) {
    INFO("tick " << t);
    CHECK((find(truth, t, 0) != nullptr) == (t >= 3 && t < 7));
    CHECK(find(truth, t, 1) != nullptr);
    CHECK((find(truth, t, 2) != nullptr) == (t == 20));
  }
  // On its first tick a target is where the scenario puts it.
  REQUIRE(find(truth, 3, 0) != nullptr);
  CHECK(find(truth, 3, 0)->x == 10.0);
  CHECK(find(truth, 3, 0)->y == 10.0);
}

TEST_CASE("with zero process noise eq. 8 is exact constant velocity", "[truth]") {
  Scenario s;
  s.run.ticks = 30;
  s.dynamics.process_noise_sigma = 0.0;
  s.dynamics.delta = 0.5;
  // Dyadic values, so every sum below is exact in binary floating point.
  s.targets.scripted = {scripted(2, 0, {10.0, 80.0}, {1.5, -0.75})};
  const Truth truth(truthConfig(s));
  for (std::int32_t t = 2; t <= 30; ++t) {
    INFO("tick " << t);
    const TargetState* target = find(truth, t, 0);
    REQUIRE(target != nullptr);
    // Oh eq. 8 with w = 0: x_t = x_2 + (t - 2) delta v, v unchanged.
    CHECK(target->x == 10.0 + (t - 2) * 0.5 * 1.5);
    CHECK(target->y == 80.0 - (t - 2) * 0.5 * 0.75);
    CHECK(target->vx == 1.5);
    CHECK(target->vy == -0.75);
  }
}

TEST_CASE("a target that leaves the region disappears", "[truth]") {
  Scenario s;
  s.run.ticks = 10;
  s.dynamics.process_noise_sigma = 0.0;
  s.targets.scripted = {scripted(1, 0, {98.0, 50.0}, {1.0, 0.0})};
  const Truth truth(truthConfig(s));
  // x = 98, 99, 100 on ticks 1, 2, 3 (the edge belongs to the region); 101 on tick 4 is outside.
  CHECK(find(truth, 3, 0) != nullptr);
  CHECK(find(truth, 4, 0) == nullptr);
  CHECK(find(truth, 10, 0) == nullptr);  // and it does not come back
}

TEST_CASE("process noise moves targets off the straight line", "[truth]") {
  Scenario s;
  s.run.ticks = 20;
  s.targets.scripted = {scripted(1, 0, {50.0, 50.0}, {0.0, 0.0})};
  const Truth truth(truthConfig(s));
  const TargetState* target = find(truth, 20, 0);
  // q = 0.15 per tick: after 19 steps the velocity has a standard deviation of 0.15 sqrt(19) = 0.65 per
  // axis, so an exactly zero velocity would mean the noise was not applied.
  REQUIRE(target != nullptr);
  CHECK((target->vx != 0.0 || target->vy != 0.0));
}

TEST_CASE("random births draw per-axis speeds from the scenario's speed class", "[truth]") {
  // Oh §VII-A: slow [0, 1], medium [1, 2], fast [2, 5] per axis. Without process noise the
  // velocities stay as drawn at birth.
  struct Case {
    SpeedClass speed_class;
    double min;
    double max;
  };
  for (const Case c : {Case{SpeedClass::kSlow, 0.0, 1.0}, Case{SpeedClass::kMedium, 1.0, 2.0},
                       Case{SpeedClass::kFast, 2.0, 5.0}}) {
    Scenario s = randomScenario(11);
    s.dynamics.process_noise_sigma = 0.0;
    s.targets.speed_class = c.speed_class;
    const Truth truth(truthConfig(s));
    std::set<TargetId> seen;
    bool negative_vx = false;
    bool positive_vx = false;
    for (std::int32_t t = 1; t <= truth.ticks(); ++t)
      for (const auto& target : truth.at(t)) {
        seen.insert(target.id);
        CHECK(std::abs(target.vx) >= c.min);
        CHECK(std::abs(target.vx) <= c.max);
        CHECK(std::abs(target.vy) >= c.min);
        CHECK(std::abs(target.vy) <= c.max);
        negative_vx = negative_vx || target.vx < 0.0;
        positive_vx = positive_vx || target.vx > 0.0;
      }
    CHECK(seen.size() > 50);  // about 200 births; the checks above looked at many targets
    CHECK(negative_vx);       // signs are random
    CHECK(positive_vx);
  }
}

TEST_CASE("with death probability 1 a random target lives one tick, a scripted one is immortal", "[truth]") {
  Scenario s = randomScenario(5);
  s.targets.death_probability = 1.0;
  s.targets.scripted = {scripted(1, 0, {50.0, 50.0}, {0.0, 0.0})};
  s.dynamics.process_noise_sigma = 0.0;
  const Truth truth(truthConfig(s));
  // Every target alive at t - 1 dies at t with probability pz = 1, so a tick holds only that
  // tick's births, whose ids all exceed those of the tick before; the scripted id 0 stays.
  TargetId previous_max = 0;
  for (std::int32_t t = 1; t <= truth.ticks(); ++t) {
    TargetId min_random = INT32_MAX;
    TargetId max_random = 0;
    for (const auto& target : truth.at(t)) {
      if (target.id == 0) continue;
      min_random = std::min(min_random, target.id);
      max_random = std::max(max_random, target.id);
    }
    CHECK(find(truth, t, 0) != nullptr);
    if (max_random > 0) {
      CHECK(min_random > previous_max);
      previous_max = max_random;
    }
  }
}

}  // namespace
TEST_CASE("drawn targets live a drawn lifetime that fits the run, at the speed class, inside the region", "[truth]") {
  // Oh §VII-A: 10 targets appear and disappear at random times, T = 50. Without process noise a
  // drawn target moves in a straight line, so each one exists on exactly L consecutive ticks, L in
  // [25, 45], and its path stays 5 % in from the edges ([5, 95]^2) whenever the class allows it:
  // medium speed moves at most 2 x 44 = 88 < 90 per axis over a life, so it always does.
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    Scenario s;
    s.run.ticks = 50;
    s.run.seed = seed;
    s.dynamics.process_noise_sigma = 0.0;
    s.targets.count = 10;
    s.targets.lifetime_min = 25;
    s.targets.lifetime_max = 45;
    const Truth truth(truthConfig(s));
    REQUIRE(truth.targetCount() == 10);
    for (TargetId id = 0; id < 10; ++id) {
      std::int32_t first = 0, last = 0;
      for (std::int32_t t = 1; t <= 50; ++t) {
        const TargetState* now = find(truth, t, id);
        if (now == nullptr) continue;
        if (first == 0) first = t;
        CHECK(last == (first == t ? 0 : t - 1));  // consecutive ticks
        last = t;
        CHECK(now->x >= 5.0 - 1e-9);
        CHECK(now->x <= 95.0 + 1e-9);
        CHECK(now->y >= 5.0 - 1e-9);
        CHECK(now->y <= 95.0 + 1e-9);
        CHECK(std::abs(now->vx) >= 1.0);
        CHECK(std::abs(now->vx) <= 2.0);
        CHECK(std::abs(now->vy) >= 1.0);
        CHECK(std::abs(now->vy) <= 2.0);
      }
      REQUIRE(first > 0);
      const std::int32_t life = last - first + 1;
      CHECK(life >= 25);
      CHECK(life <= 45);
    }
  }
}

TEST_CASE("a drawn target too fast to stay its life crosses the region from edge to edge", "[truth]") {
  // Fast class, |v| per axis in [2, 5], lives of 40 ticks in [0, 100]^2: no start keeps such a
  // path inside for 39 steps (at least 78 per axis against 90 of room, often more), so each
  // start makes it stay in as long as any could: at least 90 / 5 = 18 steps, 19 ticks.
  Scenario s;
  s.run.ticks = 50;
  s.run.seed = 4;
  s.dynamics.process_noise_sigma = 0.0;
  s.targets.speed_class = SpeedClass::kFast;
  s.targets.count = 20;
  s.targets.lifetime_min = 40;
  s.targets.lifetime_max = 40;
  const Truth truth(truthConfig(s));
  for (TargetId id = 0; id < 20; ++id) {
    std::int32_t ticks_alive = 0;
    for (std::int32_t t = 1; t <= 50; ++t) ticks_alive += find(truth, t, id) != nullptr ? 1 : 0;
    CHECK(ticks_alive >= 19);
    CHECK(ticks_alive <= 40);
  }
}

TEST_CASE("drawn targets take ids after the scripted ones, and births after both", "[truth]") {
  Scenario s = randomScenario(5);
  s.targets.scripted = {scripted(1, 0, {50, 50}, {0, 0})};
  s.targets.count = 3;
  const Truth truth(truthConfig(s));
  CHECK(find(truth, 1, 0) != nullptr);
  std::set<TargetId> drawn;
  for (std::int32_t t = 1; t <= truth.ticks(); ++t)
    for (const auto& target : truth.at(t))
      if (target.id >= 1 && target.id <= 3) drawn.insert(target.id);
  CHECK(drawn == std::set<TargetId>{1, 2, 3});
  CHECK(truth.targetCount() > 4);
}

}  // namespace wsn::common

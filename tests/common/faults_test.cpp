// The scenario's faults tick by tick (common/faults.hpp): who is live, who dies or returns, which
// handoffs a partition cuts, what a burst does to pte, which ticks a supernode settles.
#include "common/faults.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <vector>

namespace wsn::common {
namespace {

/// 4 tiles, 3 supernodes: supernode 1 killed at 10, tile 2 paused on 5..7, supernode 2 paused
/// on 20..23, supernodes 0 and 2 partitioned on 30..31.
FaultPlan plan() {
  return FaultPlan({FaultSpec::kill(FaultRole::kSupernode, 1, 10), FaultSpec::pause(FaultRole::kNode, 2, 5, 3),
                    FaultSpec::pause(FaultRole::kSupernode, 2, 20, 4), FaultSpec::partition(0, 2, 30, 2)},
                   4, 3);
}

TEST_CASE("a kill holds from its tick on and a pause for exactly its ticks", "[faults]") {
  const FaultPlan p = plan();
  // Tile 2 is paused on ticks 5, 6, 7.
  CHECK(p.tileLive(2, 4));
  CHECK_FALSE(p.tileLive(2, 5));
  CHECK_FALSE(p.tileLive(2, 7));
  CHECK(p.tileLive(2, 8));
  CHECK(p.tileLive(1, 6));  // another tile
  // The pause of tile 2 is no pause of supernode 2, nor the other way round.
  CHECK(p.supernodeLive(2, 5));
  CHECK(p.tileLive(2, 21));
  CHECK(p.tileLive(1, 10));  // the kill of supernode 1 is no kill of tile 1
  // Supernode 1 dies at 10 for good.
  CHECK(p.supernodeLive(1, 9));
  CHECK_FALSE(p.supernodeLive(1, 10));
  CHECK_FALSE(p.supernodeLive(1, 11));
  CHECK_FALSE(p.supernodeLive(1, 1000000));
  // Supernode 2 is paused on 20..23.
  CHECK(p.supernodeLive(2, 19));
  CHECK_FALSE(p.supernodeLive(2, 20));
  CHECK_FALSE(p.supernodeLive(2, 23));
  CHECK(p.supernodeLive(2, 24));
  // A partition kills nobody.
  CHECK(p.supernodeLive(0, 30));
  CHECK(p.supernodeLive(2, 31));

  CHECK(p.liveSupernodes(9) == std::vector<bool>{true, true, true});
  CHECK(p.liveSupernodes(10) == std::vector<bool>{true, false, true});
  CHECK(p.liveSupernodes(21) == std::vector<bool>{true, false, false});
  CHECK(p.liveSupernodes(24) == std::vector<bool>{true, false, true});

  CHECK(p.liveTileCount(4) == 4);
  CHECK(p.liveTileCount(5) == 3);
  CHECK(p.liveTileCount(7) == 3);
  CHECK(p.liveTileCount(8) == 4);
}

TEST_CASE("a plan without faults keeps everyone live and every pte", "[faults]") {
  const FaultPlan p({}, 2, 2);
  CHECK(p.empty());
  CHECK_FALSE(plan().empty());
  CHECK(p.tileLive(1, 1));
  CHECK(p.supernodeLive(1, 50));
  CHECK(p.liveSupernodes(3) == std::vector<bool>{true, true});
  CHECK(p.liveTileCount(3) == 2);
  CHECK_FALSE(p.burstPte(3).has_value());
  CHECK_FALSE(p.partitioned(0, 1, 3));
  CHECK(p.dyingAt(3).empty());
  CHECK(p.settles(0, 1, 10, 100));
}

TEST_CASE("a supernode dies on its first dead tick and returns on its first live one", "[faults]") {
  const FaultPlan p = plan();
  CHECK_FALSE(p.supernodeDies(1, 9));
  CHECK(p.supernodeDies(1, 10));
  CHECK_FALSE(p.supernodeDies(1, 11));  // already dead
  CHECK_FALSE(p.supernodeReturns(1, 11));
  CHECK_FALSE(p.supernodeReturns(1, 100));  // a kill never returns

  CHECK(p.supernodeDies(2, 20));
  CHECK_FALSE(p.supernodeDies(2, 21));
  CHECK_FALSE(p.supernodeReturns(2, 20));
  CHECK_FALSE(p.supernodeReturns(2, 23));
  CHECK(p.supernodeReturns(2, 24));
  CHECK_FALSE(p.supernodeReturns(2, 25));
  CHECK_FALSE(p.supernodeReturns(0, 1));  // live from the start is no return

  CHECK(p.dyingAt(10) == std::vector<std::int32_t>{1});
  CHECK(p.dyingAt(20) == std::vector<std::int32_t>{2});
  CHECK(p.dyingAt(11).empty());
  CHECK(p.dyingAt(24).empty());
  // The pause of tile 2 at 5 is no supernode dying.
  CHECK(p.dyingAt(5).empty());
  // Two at once, in index order whatever the order of the list.
  const FaultPlan two({FaultSpec::kill(FaultRole::kSupernode, 2, 7), FaultSpec::pause(FaultRole::kSupernode, 0, 7, 2)}, 1, 3);
  CHECK(two.dyingAt(7) == std::vector<std::int32_t>{0, 2});
  CHECK(two.supernodeReturns(0, 9));
}

TEST_CASE("a partition cuts the handoffs between its two supernodes, both ways, only inside its ticks",
          "[faults]") {
  const FaultPlan p = plan();  // 0 and 2 on 30..31
  CHECK_FALSE(p.partitioned(0, 2, 29));
  CHECK(p.partitioned(0, 2, 30));
  CHECK(p.partitioned(2, 0, 30));
  CHECK(p.partitioned(0, 2, 31));
  CHECK(p.partitioned(2, 0, 31));
  CHECK_FALSE(p.partitioned(0, 2, 32));
  CHECK_FALSE(p.partitioned(2, 0, 32));
  // Other pairs are not cut.
  CHECK_FALSE(p.partitioned(0, 1, 30));
  CHECK_FALSE(p.partitioned(1, 2, 30));
  CHECK_FALSE(p.partitioned(0, 0, 30));
  CHECK_FALSE(p.partitioned(2, 2, 30));
}

TEST_CASE("a burst replaces pte for its ticks, overlapping bursts taking the highest", "[faults]") {
  // 0.4 on 40..44, 0.9 on 42..43, 0.2 on 43..46 (the lowest last, so "the last one wins" fails).
  const FaultPlan p({FaultSpec::burstLoss(0.4, 40, 5), FaultSpec::burstLoss(0.9, 42, 2), FaultSpec::burstLoss(0.2, 43, 4)}, 1, 1);
  CHECK_FALSE(p.burstPte(39).has_value());
  CHECK(p.burstPte(40) == std::optional<double>(0.4));
  CHECK(p.burstPte(41) == std::optional<double>(0.4));
  CHECK(p.burstPte(42) == std::optional<double>(0.9));
  CHECK(p.burstPte(43) == std::optional<double>(0.9));
  CHECK(p.burstPte(44) == std::optional<double>(0.4));
  CHECK(p.burstPte(45) == std::optional<double>(0.2));
  CHECK(p.burstPte(46) == std::optional<double>(0.2));
  CHECK_FALSE(p.burstPte(47).has_value());
  // A burst of pte 0 is a burst: a lossless stretch, not "no burst".
  const FaultPlan lossless({FaultSpec::burstLoss(0.0, 3, 1)}, 1, 1);
  REQUIRE(lossless.burstPte(3).has_value());
  CHECK(*lossless.burstPte(3) == 0.0);
  CHECK_FALSE(lossless.burstPte(4).has_value());
  // Bursts kill nobody.
  CHECK(p.supernodeLive(0, 42));
  CHECK(p.tileLive(0, 42));
}

TEST_CASE("a supernode settles a tick only when live from it through its window or the run's end",
          "[faults]") {
  const FaultPlan p = plan();  // supernode 2 paused on 20..23, supernode 1 killed at 10
  // ws = 10: tick 10 needs 10..19, tick 11 needs 11..20.
  CHECK(p.settles(2, 10, 10, 100));
  CHECK_FALSE(p.settles(2, 11, 10, 100));
  CHECK_FALSE(p.settles(2, 20, 10, 100));
  CHECK_FALSE(p.settles(2, 23, 10, 100));
  CHECK(p.settles(2, 24, 10, 100));
  // ws = 5: tick 5 needs 5..9, tick 6 needs 6..10 and supernode 1 is dead at 10.
  CHECK(p.settles(1, 5, 5, 100));
  CHECK_FALSE(p.settles(1, 6, 5, 100));
  CHECK(p.settles(0, 6, 5, 100));
  // ws = 1: the tick itself.
  CHECK(p.settles(1, 9, 1, 100));
  CHECK_FALSE(p.settles(1, 10, 1, 100));
  // The run's end clips the window: with a kill at 60 and a run of 55 ticks, tick 50 settles at
  // the run's end (50..55 live); in a run of 60 ticks it would need tick 59, fine, but 51 needs 60.
  const FaultPlan late({FaultSpec::kill(FaultRole::kSupernode, 0, 60)}, 1, 2);
  CHECK(late.settles(0, 50, 10, 55));
  CHECK(late.settles(0, 51, 10, 55));
  CHECK(late.settles(0, 50, 10, 60));
  CHECK_FALSE(late.settles(0, 51, 10, 60));
  CHECK_FALSE(late.settles(0, 51, 10, 100));
}

TEST_CASE("a process fault is found at the tick it begins, for its role and index only", "[faults]") {
  const FaultPlan p = plan();
  const auto killed = p.processFaultAt(FaultRole::kSupernode, 1, 10);
  REQUIRE(killed.has_value());
  CHECK(*killed == FaultSpec::kill(FaultRole::kSupernode, 1, 10));
  CHECK_FALSE(p.processFaultAt(FaultRole::kSupernode, 1, 11).has_value());  // not where it holds
  CHECK_FALSE(p.processFaultAt(FaultRole::kSupernode, 1, 9).has_value());
  CHECK_FALSE(p.processFaultAt(FaultRole::kNode, 1, 10).has_value());       // another role
  CHECK_FALSE(p.processFaultAt(FaultRole::kSupernode, 0, 10).has_value());  // another index
  const auto paused = p.processFaultAt(FaultRole::kNode, 2, 5);
  REQUIRE(paused.has_value());
  CHECK(*paused == FaultSpec::pause(FaultRole::kNode, 2, 5, 3));
  CHECK_FALSE(p.processFaultAt(FaultRole::kSupernode, 2, 5).has_value());
  CHECK(p.processFaultAt(FaultRole::kSupernode, 2, 20) == std::optional<FaultSpec>(FaultSpec::pause(FaultRole::kSupernode, 2, 20, 4)));
  // A partition stops no process.
  CHECK_FALSE(p.processFaultAt(FaultRole::kSupernode, 0, 30).has_value());
  CHECK_FALSE(p.processFaultAt(FaultRole::kSupernode, 2, 30).has_value());
}

TEST_CASE("a fault describes itself and knows its last tick", "[faults]") {
  CHECK(FaultSpec::kill(FaultRole::kSupernode, 2, 40).describe() == "kill of supernode 2 at tick 40");
  CHECK(FaultSpec::kill(FaultRole::kNode, 0, 3).describe() == "kill of node 0 at tick 3");
  CHECK(FaultSpec::pause(FaultRole::kNode, 3, 5, 4).describe() == "pause of node 3 at tick 5 for 4 ticks");
  CHECK(FaultSpec::partition(0, 2, 30, 2).describe() == "partition between supernodes 0 and 2 at tick 30 for 2 ticks");
  CHECK(FaultSpec::burstLoss(0.25, 7, 3).describe() == "burst loss (pte 0.25) at tick 7 for 3 ticks");

  CHECK(FaultSpec::kill(FaultRole::kSupernode, 2, 40).lastTick() == std::numeric_limits<std::int32_t>::max());
  CHECK(FaultSpec::pause(FaultRole::kNode, 3, 5, 4).lastTick() == 8);
  CHECK(FaultSpec::pause(FaultRole::kNode, 3, 5, 1).lastTick() == 5);
  CHECK(FaultSpec::partition(0, 2, 30, 2).lastTick() == 31);
  CHECK(FaultSpec::burstLoss(0.5, 7, 3).lastTick() == 9);

  CHECK(std::string(faultActionName(FaultAction::kKill)) == "kill");
  CHECK(std::string(faultActionName(FaultAction::kPause)) == "pause");
  CHECK(std::string(faultActionName(FaultAction::kPartition)) == "partition");
  CHECK(std::string(faultActionName(FaultAction::kBurstLoss)) == "burst_loss");
  CHECK(std::string(faultRoleName(FaultRole::kNode)) == "node");
  CHECK(std::string(faultRoleName(FaultRole::kSupernode)) == "supernode");
}

TEST_CASE("a restart ends a kill and names the new process by its first tick", "[faults]") {
  // Supernode 1 killed at 10, back at 20, killed again at 30, back at 40; supernode 0 never hit.
  const FaultPlan p({FaultSpec::kill(FaultRole::kSupernode, 1, 10), FaultSpec::restart(FaultRole::kSupernode, 1, 40),
                     FaultSpec::kill(FaultRole::kSupernode, 1, 30), FaultSpec::restart(FaultRole::kSupernode, 1, 20)},
                    2, 2);
  CHECK(p.supernodeLive(1, 9));
  CHECK_FALSE(p.supernodeLive(1, 10));
  CHECK_FALSE(p.supernodeLive(1, 19));
  CHECK(p.supernodeLive(1, 20));
  CHECK(p.supernodeLive(1, 29));
  CHECK_FALSE(p.supernodeLive(1, 30));
  CHECK_FALSE(p.supernodeLive(1, 39));
  CHECK(p.supernodeLive(1, 40));
  CHECK(p.supernodeLive(1, 1000));
  // Back afresh at each restart, dying at each kill.
  CHECK(p.supernodeReturns(1, 20));
  CHECK(p.supernodeReturns(1, 40));
  CHECK_FALSE(p.supernodeReturns(1, 21));
  CHECK(p.supernodeDies(1, 10));
  CHECK(p.supernodeDies(1, 30));
  CHECK(p.restartsAt(20) == std::vector<std::uint32_t>{1});
  CHECK(p.restartsAt(40) == std::vector<std::uint32_t>{1});
  CHECK(p.restartsAt(10).empty());
  CHECK(p.restartsAt(21).empty());
  // The process live at a tick started at 1, 20 or 40; supernode 0's always at 1.
  CHECK(p.incarnation(FaultRole::kSupernode, 1, 5) == 1);
  CHECK(p.incarnation(FaultRole::kSupernode, 1, 20) == 20);
  CHECK(p.incarnation(FaultRole::kSupernode, 1, 35) == 20);
  CHECK(p.incarnation(FaultRole::kSupernode, 1, 40) == 40);
  CHECK(p.incarnation(FaultRole::kSupernode, 0, 40) == 1);
  CHECK(p.killEnds(FaultSpec::kill(FaultRole::kSupernode, 1, 10)) == 20);
  CHECK(p.killEnds(FaultSpec::kill(FaultRole::kSupernode, 1, 30)) == 40);
  CHECK_FALSE(p.killEnds(FaultSpec::kill(FaultRole::kSupernode, 0, 10)));
  CHECK_FALSE(p.killEnds(FaultSpec::restart(FaultRole::kSupernode, 1, 20)));  // only a kill ends
  // A restart starts no process fault of its own; the settled ticks skip what the kill took.
  CHECK_FALSE(p.processFaultAt(FaultRole::kSupernode, 1, 20));
  CHECK(p.settles(1, 20, 5, 100));
  CHECK_FALSE(p.settles(1, 26, 5, 100));
  CHECK(FaultSpec::restart(FaultRole::kSupernode, 1, 20).describe() == "restart of supernode 1 at tick 20");
  CHECK(FaultSpec::restart(FaultRole::kSupernode, 1, 20).lastTick() == 20);
}

TEST_CASE("processes are drawn without replacement, ascending, the same for the same seed and item", "[faults]") {
  const std::vector<std::int32_t> eligible{1, 3, 4, 6, 7};
  const auto a = drawProcesses(7, 2, eligible, 3);
  CHECK(a == drawProcesses(7, 2, eligible, 3));
  REQUIRE(a.size() == 3);
  CHECK(std::is_sorted(a.begin(), a.end()));
  CHECK(std::adjacent_find(a.begin(), a.end()) == a.end());
  for (const auto i : a) CHECK(std::find(eligible.begin(), eligible.end(), i) != eligible.end());
  // All of them, none, and never more than there are.
  CHECK(drawProcesses(7, 2, eligible, 5) == eligible);
  CHECK(drawProcesses(7, 2, eligible, 0).empty());
  CHECK(drawProcesses(7, 2, eligible, 9) == eligible);
  // One of five over 5000 seeds: each about 1000 times (a binomial sd of 28; 5 sd either way).
  std::map<std::int32_t, int> times;
  for (std::uint64_t seed = 1; seed <= 5000; ++seed) ++times[drawProcesses(seed, 0, eligible, 1).at(0)];
  REQUIRE(times.size() == 5);
  for (const auto& [index, n] : times) CHECK(std::abs(n - 1000) < 140);
  // Another item of the same list draws from a stream of its own.
  int differ = 0;
  for (std::uint64_t seed = 1; seed <= 50; ++seed) differ += drawProcesses(seed, 0, eligible, 2) != drawProcesses(seed, 1, eligible, 2);
  CHECK(differ > 25);
}

}  // namespace
}  // namespace wsn::common

// The scenario's faults section (scenario/faults_section.cpp) through the public loader: read into
// Scenario::faults, checked with file:line errors, written back into a resolved scenario with
// each item's own keys only, and changed by --set like any other value.
#include <catch2/catch.hpp>

#include <set>
#include <string>
#include <vector>

#include "scenario/overrides.hpp"
#include "scenario/writer.hpp"
#include "tests/scenario/test_support.hpp"

namespace wsn::scenario {
namespace {

using namespace common;

using Catch::Matchers::Contains;

using test_support::errorOf;
using test_support::parse;

/// Three supernodes, 50 ticks, the default 2 node tiles; the faults list starts on line 7.
const std::string kHead =
    "name: f\n"                // 1
    "supernodes:\n"            // 2
    "  - {x: 25, y: 50}\n"     // 3
    "  - {x: 75, y: 50}\n"     // 4
    "  - {x: 50, y: 90}\n"     // 5
    "run: {ticks: 50}\n"       // 6
    "faults:\n";               // 7

/// One item of each action, lines 8 to 11.
const std::string kFaults = kHead +
                            "  - {tick: 10, action: kill, role: supernode, index: 1}\n"
                            "  - {tick: 5, action: pause, role: node, index: 1, ticks: 3}\n"
                            "  - {tick: 20, action: partition, between: [[supernode, 0], [supernode, 2]], ticks: 4}\n"
                            "  - {tick: 30, action: burst_loss, pte: 0.5, ticks: 2}\n";

/// kHead with the given items.
std::string withFaults(const std::string& items) { return kHead + items; }

TEST_CASE("a faults list loads into the scenario in file order", "[scenario][faults]") {
  const Scenario s = parse(kFaults);
  REQUIRE(s.faults.size() == 4);
  const FaultSpec& kill = s.faults[0];
  CHECK(kill.tick == 10);
  CHECK(kill.action == FaultAction::kKill);
  CHECK(kill.role == FaultRole::kSupernode);
  CHECK(kill.index == 1);
  const FaultSpec& pause = s.faults[1];
  CHECK(pause.tick == 5);
  CHECK(pause.action == FaultAction::kPause);
  CHECK(pause.role == FaultRole::kNode);
  CHECK(pause.index == 1);
  CHECK(pause.ticks == 3);
  const FaultSpec& cut = s.faults[2];
  CHECK(cut.tick == 20);
  CHECK(cut.action == FaultAction::kPartition);
  CHECK(cut.between == std::vector<std::int32_t>{0, 2});
  CHECK(cut.ticks == 4);
  const FaultSpec& loss = s.faults[3];
  CHECK(loss.tick == 30);
  CHECK(loss.action == FaultAction::kBurstLoss);
  CHECK(loss.pte == 0.5);
  CHECK(loss.ticks == 2);

  // No faults, an empty list and a null one are all no faults.
  CHECK(parse("name: f\n").faults.empty());
  CHECK(parse("name: f\nfaults: []\n").faults.empty());
  CHECK(parse("name: f\nfaults:\n").faults.empty());
  // The last tick of the run and the last index of each kind are fine.
  CHECK(parse(withFaults("  - {tick: 50, action: kill, role: node, index: 1}\n")).faults.size() == 1);
  CHECK(parse(withFaults("  - {tick: 50, action: pause, role: supernode, index: 2, ticks: 9}\n")).faults.size() == 1);
}

TEST_CASE("the resolved scenario writes each fault with its action's keys only and reads back equal",
          "[scenario][faults]") {
  const Scenario s = parse(kFaults);
  const std::string resolved = resolvedScenarioYaml(s);
  CHECK_THAT(resolved, Contains("faults:\n"
                                "  - {tick: 10, action: kill, role: supernode, index: 1}\n"
                                "  - {tick: 5, action: pause, role: node, index: 1, ticks: 3}\n"
                                "  - {tick: 20, action: partition, between: [[supernode, 0], [supernode, 2]], ticks: 4}\n"
                                "  - {tick: 30, action: burst_loss, pte: 0.5, ticks: 2}\n"));
  const Scenario back = parse(resolved);
  CHECK(back == s);
  CHECK(back.faults == s.faults);
  // Without faults the resolved file has no faults section at all.
  // ("defaults" in the header comment contains "faults", hence the line start.)
  CHECK_THAT(resolvedScenarioYaml(parse("name: f\n")), !Contains("\nfaults"));
  CHECK_THAT(resolvedScenarioYaml(parse("name: f\nfaults: []\n")), !Contains("\nfaults"));
  // Equality sees the faults: a scenario with another fault tick is another scenario.
  Scenario other = s;
  other.faults[0].tick = 11;
  CHECK_FALSE(other == s);
}

TEST_CASE("a fault item needs the keys of its action and refuses the others", "[scenario][faults][errors]") {
  CHECK(errorOf(withFaults("  - {tick: 10, action: kill, role: supernode}\n")) ==
        "s.yaml:8: 'faults[0]' (kill) needs 'index' (which process dies; or `count` in place of `index`, drawn by the seed)");
  CHECK(errorOf(withFaults("  - {tick: 10, action: pause, role: node, index: 1}\n")) ==
        "s.yaml:8: 'faults[0]' (pause) needs 'ticks' (which process stops, and for how long)");
  CHECK(errorOf(withFaults("  - {tick: 10, action: partition, ticks: 2}\n")) ==
        "s.yaml:8: 'faults[0]' (partition) needs 'between' (which two supernodes lose their handoffs, and for how "
        "long)");
  CHECK(errorOf(withFaults("  - {tick: 10, action: burst_loss, ticks: 2}\n")) ==
        "s.yaml:8: 'faults[0]' (burst_loss) needs 'pte' (the loss rate, and for how long)");
  // The second item, in block style: its first line.
  CHECK(errorOf(withFaults("  - {tick: 10, action: burst_loss, pte: 1, ticks: 2}\n"
                           "  - tick: 12\n"
                           "    action: kill\n"
                           "    index: 0\n")) ==
        "s.yaml:9: 'faults[1]' (kill) needs 'role' (which process dies; or `count` in place of `index`, drawn by the "
        "seed)");

  // A key of another action, on its own line.
  CHECK(errorOf(withFaults("  - {tick: 10, action: kill, role: supernode, index: 1, ticks: 3}\n")) ==
        "s.yaml:8: 'faults[0].ticks' is not a key of a kill fault; it takes role, index");
  CHECK(errorOf(withFaults("  - tick: 10\n"
                           "    action: burst_loss\n"
                           "    pte: 0.4\n"
                           "    ticks: 2\n"
                           "    role: node\n")) ==
        "s.yaml:12: 'faults[0].role' is not a key of a burst_loss fault; it takes pte, ticks");
  CHECK(errorOf(withFaults("  - {tick: 10, action: partition, between: [[supernode, 0], [supernode, 1]], ticks: 2, "
                           "pte: 0.1}\n")) ==
        "s.yaml:8: 'faults[0].pte' is not a key of a partition fault; it takes between, ticks");
  // tick and action are required whatever the action.
  CHECK_THAT(errorOf(withFaults("  - {action: kill, role: node, index: 0}\n")), Contains("s.yaml:8:") && Contains("tick"));
}

TEST_CASE("a fault must fall inside the run and hit a process of the cluster", "[scenario][faults][errors]") {
  CHECK(errorOf(withFaults("  - {tick: 51, action: kill, role: node, index: 0}\n")) ==
        "s.yaml:8: 'faults[0].tick' is 51, after the run's last tick 50 (run.ticks)");
  CHECK(errorOf(withFaults("  - action: burst_loss\n"
                           "    pte: 0.2\n"
                           "    ticks: 1\n"
                           "    tick: 70\n")) ==
        "s.yaml:11: 'faults[0].tick' is 70, after the run's last tick 50 (run.ticks)");
  CHECK(errorOf(withFaults("  - {tick: 5, action: kill, role: node, index: 2}\n")) ==
        "s.yaml:8: 'faults[0].index' is 2; the run has 2 node tiles (run.node_processes), 0 to 1");
  CHECK(errorOf(withFaults("  - tick: 5\n"
                           "    action: pause\n"
                           "    ticks: 2\n"
                           "    role: supernode\n"
                           "    index: 3\n")) ==
        "s.yaml:12: 'faults[0].index' is 3; the run has 3 supernodes, 0 to 2");
}

TEST_CASE("a partition names two different supernodes, each as a supernode and its index",
          "[scenario][faults][errors]") {
  const auto cut = [](const std::string& between) {
    return errorOf(withFaults("  - {tick: 5, action: partition, ticks: 2, between: " + between + "}\n"));
  };
  CHECK(cut("3") == "s.yaml:8: 'faults[0].between' must be [[supernode, A], [supernode, B]], got '3'");
  CHECK(cut("[[supernode, 0]]") == "s.yaml:8: 'faults[0].between' must be [[supernode, A], [supernode, B]], got a list");
  CHECK(cut("[[supernode, 0], [supernode, 1], [supernode, 2]]") ==
        "s.yaml:8: 'faults[0].between' must be [[supernode, A], [supernode, B]], got a list");
  CHECK(cut("[[node, 0], [supernode, 1]]") ==
        "s.yaml:8: 'faults[0].between[0]' must be [supernode, INDEX] (a partition cuts the handoffs between two "
        "supernodes), got a list");
  CHECK(cut("[[supernode, 0], 1]") ==
        "s.yaml:8: 'faults[0].between[1]' must be [supernode, INDEX] (a partition cuts the handoffs between two "
        "supernodes), got '1'");
  CHECK(cut("[[supernode, 0], [supernode, 3]]") == "s.yaml:8: 'faults[0].between[1][1]' must be in [0, 2], got 3");
  CHECK(cut("[[supernode, 1], [supernode, 1]]") ==
        "s.yaml:8: 'faults[0].between' names supernode 1 twice; expected two different supernodes");
  // In block style the bad pair names its own line.
  CHECK(errorOf(withFaults("  - tick: 5\n"
                           "    action: partition\n"
                           "    ticks: 2\n"
                           "    between:\n"
                           "      - [supernode, 0]\n"
                           "      - [node, 1]\n")) ==
        "s.yaml:13: 'faults[0].between[1]' must be [supernode, INDEX] (a partition cuts the handoffs between two "
        "supernodes), got a list");
}

TEST_CASE("a process is hit by one kill or pause at a time", "[scenario][faults][errors]") {
  // A pause on 10..14, then a kill at 14: overlapping, named at the second item's line.
  CHECK(errorOf(withFaults("  - {tick: 10, action: pause, role: supernode, index: 0, ticks: 5}\n"
                           "  - {tick: 14, action: kill, role: supernode, index: 0}\n")) ==
        "s.yaml:9: faults[1] (kill of supernode 0 at tick 14) overlaps faults[0] (pause of supernode 0 at tick 10 for 5 "
        "ticks); a process can be hit by one kill or pause at a time");
  // Nothing after a kill, even listed first.
  CHECK(errorOf(withFaults("  - {tick: 40, action: pause, role: node, index: 1, ticks: 2}\n"
                           "  - {tick: 10, action: kill, role: node, index: 1}\n")) ==
        "s.yaml:9: faults[1] (kill of node 1 at tick 10) overlaps faults[0] (pause of node 1 at tick 40 for 2 ticks); a "
        "process can be hit by one kill or pause at a time");
  // Back to back is fine, and so are the same index of the other role and another index.
  CHECK(parse(withFaults("  - {tick: 10, action: pause, role: supernode, index: 0, ticks: 5}\n"
                         "  - {tick: 15, action: kill, role: supernode, index: 0}\n"))
            .faults.size() == 2);
  CHECK(parse(withFaults("  - {tick: 10, action: kill, role: supernode, index: 1}\n"
                         "  - {tick: 12, action: kill, role: node, index: 1}\n"
                         "  - {tick: 12, action: pause, role: supernode, index: 0, ticks: 3}\n"))
            .faults.size() == 3);
  // A partition or a burst is no process fault.
  CHECK(parse(withFaults("  - {tick: 10, action: kill, role: supernode, index: 0}\n"
                         "  - {tick: 12, action: partition, between: [[supernode, 0], [supernode, 1]], ticks: 3}\n"
                         "  - {tick: 12, action: burst_loss, pte: 0.9, ticks: 3}\n"))
            .faults.size() == 3);
}

TEST_CASE("the faults must leave a live supernode at every tick", "[scenario][faults][errors]") {
  // The default single supernode.
  CHECK(errorOf("name: f\nfaults:\n  - {tick: 10, action: kill, role: supernode, index: 0}\n") ==
        "s.yaml:3: faults[0] (kill of supernode 0 at tick 10) leaves no live supernode at tick 10; at least one must be "
        "live at every tick to take the tracking groups");
  // Three supernodes: 1 killed at 10, 2 at 20, then 0 paused at 30.
  CHECK(errorOf(withFaults("  - {tick: 10, action: kill, role: supernode, index: 1}\n"
                           "  - {tick: 20, action: kill, role: supernode, index: 2}\n"
                           "  - {tick: 30, action: pause, role: supernode, index: 0, ticks: 2}\n")) ==
        "s.yaml:10: faults[2] (pause of supernode 0 at tick 30 for 2 ticks) leaves no live supernode at tick 30; at least "
        "one must be live at every tick to take the tracking groups");
  // A pause that ends before the last one dies is fine; so is killing nodes.
  CHECK(parse(withFaults("  - {tick: 10, action: pause, role: supernode, index: 0, ticks: 5}\n"
                         "  - {tick: 12, action: pause, role: supernode, index: 1, ticks: 5}\n"
                         "  - {tick: 15, action: kill, role: supernode, index: 2}\n"
                         "  - {tick: 2, action: kill, role: node, index: 0}\n"
                         "  - {tick: 2, action: kill, role: node, index: 1}\n"))
            .faults.size() == 5);
  // But all three down at once is not, whichever item comes last: 0 paused 10..14, 1 paused
  // 12..16, 2 killed at 14.
  CHECK_THAT(errorOf(withFaults("  - {tick: 14, action: kill, role: supernode, index: 2}\n"
                                "  - {tick: 10, action: pause, role: supernode, index: 0, ticks: 5}\n"
                                "  - {tick: 12, action: pause, role: supernode, index: 1, ticks: 5}\n")),
             Contains("leaves no live supernode at tick 14"));
}

TEST_CASE("an override (--set) changes a fault's value and is checked like the file", "[scenario][faults][overrides]") {
  const auto set = [](const std::string& text) { return std::vector<ScenarioOverride>{parseOverride(text)}; };
  const Scenario s = applyOverrides(kFaults, "s.yaml", set("faults[0].tick=5"));
  REQUIRE(s.faults.size() == 4);
  CHECK(s.faults[0].tick == 5);
  CHECK(s.faults[0].index == 1);
  CHECK(s.faults[1] == parse(kFaults).faults[1]);
  CHECK(applyOverrides(kFaults, "s.yaml", set("faults[3].pte=0.75")).faults[3].pte == 0.75);
  CHECK(applyOverrides(kFaults, "s.yaml", set("faults[2].between[1][1]=1")).faults[2].between ==
        std::vector<std::int32_t>{0, 1});
  // Lists are never extended: there is no fifth fault to set.
  CHECK_THROWS_AS(applyOverrides(kFaults, "s.yaml", set("faults[4].tick=3")), OverrideError);
  // An override that breaks a rule names the --set.
  std::string message;
  try {
    applyOverrides(kFaults, "s.yaml", set("faults[0].tick=60"));
  } catch (const OverrideError& error) {
    message = error.what();
  }
  CHECK(message == "--set faults[0].tick=60: 'faults[0].tick' is 60, after the run's last tick 50 (run.ticks)");
  message.clear();
  try {
    applyOverrides(kFaults, "s.yaml", set("run.ticks=25"));  // the burst at 30 now lies after the run
  } catch (const OverrideError& error) {
    message = error.what();
  }
  CHECK(message == "--set run.ticks=25: 'faults[3].tick' is 30, after the run's last tick 25 (run.ticks)");
}

TEST_CASE("a restart brings back a supernode that an earlier kill took", "[scenario][faults][errors]") {
  const auto s = parse(withFaults("  - {tick: 30, action: restart, role: supernode, index: 1}\n"
                                  "  - {tick: 10, action: kill, role: supernode, index: 1}\n"
                                  "  - {tick: 40, action: pause, role: supernode, index: 1, ticks: 5}\n"));
  REQUIRE(s.faults.size() == 3);
  CHECK(s.faults[0] == FaultSpec::restart(FaultRole::kSupernode, 1, 30));
  // Written back with its own keys, and read back equal.
  CHECK(resolvedScenarioYaml(s).find("  - {tick: 30, action: restart, role: supernode, index: 1}\n") != std::string::npos);
  CHECK(parse(resolvedScenarioYaml(s)).faults == s.faults);
  // Nothing to undo: no kill, a kill after it, a kill of another supernode, a second restart.
  const std::string no_kill =
      "s.yaml:8: faults[0] (restart of supernode 1 at tick 30) has no kill of supernode 1 before it that it undoes; a "
      "restart brings back a supernode that an earlier `kill` of the list took (and no restart since)";
  CHECK(errorOf(withFaults("  - {tick: 30, action: restart, role: supernode, index: 1}\n")) == no_kill);
  CHECK(errorOf(withFaults("  - {tick: 30, action: restart, role: supernode, index: 1}\n"
                           "  - {tick: 30, action: kill, role: supernode, index: 1}\n")) == no_kill);
  CHECK(errorOf(withFaults("  - {tick: 30, action: restart, role: supernode, index: 1}\n"
                           "  - {tick: 10, action: kill, role: supernode, index: 2}\n")) == no_kill);
  CHECK_THAT(errorOf(withFaults("  - {tick: 10, action: kill, role: supernode, index: 1}\n"
                                "  - {tick: 20, action: restart, role: supernode, index: 1}\n"
                                "  - {tick: 30, action: restart, role: supernode, index: 1}\n")),
             Contains("s.yaml:10: faults[2] (restart of supernode 1 at tick 30) has no kill of supernode 1 before it"));
  // Only a supernode restarts; the keys are those of a kill.
  CHECK(errorOf(withFaults("  - {tick: 10, action: kill, role: node, index: 1}\n"
                           "  - {tick: 20, action: restart, role: node, index: 1}\n")) ==
        "s.yaml:9: 'faults[1].role' is node; only a supernode restarts (a node tile's kill is for good, and a pause "
        "brings a tile back)");
  CHECK(errorOf(withFaults("  - {tick: 10, action: kill, role: supernode, index: 1}\n"
                           "  - {tick: 20, action: restart, role: supernode, index: 1, ticks: 3}\n")) ==
        "s.yaml:9: 'faults[1].ticks' is not a key of a restart fault; it takes role, index");
  CHECK_THAT(errorOf(withFaults("  - {tick: 20, action: restart, role: supernode, index: 3}\n")),
             Contains("'faults[0].index' is 3; the run has 3 supernodes, 0 to 2"));
  // A fault of the supernode while it is dead overlaps its kill; after the restart it does not.
  CHECK_THAT(errorOf(withFaults("  - {tick: 10, action: kill, role: supernode, index: 1}\n"
                                "  - {tick: 20, action: restart, role: supernode, index: 1}\n"
                                "  - {tick: 15, action: pause, role: supernode, index: 1, ticks: 2}\n")),
             Contains("faults[2] (pause of supernode 1 at tick 15 for 2 ticks) overlaps faults[0]"));
}

TEST_CASE("a kill with a count takes that many processes drawn from the seed among those no other item names",
          "[scenario][faults]") {
  // Supernode 0 is paused by another item: the two drawn are among 1 and 2, so they are 1 and 2.
  const auto both = parse(withFaults("  - {tick: 10, action: pause, role: supernode, index: 0, ticks: 3}\n"
                                     "  - {tick: 20, action: kill, role: supernode, count: 2}\n"));
  REQUIRE(both.faults.size() == 3);
  CHECK(both.faults[1].index == 1);
  CHECK(both.faults[2].index == 2);
  CHECK(both.faults[1].count == 2);
  CHECK(both.faults[1].describe() == "kill of supernode 1 at tick 20 (one of 2 drawn by the seed)");
  // One of three: the same for the same seed, and every supernode drawn by some seed of 1..30.
  std::set<std::int32_t> drawn;
  for (int seed = 1; seed <= 30; ++seed) {
    const std::string text = withFaults("  - {tick: 20, action: kill, role: supernode, count: 1}\n");
    const std::vector<ScenarioOverride> with_seed{parseOverride("run.seed=" + std::to_string(seed))};
    const auto a = applyOverrides(text, "s.yaml", with_seed);
    const auto b = applyOverrides(text, "s.yaml", with_seed);
    REQUIRE(a.faults.size() == 1);
    CHECK(a.faults == b.faults);
    drawn.insert(a.faults[0].index);
  }
  CHECK(drawn == std::set<std::int32_t>{0, 1, 2});
  // Written back as the item it came from, with what the seed drew, and read back equal.
  const std::string resolved = resolvedScenarioYaml(both);
  CHECK_THAT(resolved, Contains("  - {tick: 20, action: kill, role: supernode, count: 2}  # drawn from run.seed: "
                                "supernode 1, 2\n"));
  CHECK(parse(resolved).faults == both.faults);
  // Count 0 kills nothing: the baseline of a sweep over it.
  CHECK(parse(withFaults("  - {tick: 20, action: kill, role: supernode, count: 0}\n")).faults.empty());
  // Tiles are drawn among run.node_processes.
  const auto tiles = parse(withFaults("  - {tick: 20, action: kill, role: node, count: 2}\n"));
  REQUIRE(tiles.faults.size() == 2);
  CHECK(tiles.faults[0].index == 0);
  CHECK(tiles.faults[1].index == 1);
}

TEST_CASE("a kill's count must leave processes to draw and a live supernode, and replaces index", "[scenario][faults][errors]") {
  CHECK(errorOf(withFaults("  - {tick: 10, action: kill, role: supernode, index: 0}\n"
                           "  - {tick: 20, action: kill, role: supernode, count: 3}\n")) ==
        "s.yaml:9: 'faults[1].count' is 3; only 2 supernodes are free of the list's other faults to draw from");
  CHECK_THAT(errorOf(withFaults("  - {tick: 20, action: kill, role: supernode, count: 3}\n")),
             Contains("s.yaml:8: faults[0] (kill of supernode ") && Contains("leaves no live supernode at tick 20"));
  CHECK(errorOf(withFaults("  - {tick: 20, action: kill, role: supernode, index: 1, count: 1}\n")) ==
        "s.yaml:8: 'faults[0]' has both 'index' and 'count'; a kill names its process (`index`) or has `count` of them "
        "drawn by the seed");
  CHECK(errorOf(withFaults("  - {tick: 20, action: pause, role: supernode, index: 0, count: 1, ticks: 2}\n")) ==
        "s.yaml:8: 'faults[0].count' is not a key of a pause fault; it takes role, index, ticks");
  // A later item's message names its own item, whatever the draw expanded before it.
  CHECK_THAT(errorOf(withFaults("  - {tick: 5, action: kill, role: node, count: 2}\n"
                                "  - {tick: 30, action: restart, role: supernode, index: 1}\n")),
             Contains("s.yaml:9: faults[1] (restart of supernode 1 at tick 30) has no kill"));
}

}  // namespace
}  // namespace wsn::scenario

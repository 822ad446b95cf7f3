// What the scenario's faults did to a run (aggregator/fault_report.hpp): εK and mean OSPA before,
// during and after each fault, the tracks a dying supernode left and the adopters carried on,
// the handoffs a partition cut, and metrics.json's "faults" block.
#include "aggregator/fault_report.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "aggregator/run_scorer.hpp"
#include "tests/aggregator/test_support.hpp"

namespace wsn::aggregator {
namespace {

using common::FaultAction;
using common::FaultPlan;
using common::FaultRole;
using common::FaultSpec;
using test::track;




/// Windows (kill: ws = 3 ticks from its tick; the others their own length), in a 12-tick run:
///   0 kill of supernode 1 at 5:           before 2..4,  during 5..7,   after 8..10
///   1 pause of supernode 2 at 9 for 2:    before 7..8,  during 9..10,  after 11..12
///   2 partition 0-2 at 3 for 2:           before 1..2,  during 3..4,   after 5..6
///   3 burst at 11 for 4:                  before 7..10, during 11..12, after none
///   4 partition 0-1 at 1 for 2:           before none,  during 1..2,   after 3..4
///   5 burst at 8 for 2:                   before 6..7,  during 8..9 (no truth), after 10..11
///   6 kill of node 0 at 12:               before 9..11, during 12,     after none
///   7 partition 1-2 at 12 for 3:          during 12 (the handoffs of tick 13 on are past the run)
FaultPlan plan() {
  return FaultPlan({FaultSpec::kill(FaultRole::kSupernode, 1, 5),
                    FaultSpec::pause(FaultRole::kSupernode, 2, 9, 2), FaultSpec::partition(0, 2, 3, 2),
                    FaultSpec::burstLoss(0.3, 11, 4), FaultSpec::partition(0, 1, 1, 2), FaultSpec::burstLoss(0.6, 8, 2),
                    FaultSpec::kill(FaultRole::kNode, 0, 12), FaultSpec::partition(1, 2, 12, 3)},
                   2, 3);
}

/// K*_t, K_t, OSPA_t of ticks 1..12.
const std::vector<FaultTickScores> kScores = {
    {2, 2, 0.0}, {2, 1, 1.0}, {2, 2, 0.5}, {2, 3, 2.0}, {2, 0, 5.0}, {2, 1, 3.0},
    {2, 2, 1.0}, {0, 0, 0.0}, {0, 1, 5.0}, {1, 1, 0.5}, {1, 1, 0.0}, {1, 2, 2.5},
};

/// Running totals of handoffs partitions cut, as supernodes count them: a handoff written at t
/// is found cut at t + 1. Partition 4 (written 1, 2) cuts 1 at 2 and 1 at 3; partition 2
/// (written 3, 4) cuts 2 at 4 and 3 at 5; partition 7 (from 12) none inside the run.
const std::vector<std::uint64_t> kHandoffsLost = {0, 1, 2, 4, 7, 7, 7, 7, 7, 7, 7, 7};

common::TrackHandoff orphan(common::TrackId id) {
  common::TrackHandoff h;
  h.track = id;
  return h;
}

SupernodeTracks tracksOf(std::uint32_t supernode, const std::vector<common::TrackId>& ids) {
  SupernodeTracks out{supernode, {}};
  for (const auto id : ids) out.tracks.push_back(track(id, 1.0, 1.0));
  return out;
}

/// The report of plan() over kScores: supernode 1 leaves tracks 100, 101, 102 at its death (5),
/// which it reported itself at 4; supernode 2 leaves 200 at 9. Adopters report 101 at 6, 100 and
/// 101 at 7; 102 and 200 never come back.
FaultReport filled() {
  FaultReport report(plan(), 3, 12);
  report.addOrphans(1, 5, {orphan(100), orphan(101), orphan(102)});
  report.addOrphans(2, 9, {orphan(200)});
  for (std::int32_t t = 1; t <= 12; ++t) {
    std::vector<SupernodeTracks> live;
    if (t == 4) live = {tracksOf(1, {100, 102})};  // before the death: not carried on
    if (t == 6) live = {tracksOf(0, {7}), tracksOf(2, {101})};
    if (t == 7) live = {tracksOf(0, {100, 101})};
    if (t == 12) live = {tracksOf(0, {300})};
    report.addTick(t, kScores[static_cast<std::size_t>(t - 1)], live, kHandoffsLost[static_cast<std::size_t>(t - 1)]);
  }
  return report;
}

/// Checks one window: its bounds, εK and mean OSPA.
void checkWindow(const Json& w, std::int32_t first, std::int32_t last, double eps_k, double ospa) {
  CHECK(w.at("first_tick") == first);
  CHECK(w.at("last_tick") == last);
  REQUIRE(w.at("eps_k").is_number());
  CHECK(w.at("eps_k").get<double>() == Approx(eps_k).margin(1e-12));
  REQUIRE(w.at("ospa_mean").is_number());
  CHECK(w.at("ospa_mean").get<double>() == Approx(ospa).margin(1e-12));
}

TEST_CASE("each fault's windows give eps_k and mean OSPA before, during and after it", "[fault_report]") {
  const Json json = filled().json();
  REQUIRE(json.is_array());
  REQUIRE(json.size() == 8);
  // Kill at 5: |K - K*| = 1, 0, 1 over K* = 6; 2, 1, 0 over 6; 0, 1, 0 over 1.
  checkWindow(json[0].at("before"), 2, 4, 2.0 / 6.0, 3.5 / 3.0);
  checkWindow(json[0].at("during"), 5, 7, 3.0 / 6.0, 9.0 / 3.0);
  checkWindow(json[0].at("after"), 8, 10, 1.0, 5.5 / 3.0);
  // Pause at 9 for 2.
  checkWindow(json[1].at("before"), 7, 8, 0.0, 0.5);
  checkWindow(json[1].at("during"), 9, 10, 1.0, 2.75);
  checkWindow(json[1].at("after"), 11, 12, 0.5, 1.25);
  // Partition at 3 for 2.
  checkWindow(json[2].at("before"), 1, 2, 0.25, 0.5);
  checkWindow(json[2].at("during"), 3, 4, 0.25, 1.25);
  checkWindow(json[2].at("after"), 5, 6, 0.75, 4.0);
  // Burst at 11 for 4: "during" is clipped to the run's end and "after" is empty.
  checkWindow(json[3].at("before"), 7, 10, 1.0 / 3.0, 6.5 / 4.0);
  checkWindow(json[3].at("during"), 11, 12, 0.5, 1.25);
  CHECK(json[3].at("after").at("eps_k").is_null());
  CHECK(json[3].at("after").at("ospa_mean").is_null());
  // Partition at 1: nothing before the run's first tick.
  CHECK(json[4].at("before").at("first_tick") == 1);
  CHECK(json[4].at("before").at("eps_k").is_null());
  CHECK(json[4].at("before").at("ospa_mean").is_null());
  checkWindow(json[4].at("during"), 1, 2, 0.25, 0.5);
  checkWindow(json[4].at("after"), 3, 4, 0.25, 1.25);
  // Burst at 8 for 2: no truth during it, so εK is undefined while OSPA is not.
  CHECK(json[5].at("during").at("eps_k").is_null());
  CHECK(json[5].at("during").at("ospa_mean").get<double>() == Approx(2.5).margin(1e-12));
  checkWindow(json[5].at("before"), 6, 7, 1.0 / 4.0, 2.0);
  checkWindow(json[5].at("after"), 10, 11, 0.0, 0.25);
  // Kill of a node at 12: a window of 3 before, the run's last tick during.
  checkWindow(json[6].at("before"), 9, 11, 1.0 / 2.0, 5.5 / 3.0);
  checkWindow(json[6].at("during"), 12, 12, 1.0, 2.5);
  CHECK(json[6].at("after").at("eps_k").is_null());
}

TEST_CASE("a fault names itself with its action's keys only", "[fault_report]") {
  const Json json = filled().json();
  CHECK(json[0].at("tick") == 5);
  CHECK(json[0].at("action") == "kill");
  CHECK(json[0].at("what") == "kill of supernode 1 at tick 5");
  CHECK(json[0].at("role") == "supernode");
  CHECK(json[0].at("index") == 1);
  CHECK_FALSE(json[0].contains("ticks"));
  CHECK_FALSE(json[0].contains("pte"));
  CHECK_FALSE(json[0].contains("handoffs_lost"));

  CHECK(json[1].at("action") == "pause");
  CHECK(json[1].at("ticks") == 2);
  CHECK(json[1].at("index") == 2);

  CHECK(json[2].at("action") == "partition");
  CHECK(json[2].at("what") == "partition between supernodes 0 and 2 at tick 3 for 2 ticks");
  CHECK(json[2].at("ticks") == 2);
  CHECK_FALSE(json[2].contains("role"));
  CHECK_FALSE(json[2].contains("tracks_left"));

  CHECK(json[3].at("action") == "burst_loss");
  CHECK(json[3].at("pte") == 0.3);
  CHECK(json[3].at("ticks") == 4);
  CHECK_FALSE(json[3].contains("role"));
  CHECK_FALSE(json[3].contains("handoffs_lost"));

  // A node tile leaves no tracks.
  CHECK(json[6].at("role") == "node");
  CHECK(json[6].at("index") == 0);
  CHECK_FALSE(json[6].contains("tracks_left"));
  CHECK_FALSE(json[6].contains("rehome_ticks"));
}

TEST_CASE("a dying supernode's tracks are counted as carried on or lost, with the ticks it took",
          "[fault_report]") {
  const Json json = filled().json();
  // Supernode 1: 100, 101 and 102 left; 101 back at 6 (one tick after the death), 100 at 7.
  CHECK(json[0].at("tracks_left") == 3);
  CHECK(json[0].at("tracks_carried_on") == 2);
  CHECK(json[0].at("tracks_lost") == 1);
  CHECK(json[0].at("rehome_ticks") == 1);
  // Supernode 2: 200 never back.
  CHECK(json[1].at("tracks_left") == 1);
  CHECK(json[1].at("tracks_carried_on") == 0);
  CHECK(json[1].at("tracks_lost") == 1);
  CHECK(json[1].at("rehome_ticks").is_null());

  // A supernode that died with no tracks left nothing, and took no ticks.
  FaultReport bare(FaultPlan({FaultSpec::kill(FaultRole::kSupernode, 0, 2)}, 1, 2), 3, 4);
  for (std::int32_t t = 1; t <= 4; ++t) bare.addTick(t, {1, 1, 0}, {tracksOf(1, {5})}, 0);
  const Json none = bare.json();
  CHECK(none[0].at("tracks_left") == 0);
  CHECK(none[0].at("tracks_carried_on") == 0);
  CHECK(none[0].at("tracks_lost") == 0);
  CHECK(none[0].at("rehome_ticks").is_null());

  // An adopter reporting an orphan at the death tick itself: 0 ticks.
  FaultReport at_once(FaultPlan({FaultSpec::kill(FaultRole::kSupernode, 0, 2)}, 1, 2), 3, 4);
  at_once.addOrphans(0, 2, {orphan(5), orphan(6)});
  at_once.addTick(1, {1, 1, 0}, {tracksOf(0, {5, 6})}, 0);
  at_once.addTick(2, {1, 1, 0}, {tracksOf(1, {5})}, 0);
  at_once.addTick(3, {1, 1, 0}, {tracksOf(1, {5})}, 0);  // 5 again: counted once
  const Json once = at_once.json();
  CHECK(once[0].at("tracks_left") == 2);
  CHECK(once[0].at("tracks_carried_on") == 1);
  CHECK(once[0].at("tracks_lost") == 1);
  CHECK(once[0].at("rehome_ticks") == 0);
}

TEST_CASE("a partition's lost handoffs come from the running totals of its ticks", "[fault_report]") {
  const Json json = filled().json();
  // Written on 3 and 4, found cut on 4 and 5: 7 - 2.
  CHECK(json[2].at("handoffs_lost") == 5);
  // Written on 1 and 2, found cut on 2 and 3: 2 - 0.
  CHECK(json[4].at("handoffs_lost") == 2);
  // From tick 12 on: nothing found cut inside the run.
  CHECK(json[7].at("handoffs_lost") == 0);
}

TEST_CASE("metrics.json has a faults block only when the run had faults", "[fault_report][run_scorer][json]") {
  RunScorer scorer(kLiveStream, common::MetricsConfig{}, {{50, 50}});
  scorer.add(1, {test::target(1, 50, 50)}, {track(9, 50, 50)});
  const RunScores scores = scorer.finish();
  RunInfo info{"s", 1, 1, "gnn", 1, 0, "gated", "{\"version\":\"0.1.0\"}"};
  const std::string plain = metricsJson(info, scores, 1.0, 1.0);
  CHECK(plain.find("\"faults\"") == std::string::npos);

  info.faults = filled().json();
  const std::string text = metricsJson(info, scores, 1.0, 1.0);
  const auto json = Json::parse(text);
  REQUIRE(json.contains("faults"));
  CHECK(json.at("faults") == info.faults);
  CHECK(json.at("faults").size() == 8);
  // Before the provenance and timing lines, which stay last.
  CHECK(text.find("\"faults\"") < text.find("\"provenance\""));
  CHECK(text.find("\"faults\"") < text.find("\"timing\""));
  // Everything else is as without faults.
  auto without = json;
  without.erase("faults");
  auto expected = Json::parse(plain);
  without.erase("timing");
  expected.erase("timing");
  CHECK(without == expected);
}

TEST_CASE("a restarted supernode's tracks taken back are those the others held the tick before", "[fault_report]") {
  // Supernode 1 killed at 3, back at 6. At 5 the others hold 10, 11 and 12; from 6 supernode 1
  // reports 11 at 7 and 10 and 13 at 8 (13 is new: not taken back); supernode 0 keeps 12.
  FaultReport report(FaultPlan({FaultSpec::kill(FaultRole::kSupernode, 1, 3),
                                FaultSpec::restart(FaultRole::kSupernode, 1, 6)},
                               1, 2),
                     3, 10);
  for (std::int32_t t = 1; t <= 10; ++t) {
    std::vector<SupernodeTracks> live;
    if (t == 2) live = {tracksOf(1, {10, 11})};  // its own, before it died
    if (t == 5) live = {tracksOf(0, {10, 11, 12})};
    if (t == 6) live = {tracksOf(0, {10, 11, 12}), tracksOf(1, {})};
    if (t == 7) live = {tracksOf(0, {10, 12}), tracksOf(1, {11})};
    if (t >= 8) live = {tracksOf(0, {12}), tracksOf(1, {10, 11, 13})};
    report.addTick(t, {1, 1, 0}, live, 0);
  }
  const Json json = report.json();
  REQUIRE(json.size() == 2);
  CHECK(json[1].at("action") == "restart");
  CHECK(json[1].at("what") == "restart of supernode 1 at tick 6");
  CHECK(json[1].at("role") == "supernode");
  CHECK(json[1].at("index") == 1);
  CHECK(json[1].at("tracks_taken_back") == 2);
  CHECK(json[1].at("takeback_ticks") == 1);
  // One window (3 ticks) from the restart on is its "during".
  CHECK(json[1].at("during").at("first_tick") == 6);
  CHECK(json[1].at("during").at("last_tick") == 8);
  CHECK_FALSE(json[1].contains("ticks"));

  // Nothing handed back: no tick of taking back.
  FaultReport empty(FaultPlan({FaultSpec::kill(FaultRole::kSupernode, 1, 3),
                               FaultSpec::restart(FaultRole::kSupernode, 1, 6)},
                              1, 2),
                    3, 10);
  for (std::int32_t t = 1; t <= 10; ++t) empty.addTick(t, {1, 1, 0}, {tracksOf(0, {12})}, 0);
  CHECK(empty.json()[1].at("tracks_taken_back") == 0);
  CHECK(empty.json()[1].at("takeback_ticks").is_null());
}

}  // namespace
}  // namespace wsn::aggregator

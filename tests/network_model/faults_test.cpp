// The network model under the scenario's faults: the communication graph over the live supernodes
// (Oh §V's g(i) and shortest paths over the survivors), the topologies a run builds by live set,
// what a re-homing did, the router's burst losses and reports due at a dead supernode, and the
// run files that record them.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/faults.hpp"
#include "network_model/live_topologies.hpp"
#include "network_model/role_config.hpp"
#include "network_model/router.hpp"
#include "network_model/run_files.hpp"
#include "network_model/topology.hpp"

namespace nm = wsn::network_model;
using wsn::common::FaultAction;
using wsn::common::FaultPlan;
using wsn::common::FaultRole;
using wsn::common::FaultSpec;
using wsn::common::Report;
using wsn::common::SensorId;
using wsn::common::Vec2;

namespace {

/// Range 1 on the x axis: S0 at 0, sensors 0 and 1 at 1 and 2, S1 at 3, sensors 2..5 at 4..7,
/// S2 at 8.
///   all live:  g = (0, 1, 1, 1, 2, 2), hops = (1, 1, 1, 2, 2, 1).
///   S1 dead:   sensor 1 goes to S0 over sensor 0 (2 hops); sensor 2 (x = 4) is 4 from S0 and
///              from S2, so the tie gives it to S0, and S1 was its only relay to the left: it is
///              unreachable. Sensor 3 goes to S2 (3 hops). g = (0, 0, 0, 2, 2, 2),
///              hops = (1, 2, -1, 3, 2, 1).
const std::vector<Vec2> kSupernodes = {{0, 0}, {3, 0}, {8, 0}};
const std::vector<Vec2> kSensors = {{1, 0}, {2, 0}, {4, 0}, {5, 0}, {6, 0}, {7, 0}};
const std::vector<bool> kWithoutS1 = {true, false, true};

nm::TopologyConfig lineConfig(std::vector<bool> live = {}) {
  return nm::TopologyConfig{kSupernodes, 1.0, std::move(live)};
}

std::vector<std::uint32_t> groupsOf(const nm::Topology& t) {
  std::vector<std::uint32_t> out;
  for (SensorId i = 0; i < t.sensorCount(); ++i) out.push_back(t.supernodeOf(i));
  return out;
}

std::vector<std::int32_t> hopsOf(const nm::Topology& t) { return {t.allHops().begin(), t.allHops().end()}; }



/// One report per sensor of `count` at `tick`.
std::vector<Report> everySensor(std::int32_t tick, std::size_t count) {
  std::vector<Report> out;
  for (SensorId s = 0; s < count; ++s) out.push_back(Report{tick, s, static_cast<double>(s) + 0.5, 0.0, 0});
  return out;
}

void checkBalanced(const nm::NetworkCounts& c) {
  CHECK(c.sent == c.lost + c.unreachable + c.delivered + c.after_end + c.lost_dead_supernode);
}

}  // namespace

TEST_CASE("the graph over the live supernodes: g(i) nearest live, hops over the survivors",
          "[network][topology][faults]") {
  const nm::Topology all(lineConfig(), kSensors);
  CHECK(groupsOf(all) == std::vector<std::uint32_t>{0, 1, 1, 1, 2, 2});
  CHECK(hopsOf(all) == std::vector<std::int32_t>{1, 1, 1, 2, 2, 1});
  // An explicit all-live mask is the same graph.
  const nm::Topology explicit_all(lineConfig({true, true, true}), kSensors);
  CHECK(groupsOf(explicit_all) == groupsOf(all));
  CHECK(hopsOf(explicit_all) == hopsOf(all));

  const nm::Topology without(lineConfig(kWithoutS1), kSensors);
  // Indices are the scenario's: 0 and 2, not 0 and 1.
  CHECK(without.supernodeCount() == 3);
  CHECK(without.supernodePosition(2).x == 8.0);
  CHECK(groupsOf(without) == std::vector<std::uint32_t>{0, 0, 0, 2, 2, 2});
  // The dead supernode relays nothing: sensor 2 would be 4 hops from S0 through it.
  CHECK(hopsOf(without) == std::vector<std::int32_t>{1, 2, -1, 3, 2, 1});
  CHECK(without.groupSize(0) == 3);
  CHECK(without.groupSize(1) == 0);
  CHECK(without.groupSize(2) == 3);
  CHECK(without.unreachableCount() == 1);
  CHECK(without.reachableCount() == 5);
  CHECK(without.maxHops() == 3);
  CHECK(without.hopHistogram() == std::vector<std::size_t>{0, 2, 2, 1});
  CHECK(without.meanHops() == Approx(9.0 / 5.0).margin(1e-12));

  // Only S2 live: every sensor goes to it; sensors 2..5 reach it along the line, 0 and 1 do not
  // (S1 is no relay).
  const nm::Topology only2(lineConfig({false, false, true}), kSensors);
  CHECK(groupsOf(only2) == std::vector<std::uint32_t>{2, 2, 2, 2, 2, 2});
  CHECK(hopsOf(only2) == std::vector<std::int32_t>{-1, -1, 4, 3, 2, 1});
  CHECK(only2.groupSize(2) == 6);
  // Only S0 live: the dead S2 is no relay for anyone either; sensors 2..5 are cut off at S1.
  const nm::Topology only0(lineConfig({true, false, false}), kSensors);
  CHECK(hopsOf(only0) == std::vector<std::int32_t>{1, 2, -1, -1, -1, -1});

  CHECK_THROWS_AS(nm::Topology(lineConfig({false, false, false}), kSensors), std::invalid_argument);
}

TEST_CASE("live topologies are built once per live set", "[network][topology][faults]") {
  nm::LiveTopologies topologies(lineConfig(), kSensors);
  const nm::Topology& full = topologies.full();
  CHECK(groupsOf(full) == std::vector<std::uint32_t>{0, 1, 1, 1, 2, 2});
  CHECK(&topologies.at({true, true, true}) == &full);
  const nm::Topology& without = topologies.at(kWithoutS1);
  CHECK(&without != &full);
  CHECK(&topologies.at(kWithoutS1) == &without);
  CHECK(without.groupSize(1) == 0);
  CHECK(hopsOf(without) == std::vector<std::int32_t>{1, 2, -1, 3, 2, 1});
  const nm::Topology& only2 = topologies.at({false, false, true});
  CHECK(&only2 != &without);
  CHECK(only2.groupSize(2) == 6);
  CHECK(&topologies.at(kWithoutS1) == &without);  // still the first one built
  CHECK_THROWS_AS(topologies.at({false, false, false}), std::invalid_argument);
}

TEST_CASE("a re-homing counts the dead group's sensors, adopters, reachability and hops",
          "[network][topology][faults]") {
  const nm::Topology all(lineConfig(), kSensors);
  const nm::Topology without(lineConfig(kWithoutS1), kSensors);
  // S1's group: sensors 1, 2, 3 at 1, 1, 2 hops; after: S0 takes 1 (2 hops) and 2 (unreachable),
  // S2 takes 3 (3 hops).
  const nm::Rehome r = nm::rehomeOf(all, without, 1, 10);
  CHECK(r.supernode == 1);
  CHECK(r.tick == 10);
  CHECK(r.sensors == 3);
  CHECK(r.adopters == std::map<std::uint32_t, std::size_t>{{0, 2}, {2, 1}});
  CHECK(r.reachable_before == 3);
  CHECK(r.reachable_after == 2);
  CHECK(r.mean_hops_before == Approx(4.0 / 3.0).margin(1e-12));
  CHECK(r.mean_hops_after == Approx(5.0 / 2.0).margin(1e-12));
  // S2 dying after S1: its group (sensors 3, 4, 5) all go to S0, none reachable.
  const nm::Topology only0(lineConfig({true, false, false}), kSensors);
  const nm::Rehome second = nm::rehomeOf(without, only0, 2, 20);
  CHECK(second.sensors == 3);
  CHECK(second.adopters == std::map<std::uint32_t, std::size_t>{{0, 3}});
  CHECK(second.reachable_before == 3);
  CHECK(second.reachable_after == 0);
  CHECK(second.mean_hops_before == Approx(2.0).margin(1e-12));  // (3 + 2 + 1) / 3
  CHECK(second.mean_hops_after == 0.0);
}

TEST_CASE("a burst loss replaces pte for its ticks only", "[network][router][faults]") {
  const nm::Topology topology(lineConfig(), kSensors);
  // pte 0 and pde 0: everything arrives at once, except on the burst's ticks 3 and 4 (pte 1).
  nm::RouterConfig config{.pte = 0.0, .pde = 0.0, .run_ticks = 10, .window_size = 10, .seed = 5};
  config.faults = FaultPlan({FaultSpec::burstLoss(1.0, 3, 2)}, 1, 3);
  nm::Router router(config, topology);
  for (std::int32_t t = 1; t <= 6; ++t) {
    INFO("tick " << t);
    const bool in_burst = t == 3 || t == 4;
    for (const nm::ReportFate& fate : router.submit(t, everySensor(t, kSensors.size()))) {
      CHECK(fate.hops >= 1);
      CHECK(fate.lost == in_burst);
      CHECK_FALSE(fate.to_dead_supernode);
      CHECK(fate.tick_delivered == (in_burst ? -1 : t));
    }
    std::size_t due = 0;
    for (std::uint32_t j = 0; j < 3; ++j) due += router.deliveriesDue(t, j).size();
    CHECK(due == (in_burst ? 0u : kSensors.size()));
  }
  CHECK(router.counts().sent == 36);
  CHECK(router.counts().lost == 12);
  CHECK(router.counts().delivered == 24);
  CHECK(router.counts().lost_dead_supernode == 0);
  // The router's own pte (network.json's) is still the scenario's.
  CHECK(router.config().pte == 0.0);
}

TEST_CASE("a report due at a dead supernode is lost with it, counted apart", "[network][router][faults]") {
  const nm::Topology topology(lineConfig(), kSensors);
  // S1 killed at tick 3; the router still routes over the full graph, so S1's group (sensors
  // 1, 2, 3) is due at a dead supernode from tick 3 on.
  nm::RouterConfig config{.pte = 0.0, .pde = 0.0, .run_ticks = 10, .window_size = 10, .seed = 5};
  config.faults = FaultPlan({FaultSpec::kill(FaultRole::kSupernode, 1, 3)}, 1, 3);
  nm::Router router(config, topology);
  for (std::int32_t t = 1; t <= 4; ++t) {
    INFO("tick " << t);
    for (const nm::ReportFate& fate : router.submit(t, everySensor(t, kSensors.size()))) {
      const bool dead = fate.supernode == 1 && t >= 3;
      CHECK(fate.to_dead_supernode == dead);
      CHECK(fate.lost == dead);
      CHECK(fate.hops >= 1);  // still the path it had
      CHECK(fate.tick_delivered == (dead ? -1 : t));
      CHECK(fate.delay == (dead ? -1 : 0));
    }
    CHECK(router.deliveriesDue(t, 1).size() == (t >= 3 ? 0u : 3u));
  }
  CHECK(router.counts().sent == 24);
  CHECK(router.counts().lost_dead_supernode == 6);
  CHECK(router.counts().delivered == 18);
  CHECK(router.counts().lost == 0);
  CHECK(router.counts(1).lost_dead_supernode == 6);
  CHECK(router.counts(0).lost_dead_supernode == 0);
  checkBalanced(router.counts());
  for (std::uint32_t j = 0; j < 3; ++j) checkBalanced(router.counts(j));
}

TEST_CASE("the dead supernode is judged at the delivery tick, not the tick of the report",
          "[network][router][faults]") {
  const nm::Topology topology(lineConfig(), kSensors);
  // pde 0.6: delays of several ticks; S1 killed at tick 20, reports from ticks 1..19.
  nm::RouterConfig config{.pte = 0.2, .pde = 0.6, .run_ticks = 40, .window_size = 10, .seed = 11};
  config.faults = FaultPlan({FaultSpec::kill(FaultRole::kSupernode, 1, 20)}, 1, 3);
  nm::Router router(config, topology);
  std::uint64_t to_dead = 0;
  for (std::int32_t t = 1; t <= 19; ++t)
    for (const nm::ReportFate& fate : router.submit(t, everySensor(t, kSensors.size()))) {
      if (fate.to_dead_supernode) {
        ++to_dead;
        CHECK(fate.supernode == 1);
        CHECK(fate.lost);
        CHECK(fate.delay == -1);
        CHECK(fate.tick_delivered == -1);
      }
      // Nothing is delivered to S1 from tick 20 on, and what is delivered elsewhere is due then.
      if (fate.tick_delivered >= 0 && fate.supernode == 1) CHECK(fate.tick_delivered < 20);
    }
  // Reports made while S1 lived but due after its death: some of the 57 of its group.
  CHECK(to_dead > 0);
  CHECK(router.counts().lost_dead_supernode == to_dead);
  CHECK(router.counts(1).lost_dead_supernode == to_dead);
  CHECK(router.counts().lost > 0);
  CHECK(router.counts().delayed > 0);
  checkBalanced(router.counts());
  for (std::uint32_t j = 0; j < 3; ++j) checkBalanced(router.counts(j));
}

TEST_CASE("the router switches groups and hop counts with the topology", "[network][router][faults]") {
  nm::LiveTopologies topologies(lineConfig(), kSensors);
  nm::RouterConfig config{.pte = 0.0, .pde = 0.0, .run_ticks = 10, .window_size = 10, .seed = 5};
  config.faults = FaultPlan({FaultSpec::kill(FaultRole::kSupernode, 1, 2)}, 1, 3);
  nm::Router router(config, topologies.full());
  router.submit(1, everySensor(1, kSensors.size()));
  CHECK(router.deliveriesDue(1, 1).size() == 3);
  router.useTopology(topologies.at(kWithoutS1));
  CHECK(&router.topology() == &topologies.at(kWithoutS1));
  const auto fates = router.submit(2, everySensor(2, kSensors.size()));
  REQUIRE(fates.size() == 6);
  std::vector<std::uint32_t> groups;
  std::vector<std::int32_t> hops;
  for (const auto& fate : fates) {
    groups.push_back(fate.supernode);
    hops.push_back(fate.hops);
    CHECK_FALSE(fate.to_dead_supernode);
  }
  CHECK(groups == std::vector<std::uint32_t>{0, 0, 0, 2, 2, 2});
  CHECK(hops == std::vector<std::int32_t>{1, 2, -1, 3, 2, 1});  // 3 hops: more than the full graph's max
  CHECK(router.deliveriesDue(2, 0).size() == 2);  // sensor 2 is unreachable
  CHECK(router.deliveriesDue(2, 1).empty());
  CHECK(router.deliveriesDue(2, 2).size() == 3);
  CHECK(router.counts().lost_dead_supernode == 0);
  CHECK(router.counts().unreachable == 1);
  CHECK(router.counts(0).unreachable == 1);
  CHECK(router.counts().delivered == 11);
  // Another sensor set is refused.
  const nm::Topology fewer(lineConfig(), std::vector<Vec2>{{1, 0}});
  CHECK_THROWS_AS(router.useTopology(fewer), std::logic_error);
}

TEST_CASE("an observations row names a report lost to a dead supernode", "[network_model][run_files][faults]") {
  nm::ReportFate fate;
  fate.report.tick = 5;
  fate.report.sensor = 17;
  fate.report.x = 1.5;
  fate.report.y = -2.25;
  fate.report.target = 3;
  fate.supernode = 1;
  fate.hops = 2;
  fate.lost = true;
  fate.to_dead_supernode = true;
  CHECK(nm::observationRow(fate) == "5,,17,1,2,,1.500000,-2.250000,3,dead_supernode,0");
  CHECK(std::string(nm::kDeadSupernodeFate) == "dead_supernode");
  fate.to_dead_supernode = false;
  CHECK(nm::observationRow(fate) == "5,,17,1,2,,1.500000,-2.250000,3,lost,0");
  // Every fate a row can name is in the list the catalogue gives the Python readers.
  const auto listed = [](const std::string& fate_name) {
    return std::find(std::begin(nm::kObservationFates), std::end(nm::kObservationFates), fate_name) !=
           std::end(nm::kObservationFates);
  };
  for (const auto& row : {nm::observationRow(fate), std::string("5,,17,1,2,,1.500000,-2.250000,3,dead_supernode,0")}) {
    const auto end = row.rfind(',');
    CHECK(listed(row.substr(row.rfind(',', end - 1) + 1, end - row.rfind(',', end - 1) - 1)));
  }
  for (const char* name : {"delivered", "lost", "unreachable", "after_end", "dead_supernode"}) CHECK(listed(name));
}

TEST_CASE("network.json has the fault counts only for a run with faults", "[network_model][run_files][faults]") {
  nm::NetworkReport report;
  report.per_supernode.resize(2);
  report.per_supernode[0].sent = 60;
  report.per_supernode[0].lost = 10;
  report.per_supernode[0].delivered = 45;
  report.per_supernode[0].lost_dead_supernode = 5;
  report.per_supernode[1].sent = 40;
  report.per_supernode[1].lost = 5;
  report.per_supernode[1].unreachable = 2;
  report.per_supernode[1].delivered = 33;
  report.total = report.per_supernode[0];
  report.total += report.per_supernode[1];
  report.silent_tile_ticks = 7;
  nm::Rehome r;
  r.supernode = 1;
  r.tick = 12;
  r.sensors = 3;
  r.reachable_before = 3;
  r.reachable_after = 2;
  r.adopters = {{0, 2}, {2, 1}};
  r.mean_hops_before = 4.0 / 3.0;
  r.mean_hops_after = 2.5;
  report.rehomes = {r};

  const auto plain = nlohmann::json::parse(nm::networkJson(report));
  CHECK_FALSE(plain.contains("lost_dead_supernode"));
  CHECK_FALSE(plain.contains("silent_tile_ticks"));
  CHECK_FALSE(plain.contains("rehomes"));
  CHECK_FALSE(plain.at("supernodes")[0].contains("lost_dead_supernode"));

  report.with_faults = true;
  const auto json = nlohmann::json::parse(nm::networkJson(report));
  CHECK(json.at("lost_dead_supernode") == 5);
  CHECK(json.at("supernodes")[0].at("lost_dead_supernode") == 5);
  CHECK(json.at("supernodes")[1].at("lost_dead_supernode") == 0);
  CHECK(json.at("silent_tile_ticks") == 7);
  // lost_to_total counts the dead supernode's losses: (15 + 2 + 5) / 100.
  CHECK(json.at("lost_to_total").get<double>() == Approx(0.22).margin(1e-12));
  // The end-to-end delivery ratio: delivered within the run over sent, (45 + 33) / 100.
  CHECK(json.at("delivered_to_total").get<double>() == Approx(0.78).margin(1e-12));
  CHECK(plain.at("delivered_to_total").get<double>() == Approx(0.78).margin(1e-12));
  // Every quantity the catalogue offers sweeps is a number network.json has.
  for (const auto& q : nm::networkQuantities()) {
    INFO(q.key);
    CHECK(plain.at(q.key).is_number());
  }
  REQUIRE(json.at("rehomes").size() == 1);
  const auto& rehome = json.at("rehomes")[0];
  CHECK(rehome.at("supernode") == 1);
  CHECK(rehome.at("tick") == 12);
  CHECK(rehome.at("sensors") == 3);
  CHECK(rehome.at("reachable_before") == 3);
  CHECK(rehome.at("reachable_after") == 2);
  CHECK(rehome.at("mean_hops_before").get<double>() == 4.0 / 3.0);
  CHECK(rehome.at("mean_hops_after").get<double>() == 2.5);
  CHECK(rehome.at("adopters") ==
        nlohmann::json::parse(R"([{"supernode": 0, "sensors": 2}, {"supernode": 2, "sensors": 1}])"));
  // A run with faults but no supernode death still has the (empty) list.
  report.rehomes.clear();
  CHECK(nlohmann::json::parse(nm::networkJson(report)).at("rehomes").empty());
}

TEST_CASE("the router's config carries the scenario's faults over its tiles and supernodes",
          "[network][role_config][faults]") {
  wsn::common::Scenario scenario;
  scenario.supernodes = kSupernodes;
  scenario.run.node_processes = 3;
  CHECK(nm::routerConfig(scenario).faults.empty());
  scenario.faults = {FaultSpec::kill(FaultRole::kSupernode, 1, 4), FaultSpec::burstLoss(0.7, 2, 1)};
  const nm::RouterConfig config = nm::routerConfig(scenario);
  CHECK(config.faults == FaultPlan(scenario.faults, 3, 3));
  CHECK(config.faults.liveSupernodes(4) == kWithoutS1);
  CHECK(config.faults.liveTileCount(4) == 3);
  CHECK(config.faults.burstPte(2) == std::optional<double>(0.7));
}

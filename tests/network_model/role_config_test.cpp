// The role edge (network_model/role_config.cpp): the configs it splits off a scenario carry
// exactly the scenario's values, and a router built from them routes as it did when it took the
// whole scenario.
#include "network_model/role_config.hpp"

#include <tuple>
#include <vector>

#include <catch2/catch.hpp>

namespace nm = wsn::network_model;
using wsn::common::Report;
using wsn::common::Vec2;

namespace {

/// Values unlike every default, so a field read from the wrong place shows.
wsn::common::Scenario handMadeScenario() {
  wsn::common::Scenario scenario;
  scenario.supernodes = {{0, 0}, {10, 0}};
  scenario.network.communication_range = 1.0;
  scenario.network.pte = 0.3;
  scenario.network.pde = 0.5;
  scenario.run.ticks = 6;
  scenario.run.seed = 7;
  scenario.tracker.window_size = 2;
  return scenario;
}

}  // namespace

TEST_CASE("the role edge copies the network section, run length, seed and window into the configs",
          "[network_model][role_config]") {
  const auto scenario = handMadeScenario();
  CHECK(nm::topologyConfig(scenario) == nm::TopologyConfig{{{0, 0}, {10, 0}}, 1.0});
  CHECK(nm::routerConfig(scenario) ==
        nm::RouterConfig{.pte = 0.3, .pde = 0.5, .run_ticks = 6, .window_size = 2, .seed = 7});
  // The configs' defaults are the scenario's, so a default scenario splits into default configs.
  const wsn::common::Scenario defaults;
  CHECK(nm::routerConfig(defaults) == nm::RouterConfig{});
  CHECK(nm::topologyConfig(defaults).communication_range == nm::TopologyConfig{}.communication_range);
}

TEST_CASE("a router built from routerConfig of a scenario delivers what the scenario-taking router did",
          "[network_model][role_config]") {
  // Supernode A = (0, 0) with sensors 0..2 at x = 1, 2, 3 (1..3 hops); B = (10, 0) with sensor 3
  // at 10.5 (1 hop) and sensor 4 at 13, out of range (unreachable). Every sensor reports at
  // ticks 1..6.
  const auto scenario = handMadeScenario();
  const std::vector<Vec2> sensors{{1, 0}, {2, 0}, {3, 0}, {10.5, 0}, {13, 0}};
  const nm::Topology topology(nm::topologyConfig(scenario), sensors);
  nm::Router router(nm::routerConfig(scenario), topology);
  using Delivery = std::tuple<std::uint32_t, std::int32_t, std::int32_t, wsn::common::SensorId>;
  std::vector<Delivery> deliveries;  // (supernode, tick_generated, tick_delivered, sensor)
  for (std::int32_t t = 1; t <= 6; ++t) {
    std::vector<Report> reports;
    for (wsn::common::SensorId s = 0; s < 5; ++s)
      reports.push_back(Report{t, s, s + 0.25, 0.5, static_cast<wsn::common::TargetId>(s % 3)});
    router.submit(t, reports);
    for (std::uint32_t j = 0; j < 2; ++j)
      for (const auto& o : router.deliveriesDue(t, j))
        deliveries.emplace_back(j, o.tick_generated, o.tick_delivered, o.sensor);
  }
  // Recorded from Router(const Scenario&, const Topology&) at 07fff3c with this scenario; the
  // streams are keyed by (seed 7, purpose, sensor, tick), so any change of seed or rates moves them.
  const std::vector<Delivery> recorded{{0, 1, 1, 0}, {1, 1, 1, 3}, {1, 3, 3, 3}, {0, 3, 4, 1},
                                       {0, 1, 5, 2}, {1, 2, 5, 3}, {0, 4, 6, 2}, {0, 6, 6, 0}};
  CHECK(deliveries == recorded);
  // 5 x 6 = 30 sent = 11 lost + 6 unreachable (sensor 4) + 8 delivered + 5 after the end; the
  // delayed ones are d = 1, 4, 3, 2, of which 3 reach ws = 2.
  const auto& c = router.counts();
  CHECK(std::tie(c.sent, c.lost, c.unreachable, c.delivered, c.after_end) == std::tuple(30u, 11u, 6u, 8u, 5u));
  CHECK(c.delayed == 4);
  CHECK(c.beyond_window == 3);
}

// The network model's run-directory formats (network_model/run_files.cpp): network.json read back
// as JSON, and observations.csv rows for each fate.
#include "network_model/run_files.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

namespace nm = wsn::network_model;

namespace {

nm::NetworkCounts counts(std::uint64_t sent, std::uint64_t lost, std::uint64_t unreachable, std::uint64_t delivered,
                         std::uint64_t delayed, std::uint64_t beyond_window, std::uint64_t after_end) {
  nm::NetworkCounts c;
  c.sent = sent;
  c.lost = lost;
  c.unreachable = unreachable;
  c.delivered = delivered;
  c.delayed = delayed;
  c.beyond_window = beyond_window;
  c.after_end = after_end;
  return c;
}

/// Two supernodes whose counts add up to the total (rejected is a total only).
nm::NetworkReport twoGroups() {
  nm::NetworkReport report;
  report.communication_range = 11.6;
  report.pte = 0.3;
  report.pde = 0.2;
  report.mean_hops = 2.0 / 3.0;
  report.max_hops = 4;
  report.per_supernode = {counts(60, 10, 2, 40, 12, 3, 8), counts(40, 5, 0, 30, 6, 1, 5)};
  report.total = counts(100, 15, 2, 70, 18, 4, 13);
  report.total.rejected = 3;
  return report;
}

nm::NetworkCounts countsOf(const nlohmann::json& j) {
  return counts(j.at("sent"), j.at("lost"), j.at("unreachable"), j.at("delivered"), j.at("delayed"),
                j.at("beyond_window"), j.at("after_end"));
}

}  // namespace

TEST_CASE("network.json reads back to the report it was written from", "[network_model][run_files]") {
  const auto report = twoGroups();
  const auto json = nlohmann::json::parse(nm::networkJson(report));
  // Full precision: 2/3 comes back as the same double, not as 0.666667.
  CHECK(json.at("mean_hops").get<double>() == report.mean_hops);
  CHECK(json.at("communication_range").get<double>() == 11.6);
  CHECK(json.at("pte").get<double>() == 0.3);
  CHECK(json.at("pde").get<double>() == 0.2);
  CHECK(json.at("max_hops").get<int>() == 4);
  auto total = countsOf(json);
  total.rejected = json.at("rejected");
  CHECK(total == report.total);
  REQUIRE(json.at("supernodes").size() == 2);
  for (std::size_t j = 0; j < 2; ++j) {
    CHECK(json["supernodes"][j].at("supernode").get<std::size_t>() == j);
    CHECK(countsOf(json["supernodes"][j]) == report.per_supernode[j]);
    CHECK_FALSE(json["supernodes"][j].contains("rejected"));
  }
}

TEST_CASE("network.json gives the loss and delay ratios of Oh VII-E", "[network_model][run_files]") {
  const auto json = nlohmann::json::parse(nm::networkJson(twoGroups()));
  // lost_to_total = (lost + unreachable) / sent = (15 + 2) / 100.
  CHECK(json.at("lost_to_total").get<double>() == Approx(0.17).margin(1e-12));
  // Received = delivered + after_end = 70 + 13 = 83; delayed = delayed + after_end = 18 + 13 = 31.
  CHECK(json.at("delayed_to_received").get<double>() == Approx(31.0 / 83.0).margin(1e-12));
  // The paper's counts are a reference that says which scenario they belong to.
  CHECK_FALSE(json.contains("paper_oh_vii_e"));
  const auto& reference = json.at("reference_oh_vii_e");
  CHECK_THAT(reference.at("applies_to").get<std::string>(), Catch::Contains("scenarios/oh_quadrants.yaml"));
  CHECK(reference.at("reports") == 1174);
  CHECK(reference.at("lost_reports") == 319);
  CHECK(reference.at("received_reports") == 855);
  CHECK(reference.at("delayed_reports") == 449);
  // Nothing sent: the ratios are 0, not NaN (which JSON cannot hold).
  const auto empty = nlohmann::json::parse(nm::networkJson(nm::NetworkReport{}));
  CHECK(empty.at("lost_to_total").get<double>() == 0.0);
  CHECK(empty.at("delayed_to_received").get<double>() == 0.0);
  CHECK(empty.at("supernodes").empty());
}

TEST_CASE("network.json keeps its keys in the documented order, one per line", "[network_model][run_files]") {
  const std::string text = nm::networkJson(twoGroups());
  // Scripts grep the first '"beyond_window": N', which must be the total's.
  const auto first = text.find("\"beyond_window\": 4");
  REQUIRE(first != std::string::npos);
  CHECK(first < text.find("\"supernodes\""));
  CHECK(text.find("\"communication_range\"") < text.find("\"max_hops\""));
  CHECK(text.find("\"rejected\"") < text.find("\"lost_to_total\""));
  CHECK(text.back() == '\n');
}

TEST_CASE("an observations row names the fate of its report", "[network_model][run_files]") {
  nm::ReportFate fate;
  fate.report.tick = 5;
  fate.report.sensor = 17;
  fate.report.x = 1.5;
  fate.report.y = -2.25;
  fate.report.target = 3;
  fate.supernode = 1;
  fate.hops = 2;
  fate.delay = 1;
  fate.tick_delivered = 6;
  CHECK(nm::observationRow(fate) == "5,6,17,1,2,1,1.500000,-2.250000,3,delivered,0");
  fate.tick_delivered = -1;
  CHECK(nm::observationRow(fate) == "5,,17,1,2,1,1.500000,-2.250000,3,after_end,0");
  fate.lost = true;
  fate.delay = -1;
  CHECK(nm::observationRow(fate) == "5,,17,1,2,,1.500000,-2.250000,3,lost,0");
  fate.hops = -1;
  CHECK(nm::observationRow(fate) == "5,,17,1,-1,,1.500000,-2.250000,3,unreachable,0");
  fate.report.power_level = 3;  // an ADMAN inside target
  CHECK(nm::observationRow(fate) == "5,,17,1,-1,,1.500000,-2.250000,3,unreachable,3");
}

TEST_CASE("the network report records the range, rates and counts the topology and router ran with",
          "[network_model][run_files]") {
  // Supernodes at 0 and 10, sensors at 1 and 2 (group 0, 1 and 2 hops) and 9 (group 1, 1 hop):
  // mean hops (1 + 2 + 1) / 3, max 2.
  const std::vector<wsn::common::Vec2> sensors{{1, 0}, {2, 0}, {9, 0}};
  const nm::Topology topology(nm::TopologyConfig{{{0, 0}, {10, 0}}, 1.5}, sensors);
  nm::Router router(nm::RouterConfig{.pte = 0.25, .pde = 0.125, .run_ticks = 1, .window_size = 10, .seed = 3},
                    topology);
  router.submit(1, std::vector<wsn::common::Report>{{1, 0, 1.0, 0.0, 0}, {1, 2, 9.0, 0.0, 1}});
  const nm::NetworkReport report = nm::networkReport(topology, router);
  CHECK(report.communication_range == 1.5);
  CHECK(report.pte == 0.25);
  CHECK(report.pde == 0.125);
  CHECK(report.mean_hops == Approx(4.0 / 3.0).margin(1e-12));
  CHECK(report.max_hops == 2);
  CHECK(report.total == router.counts());
  // One entry per supernode, each with its group's single report.
  REQUIRE(report.per_supernode.size() == 2);
  CHECK(report.per_supernode[0] == router.counts(0));
  CHECK(report.per_supernode[1] == router.counts(1));
  CHECK(report.per_supernode[0].sent == 1);
  CHECK(report.per_supernode[1].sent == 1);
}

#include "network_model/role.hpp"

#include <cstdio>
#include <fstream>

#include "common/dds/codec.hpp"
#include "common/output.hpp"
#include "common/sensor_layout.hpp"
#include "network_model/router.hpp"
#include "network_model/topology.hpp"

namespace wsn::network_model {
namespace {

/// One observations.csv row; `fate` reads delivered, lost, unreachable or after_end.
std::string formatFate(const ReportFate& fate) {
  const auto& r = fate.report;
  const char* what = fate.hops < 0 ? "unreachable" : fate.lost ? "lost" : fate.tick_delivered < 0 ? "after_end" : "delivered";
  return std::to_string(r.tick) + "," + (fate.tick_delivered < 0 ? std::string() : std::to_string(fate.tick_delivered)) +
         "," + std::to_string(r.sensor) + "," + std::to_string(fate.supernode) + "," + std::to_string(fate.hops) + "," +
         (fate.delay < 0 ? std::string() : std::to_string(fate.delay)) + "," + common::fixed6(r.x) + "," +
         common::fixed6(r.y) + "," + std::to_string(r.target) + "," + what;
}

std::string countsJson(const NetworkCounts& c) {
  return "\"sent\": " + std::to_string(c.sent) + ", \"lost\": " + std::to_string(c.lost) +
         ", \"unreachable\": " + std::to_string(c.unreachable) + ", \"delivered\": " + std::to_string(c.delivered) +
         ", \"delayed\": " + std::to_string(c.delayed) + ", \"beyond_window\": " + std::to_string(c.beyond_window) +
         ", \"after_end\": " + std::to_string(c.after_end);
}

double ratio(std::uint64_t part, std::uint64_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

/// network.json: the model's settings, the counts, and the paper's §VII-E counts beside them.
std::string networkJson(const common::Scenario& scenario, const Topology& topology, const Router& router) {
  const auto& c = router.counts();
  // A report is "received" when it is not lost, as in Oh §VII-E; one due after the last tick is
  // received late, so it counts as delayed too (its d > 0 by construction).
  const std::uint64_t received = c.delivered + c.after_end;
  std::string json = "{\n  \"communication_range\": " + common::fixed6(scenario.network.communication_range) +
                     ",\n  \"pte\": " + common::fixed6(scenario.network.pte) +
                     ",\n  \"pde\": " + common::fixed6(scenario.network.pde) +
                     ",\n  \"mean_hops\": " + common::fixed6(topology.meanHops()) +
                     ",\n  \"max_hops\": " + std::to_string(topology.maxHops()) + ",\n  " + countsJson(c) +
                     ", \"rejected\": " + std::to_string(c.rejected) +
                     ",\n  \"lost_to_total\": " + common::fixed6(ratio(c.lost + c.unreachable, c.sent)) +
                     ",\n  \"delayed_to_received\": " + common::fixed6(ratio(c.delayed + c.after_end, received)) +
                     ",\n  \"supernodes\": [";
  for (std::uint32_t j = 0; j < scenario.supernodes.size(); ++j)
    json += std::string(j == 0 ? "" : ",") + "\n    {\"supernode\": " + std::to_string(j) + ", " + countsJson(router.counts(j)) + "}";
  json += "\n  ],\n  \"paper_oh_vii_e\": {\"reports\": 1174, \"lost_reports\": 319, \"received_reports\": 855, "
          "\"delayed_reports\": 449}\n}\n";
  return json;
}

}  // namespace

void runNetworkRole(const dds::RoleContext& context) {
  using namespace wsn::dds;
  runRole(context, [&](const Participant& participant, const RunTopics& topics, StatusPublisher& status) {
    const auto& scenario = context.scenario;
    const common::SensorLayout layout(scenario);
    const Topology topology(scenario, layout);
    Router router(scenario, topology);

    Reader<wsn_msg_ReportBatch> report_reader(participant, topics.report_batch, Qos::reliableKeepAll());
    Writer<wsn_msg_DeliveryBatch> delivery_writer(participant, topics.delivery_batch, Qos::reliableKeepAll());
    RoleLoop loop(participant, context);
    PipelineProgress progress(participant, topics, context, loop);

    TickInbox<std::vector<common::Report>> inbox;
    loop.watch(report_reader, [&] {
      report_reader.take([&](const wsn_msg_ReportBatch& batch) {
        if (batch.run_id != context.run_id || batch.tile >= static_cast<std::uint32_t>(context.shape.tiles)) return;
        inbox.put(batch.tick, batch.tile, decode(batch.reports, batch.tick));
      });
    });
    waitForDiscovery(participant, {{&delivery_writer, context.shape.supernodes}},
                     {{&report_reader, context.shape.tiles}, {&progress.reader(), 1}}, context, std::chrono::seconds(30));
    status.ready();

    common::CsvFile observations(context.run_dir + "/observations.csv",
                                 "tick_generated,tick_delivered,sensor,supernode,hops,delay,x,y,target,fate");
    const auto tiles = static_cast<std::size_t>(context.shape.tiles);
    const std::int32_t ticks = scenario.run.ticks;
    for (std::int32_t t = 1; t <= ticks; ++t) {
      loop.waitUntil([&] { return inbox.count(t) >= tiles; },
                     [&] { return "reports of tick " + std::to_string(t) + " from every tile"; });
      std::vector<common::Report> reports;
      for (auto& [tile, batch] : inbox.take(t)) reports.insert(reports.end(), batch.begin(), batch.end());
      for (const auto& fate : router.submit(t, reports)) observations.row(formatFate(fate));
      router.forgetFatesBefore(t + 1);

      for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(context.shape.supernodes); ++j) {
        auto due = encode(router.deliveriesDue(t, j));
        wsn_msg_DeliveryBatch sample{};
        sample.run_id = context.run_id;
        sample.supernode = j;
        sample.tick = t;
        sample.observations = sequenceView<dds_sequence_wsn_msg_Observation>(due);
        delivery_writer.write(sample);
      }
    }
    observations.close();
    common::writeTextFile(context.run_dir + "/network.json", networkJson(scenario, topology, router));
    progress.waitForCompleted(ticks);
    status.done(ticks);
  });
}

}  // namespace wsn::network_model

#include "network_model/role.hpp"

#include "common/dds/codec.hpp"
#include "common/output.hpp"
#include "common/sensor_layout.hpp"
#include "network_model/role_config.hpp"
#include "network_model/router.hpp"
#include "network_model/run_files.hpp"
#include "network_model/topology.hpp"

namespace wsn::network_model {

void runNetworkRole(const dds::RoleContext& context) {
  using namespace wsn::dds;
  runRole(context, [&](const Participant& participant, const RunTopics& topics, StatusPublisher& status) {
    const auto& scenario = context.scenario;
    const common::SensorLayout layout(sensorFieldConfig(scenario));
    const Topology topology(topologyConfig(scenario), layout.truePositions());
    Router router(routerConfig(scenario), topology);

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
                     {{&report_reader, context.shape.tiles}, {&progress.reader(), 1}}, context);
    status.ready();

    common::CsvFile observations(context.run_dir + "/observations.csv", kObservationsHeader);
    const auto tiles = static_cast<std::size_t>(context.shape.tiles);
    const std::int32_t ticks = scenario.run.ticks;
    for (std::int32_t t = 1; t <= ticks; ++t) {
      loop.waitUntil([&] { return inbox.count(t) >= tiles; },
                     [&] { return "reports of tick " + std::to_string(t) + " from every tile"; });
      std::vector<common::Report> reports;
      for (auto& [tile, batch] : inbox.take(t)) reports.insert(reports.end(), batch.begin(), batch.end());
      for (const auto& fate : router.submit(t, reports)) observations.row(observationRow(fate));
      router.forgetFatesBefore(t + 1);

      for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(context.shape.supernodes); ++j) {
        auto due = encode(router.deliveriesDue(t, j));
        wsn_msg_DeliveryBatch sample{};
        sample.run_id = context.run_id;
        sample.supernode = j;
        sample.tick = t;
        sample.observations = sequenceView<dds_sequence_wsn_msg_Observation>(due.items);
        delivery_writer.write(sample);
      }
    }
    observations.close();
    common::writeTextFile(context.run_dir + "/network.json", networkJson(networkReport(topology, router)));
    progress.waitForCompleted(ticks);
    status.done(ticks);
  });
}

}  // namespace wsn::network_model

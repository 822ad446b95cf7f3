#include "network_model/role.hpp"

#include "common/dds/codec.hpp"
#include "common/dds/packing.hpp"
#include "common/edge_checks.hpp"
#include "common/output.hpp"
#include "common/sensor_layout.hpp"
#include "network_model/live_topologies.hpp"
#include "network_model/role_config.hpp"
#include "network_model/router.hpp"
#include "network_model/run_files.hpp"
#include "network_model/topology.hpp"

namespace wsn::network_model {

void runNetworkRole(const dds::RoleContext& context) {
  using namespace wsn::dds;
  runRole(context, [&](const Participant& participant, const RunTopics& topics, StatusPublisher& status) {
    const auto& scenario = context.scenario;
    auto plan = context.faultPlan();
    const common::SensorLayout layout(sensorFieldConfig(scenario));
    LiveTopologies topologies(topologyConfig(scenario), layout.truePositions());
    Router router(routerConfig(scenario), topologies.full());

    Reader<wsn_msg_ReportBatch> report_reader(participant, topics.report_batch, Qos::reliableKeepAll());
    // One delivery writer per supernode, in that supernode's partition.
    std::vector<Writer<wsn_msg_DeliveryBatch>> delivery_writers;
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(context.shape.supernodes); ++j)
      delivery_writers.emplace_back(participant, topics.delivery_batch,
                                    Qos::reliableKeepAll().inPartition(topic_names::supernodePartition(j)));
    RoleLoop loop(participant, context);
    PipelineProgress progress(participant, topics, context, loop);
    RestartedReaders restarted(participant, context, plan);

    TickInbox<std::vector<common::Report>> inbox;
    // Every batch and report is checked before it counts: a first batch of a producer and tick is
    // kept, a later one never displaces it, and whatever is refused is counted (rejected.json).
    const common::EdgeBounds bounds = common::edgeBounds(scenario);
    RejectionsRecord rejections_record(context);  // on disk also if the role fails
    common::RejectionLog& rejections = rejections_record.log();
    const std::string topic = topic_names::kReportBatch;
    loop.watch(report_reader, [&] {
      report_reader.take([&](const wsn_msg_ReportBatch& batch) {
        using common::RejectReason;
        if (const auto why = common::checkBatchHeader(batch.run_id, context.run_id, batch.tile,
                                                      static_cast<std::uint32_t>(context.shape.tiles), batch.tick, bounds.ticks))
          return rejections.add(topic, *why);
        if (!plan.tileLive(static_cast<std::int32_t>(batch.tile), batch.tick)) return;  // the scenario's faults
        if (packedCount(batch.reports) > bounds.max_reports) return rejections.add(topic, RejectReason::kTooLong);
        if (!inbox.accepts(batch.tick, batch.tile)) return rejections.add(topic, RejectReason::kDuplicate);
        std::vector<common::Report> reports;
        try {
          reports = unpackReports(batch.reports, batch.tick);
        } catch (const PackingError&) {
          return rejections.add(topic, RejectReason::kMalformed);  // not filed: the tile's own batch still counts
        }
        common::dropRejectedReports(reports, bounds, topic, rejections);
        inbox.put(batch.tick, batch.tile, std::move(reports));
      });
    });
    // A process killed by hand: a tile is silent from the first tick whose reports did not come,
    // a supernode's group is re-homed from the tick being routed (its pending deliveries lost).
    std::int32_t t = 1;
    LostProcesses lost(participant, topics, context, loop, [&](common::FaultRole role, std::int32_t index) {
      if (role == common::FaultRole::kNode) {
        plan.loseUnscheduled(role, index, inbox.firstMissing(static_cast<std::uint32_t>(index), t));
      } else {
        plan.loseUnscheduled(role, index, t);
        router.loseSupernode(static_cast<std::uint32_t>(index), t);
      }
    });
    std::vector<std::pair<const WriterBase*, int>> writers;
    for (const auto& writer : delivery_writers) writers.push_back({&writer, 1});
    waitForDiscovery(participant, writers, {{&report_reader, context.shape.tiles}, {&progress.reader(), 1}}, context);
    status.ready();

    common::CsvFile observations(context.run_dir + "/observations.csv", kObservationsHeader);
    NetworkReport faults_seen;
    const std::int32_t ticks = scenario.run.ticks;
    for (; t <= ticks; ++t) {
      // A dead or paused tile sends nothing: wait for the live ones only (a loss announced
      // meanwhile changes whom).
      loop.waitUntil([&] { return inbox.count(t) >= static_cast<std::size_t>(plan.liveTileCount(t)); },
                     [&] { return "reports of tick " + std::to_string(t) + " from " + inbox.missing(t, plan.liveTiles(t), "node"); });
      faults_seen.silent_tile_ticks += static_cast<std::uint64_t>(context.shape.tiles - plan.liveTileCount(t));
      std::vector<common::Report> reports;
      for (auto& [tile, batch] : inbox.take(t))
        if (plan.tileLive(static_cast<std::int32_t>(tile), t)) reports.insert(reports.end(), batch.begin(), batch.end());

      // Oh §V over the survivors: the groups and hop counts of the supernodes live at t.
      const auto live = plan.liveSupernodes(t);
      const Topology& before = router.topology();
      const Topology& now = topologies.at(live);
      for (std::uint32_t j = 0; j < live.size(); ++j)
        if (!live[j] && before.groupSize(j) > 0)  // it owned a group until now: a death at t
          faults_seen.rehomes.push_back(rehomeOf(before, now, j, t));
      router.useTopology(now);
      for (const auto& fate : router.submit(t, reports)) observations.row(observationRow(fate));
      router.forgetFatesBefore(t + 1);

      for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(context.shape.supernodes); ++j) {
        if (!live[j]) continue;  // its deliveries were counted lost when they were routed
        restarted.waitFor(delivery_writers[j], t, j);
        auto due = packObservations(router.deliveriesDue(t, j));
        wsn_msg_DeliveryBatch sample{};
        sample.run_id = context.run_id;
        sample.supernode = j;
        sample.tick = t;
        sample.observations = due.view();
        delivery_writers[j].write(sample);
      }
    }
    observations.close();
    auto report = networkReport(topologies.full(), router);
    report.with_faults = !plan.empty();
    report.silent_tile_ticks = faults_seen.silent_tile_ticks;
    report.rehomes = std::move(faults_seen.rehomes);
    common::writeTextFile(context.run_dir + "/network.json", networkJson(report));
    rejections_record.write();
    progress.waitForCompleted(ticks);
    status.done(ticks);
  });
}

}  // namespace wsn::network_model

#include "node/role.hpp"

#include "common/dds/codec.hpp"
#include "common/dds/packing.hpp"
#include "common/edge_checks.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/sensor_model_registry.hpp"
#include "node/tiling.hpp"

namespace wsn::node {

void runNodeRole(const dds::RoleContext& context) {
  using namespace wsn::dds;
  runRole(context, [&](const Participant& participant, const RunTopics& topics, StatusPublisher& status) {
    const auto& scenario = context.scenario;
    const common::Truth truth(truthConfig(scenario));
    const common::SensorLayout layout(sensorFieldConfig(scenario));
    const auto tiles = makeTiles(layout, context.shape.tiles);
    const auto sensors = makeTileSensors(
        {scenario.sensor_model, scenario.run.seed, scenario.targets.scripted, layout, tiles.at(context.index), truth,
         &scenario.terrain});

    Writer<wsn_msg_SensorBoundary> boundary_writer(participant, topics.sensor_boundary, Qos::reliableKeepAll());
    Writer<wsn_msg_ReportBatch> report_writer(participant, topics.report_batch, Qos::reliableKeepAll());
    Reader<wsn_msg_SensorBoundary> boundary_reader(participant, topics.sensor_boundary, Qos::reliableKeepAll());
    RoleLoop loop(participant, context);
    PipelineProgress progress(participant, topics, context, loop);

    auto plan = context.faultPlan();
    TickInbox<std::vector<common::SensorReading>> boundary_inbox;
    // Every batch and reading is checked before it counts (common/edge_checks.hpp); refusals are
    // counted for rejected.json.
    const common::EdgeBounds bounds = common::edgeBounds(context.scenario);
    RejectionsRecord rejections_record(context);  // on disk also if the role fails
    common::RejectionLog& rejections = rejections_record.log();
    loop.watch(boundary_reader, [&] {
      boundary_reader.take([&](const wsn_msg_SensorBoundary& batch) {
        const std::string topic = topic_names::kSensorBoundary;
        if (const auto why = common::checkBatchHeader(batch.run_id, context.run_id, batch.tile,
                                                      static_cast<std::uint32_t>(context.shape.tiles), batch.tick, bounds.ticks))
          return rejections.add(topic, *why);
        // Its own readings (the reader hears its own writer), and a tile the faults silenced.
        if (batch.tile == context.index || !plan.tileLive(static_cast<std::int32_t>(batch.tile), batch.tick)) return;
        if (batch.readings._length > bounds.sensors) return rejections.add(topic, common::RejectReason::kTooLong);
        if (!boundary_inbox.accepts(batch.tick, batch.tile)) return rejections.add(topic, common::RejectReason::kDuplicate);
        auto readings = decode(batch.readings);
        common::dropRejected(readings, [&](const common::SensorReading& r) { return common::checkReading(r, bounds); },
                             topic, rejections);
        boundary_inbox.put(batch.tick, batch.tile, std::move(readings));
      });
    });

    // Another tile killed by hand: its boundary readings stop at the first tick that did not come.
    std::int32_t t = 1;
    LostProcesses lost(participant, topics, context, loop, [&](common::FaultRole role, std::int32_t index) {
      if (role == common::FaultRole::kNode)
        plan.loseUnscheduled(role, index, boundary_inbox.firstMissing(static_cast<std::uint32_t>(index), t));
    });
    const int tiles_count = context.shape.tiles;
    waitForDiscovery(participant, {{&boundary_writer, tiles_count}, {&report_writer, 1}},
                     {{&boundary_reader, tiles_count}, {&progress.reader(), 1}}, context);
    status.ready();
    // Sources start only when every consumer is connected, so tick 1 reaches everybody.
    waitForClusterReady(participant, topics, context, context.stall_timeout);

    const std::int32_t ticks = scenario.run.ticks;
    const std::int32_t in_flight = scenario.run.max_ticks_in_flight;
    const auto self = static_cast<std::int32_t>(context.index);
    for (; t <= ticks; ++t) {
      if (const auto fault = plan.processFaultAt(common::FaultRole::kNode, self, t)) {
        enactProcessFault(*fault, context, status, progress, loop);
        t = fault->lastTick();  // a pause: its sensors stayed silent through these ticks
        continue;
      }
      progress.paceTick();  // --tick-interval: the sources set the pace, back-pressure the rest
      progress.waitForCompleted(t - in_flight);
      auto boundary_readings = sensors->sense(t);
      std::vector<common::SensorReading> foreign;
      if (sensors->exchangesReadings()) {
        auto boundary = encode(boundary_readings);
        wsn_msg_SensorBoundary boundary_sample{};
        boundary_sample.run_id = context.run_id;
        boundary_sample.tile = context.index;
        boundary_sample.tick = t;
        boundary_sample.readings = sequenceView<dds_sequence_wsn_msg_SensorReading>(boundary);
        boundary_writer.write(boundary_sample);

        // Only the tiles live at t send: a dead or paused tile's sensors are silent.
        loop.waitUntil([&] { return boundary_inbox.count(t) >= static_cast<std::size_t>(plan.liveTileCount(t) - 1); },
                       [&] {
                         auto others_live = plan.liveTiles(t);
                         std::erase(others_live, context.index);
                         return "boundary readings of tick " + std::to_string(t) + " from " +
                                boundary_inbox.missing(t, others_live, "node");
                       });
        for (auto& [tile, readings] : boundary_inbox.take(t))
          if (plan.tileLive(static_cast<std::int32_t>(tile), t)) foreign.insert(foreign.end(), readings.begin(), readings.end());
      }
      const std::vector<common::Report> tick_reports = sensors->report(t, foreign);

      auto reports = packReports(tick_reports);
      wsn_msg_ReportBatch report_sample{};
      report_sample.run_id = context.run_id;
      report_sample.tile = context.index;
      report_sample.tick = t;
      report_sample.reports = reports.view();
      report_writer.write(report_sample);
    }
    rejections_record.write();
    progress.waitForCompleted(ticks);
    status.done(ticks);
  });
}

}  // namespace wsn::node

#include "supernode/role.hpp"

#include <algorithm>

#include "common/dds/codec.hpp"
#include "supernode/supernode_tracker.hpp"

namespace wsn::supernode {

void runSupernodeRole(const dds::RoleContext& context) {
  using namespace wsn::dds;
  runRole(context, [&](const Participant& participant, const RunTopics& topics, StatusPublisher& status) {
    const auto& scenario = context.scenario;
    const std::uint32_t self = context.index;
    const auto supernodes = static_cast<std::uint32_t>(context.shape.supernodes);
    SupernodeTracker tracker(supernodeConfig(scenario, self));

    Reader<wsn_msg_DeliveryBatch> delivery_reader(participant, topics.delivery_batch, Qos::reliableKeepAll());
    Reader<wsn_msg_HandoffBatch> handoff_reader(participant, topics.handoff_batch, Qos::reliableKeepAll());
    Writer<wsn_msg_HandoffBatch> handoff_writer(participant, topics.handoff_batch, Qos::reliableKeepAll());
    Writer<wsn_msg_TrackBatch> track_writer(participant, topics.track_batch, Qos::reliableKeepAll());
    RoleLoop loop(participant, context);
    PipelineProgress progress(participant, topics, context, loop);

    TickInbox<std::vector<common::Observation>> deliveries;
    TickInbox<std::vector<common::TrackHandoff>> handoffs;
    loop.watch(delivery_reader, [&] {
      delivery_reader.take([&](const wsn_msg_DeliveryBatch& batch) {
        if (batch.run_id != context.run_id || batch.supernode != self) return;
        deliveries.put(batch.tick, 0, decode(batch.observations, batch.tick));
      });
    });
    loop.watch(handoff_reader, [&] {
      handoff_reader.take([&](const wsn_msg_HandoffBatch& batch) {
        if (batch.run_id != context.run_id || batch.from_supernode == self || batch.from_supernode >= supernodes) return;
        handoffs.put(batch.tick, batch.from_supernode, decode(batch.handoffs));
      });
    });
    const int s = context.shape.supernodes;
    waitForDiscovery(participant, {{&handoff_writer, s}, {&track_writer, 1}},
                     {{&delivery_reader, 1}, {&handoff_reader, s}, {&progress.reader(), 1}}, context);
    status.ready();

    const std::int32_t ticks = scenario.run.ticks;
    const std::size_t others = supernodes - 1;
    for (std::int32_t t = 1; t <= ticks; ++t) {
      loop.waitUntil([&] { return deliveries.count(t) == 1 && (t == 1 || handoffs.count(t - 1) >= others); },
                     [&] { return "deliveries of tick " + std::to_string(t) + " and the other supernodes' handoffs of tick " +
                                  std::to_string(t - 1); });
      auto delivered = std::move(deliveries.take(t)[0]);
      std::vector<common::TrackHandoff> incoming;
      for (auto& [from, batch] : handoffs.take(t - 1))
        for (auto& handoff : batch)
          if (handoff.to_supernode == self) incoming.push_back(handoff);

      auto output = tracker.step(t, delivered, incoming);
      if (t == ticks) {  // the last tick settles what is left in the window
        auto rest = tracker.settleRemaining();
        for (auto& tick_tracks : rest.by_tick) output.settled.by_tick.push_back(std::move(tick_tracks));
      }

      auto tracks = encode(output.tracks);
      auto settled = encodeSettled(output.settled.first, output.settled.by_tick);
      wsn_msg_TrackBatch track_sample{};
      track_sample.run_id = context.run_id;
      track_sample.supernode = self;
      track_sample.tick = t;
      track_sample.observations_in_window = output.observations_in_window;
      track_sample.observations_dropped_stale = static_cast<std::uint32_t>(output.observations_dropped_stale);
      track_sample.tracks = sequenceView<dds_sequence_wsn_msg_TrackEstimate>(tracks.items);
      track_sample.settled_first = output.settled.first;
      track_sample.settled_last = output.settled.last();
      track_sample.settled = sequenceView<dds_sequence_wsn_msg_SettledTrack>(settled.items);
      track_writer.write(track_sample);

      auto outgoing = encode(output.handoffs);
      wsn_msg_HandoffBatch handoff_sample{};
      handoff_sample.run_id = context.run_id;
      handoff_sample.from_supernode = self;
      handoff_sample.tick = t;
      handoff_sample.handoffs = sequenceView<dds_sequence_wsn_msg_TrackHandoff>(outgoing.items);
      handoff_writer.write(handoff_sample);
    }
    progress.waitForCompleted(ticks);
    status.done(ticks);
  });
}

}  // namespace wsn::supernode

#include "supernode/role.hpp"

#include <algorithm>
#include <memory>
#include <optional>
#include <set>

#include "common/dds/codec.hpp"
#include "common/dds/packing.hpp"
#include "common/edge_checks.hpp"
#include "supernode/supernode_tracker.hpp"

namespace wsn::supernode {
namespace {

/// What a supernode takes in at tick t besides its deliveries: the handoffs of tick t - 1
/// addressed to it (a partition cuts those of its partner, counted), and the last tracks of each
/// supernode that dies at t, addressed to it, but for the ones that supernode itself handed on
/// at its last tick.
std::vector<common::TrackHandoff> incomingAt(std::int32_t t, std::uint32_t self, const common::FaultPlan& plan,
                                             std::map<std::uint32_t, std::vector<common::TrackHandoff>> handoffs,
                                             std::map<std::uint32_t, std::vector<common::TrackHandoff>> orphans,
                                             std::uint64_t& lost_to_partition) {
  std::vector<common::TrackHandoff> incoming;
  for (const auto& [from, batch] : handoffs)
    for (const auto& handoff : batch) {
      if (handoff.to_supernode != self) continue;
      if (plan.partitioned(static_cast<std::int32_t>(from), static_cast<std::int32_t>(self), t - 1))
        ++lost_to_partition;
      else
        incoming.push_back(handoff);
    }
  for (const auto& [dead, batch] : orphans) {
    std::set<common::TrackId> handed_on;
    if (const auto it = handoffs.find(dead); it != handoffs.end())
      for (const auto& handoff : it->second) handed_on.insert(handoff.track);
    for (const auto& orphan : batch)
      if (orphan.to_supernode == self && handed_on.count(orphan.track) == 0) incoming.push_back(orphan);
  }
  return incoming;
}

/// The last tracks of supernodes lost by hand, which the aggregator sends once it saw them go: taken
/// at the next step after they arrive, but for those the lost supernode handed on itself at its
/// last tick. Its neighbours received that batch, and an orphan goes to a neighbour: the nearest
/// other supernode to a point of a group always borders it (common/voronoi.hpp).
class LateOrphans {
 public:
  /// Keeps the ids each sender handed on in its latest batch.
  void noteHandoffs(const std::map<std::uint32_t, std::vector<common::TrackHandoff>>& batches) {
    for (const auto& [from, batch] : batches) {
      auto& ids = last_handed_[from];
      ids.clear();
      for (const auto& handoff : batch) ids.insert(handoff.track);
    }
  }
  void add(std::uint32_t dead, std::vector<common::TrackHandoff> orphans) { pending_.emplace_back(dead, std::move(orphans)); }
  /// The orphans addressed to `self` that arrived since the last call.
  std::vector<common::TrackHandoff> takeFor(std::uint32_t self) {
    std::vector<common::TrackHandoff> out;
    for (auto& [dead, batch] : pending_)
      for (auto& orphan : batch)
        if (orphan.to_supernode == self && last_handed_[dead].count(orphan.track) == 0) out.push_back(std::move(orphan));
    pending_.clear();
    return out;
  }

 private:
  std::map<std::uint32_t, std::set<common::TrackId>> last_handed_;
  std::vector<std::pair<std::uint32_t, std::vector<common::TrackHandoff>>> pending_;
};

/// Handoffs travel between bordering groups only (common/voronoi.hpp): a supernode reads those
/// written into its own partition and writes its own into its neighbours', so a batch crosses the
/// wire to the few supernodes that border it instead of to all of them. No neighbours: no writer.
struct HandoffLinks {
  HandoffLinks(const dds::Participant& participant, const dds::RunTopics& topics, std::uint32_t self,
               std::vector<std::uint32_t> bordering)
      : neighbours(std::move(bordering)),
        reader(participant, topics.handoff_batch,
               dds::Qos::reliableKeepAll().inPartition(dds::topic_names::handoffPartition(self))) {
    std::vector<std::string> partitions;
    for (const auto j : neighbours) partitions.push_back(dds::topic_names::handoffPartition(j));
    if (!neighbours.empty())
      writer.emplace(participant, topics.handoff_batch, dds::Qos::reliableKeepAll().inPartitions(partitions));
  }
  bool borders(std::uint32_t j) const { return std::find(neighbours.begin(), neighbours.end(), j) != neighbours.end(); }
  dds::Writer<wsn_msg_HandoffBatch>* writerOrNull() { return writer ? &*writer : nullptr; }

  const std::vector<std::uint32_t> neighbours;
  dds::Reader<wsn_msg_HandoffBatch> reader;
  std::optional<dds::Writer<wsn_msg_HandoffBatch>> writer;
};

/// Tick t's tracks (with the settled ticks and the running counts), then its handoffs, once the
/// handoff writer matched every neighbour that restarts at t + 1 (the tracks first: the aggregator
/// must finish t for the restarted supernode's predecessor to be gone). Without neighbours there
/// is no handoff writer and nothing to hand off.
void publishTick(dds::Writer<wsn_msg_TrackBatch>& track_writer, dds::Writer<wsn_msg_HandoffBatch>* handoff_writer,
                 const std::vector<std::uint32_t>& neighbours, dds::RestartedReaders& restarted, std::uint64_t run_id,
                 std::uint32_t self, const SupernodeTracker::TickOutput& output, std::uint64_t handoffs_lost_partition) {
  using namespace wsn::dds;
  auto tracks = encode(output.tracks);
  auto settled = encodeSettled(output.settled.first, output.settled.by_tick);
  wsn_msg_TrackBatch track_sample{};
  track_sample.run_id = run_id;
  track_sample.supernode = self;
  track_sample.tick = output.tick;
  track_sample.observations_in_window = output.observations_in_window;
  track_sample.observations_dropped_stale = static_cast<std::uint32_t>(output.observations_dropped_stale);
  track_sample.handoffs_lost_partition = static_cast<std::uint32_t>(handoffs_lost_partition);
  track_sample.tracks = sequenceView<dds_sequence_wsn_msg_TrackEstimate>(tracks.items);
  track_sample.settled_first = output.settled.first;
  track_sample.settled_last = output.settled.last();
  track_sample.settled = sequenceView<dds_sequence_wsn_msg_SettledTrack>(settled.items);
  track_writer.write(track_sample);

  if (handoff_writer == nullptr) return;
  restarted.waitFor(*handoff_writer, output.tick + 1, neighbours);
  auto outgoing = encode(output.handoffs);
  wsn_msg_HandoffBatch handoff_sample{};
  handoff_sample.run_id = run_id;
  handoff_sample.from_supernode = self;
  handoff_sample.tick = output.tick;
  handoff_sample.handoffs = sequenceView<dds_sequence_wsn_msg_TrackHandoff>(outgoing.items);
  handoff_writer->write(handoff_sample);
}

/// What a supernode reads, checked at the edge (common/edge_checks.hpp) and filed per tick: its
/// deliveries, its neighbours' handoffs and the aggregator's re-homed tracks. Refusals are counted
/// for rejected.json; a sample of a tick before a restarted supernode's first is no refusal.
class CheckedInputs {
 public:
  CheckedInputs(const dds::RoleContext& context, const common::FaultPlan& plan, const HandoffLinks& links,
                LateOrphans& late_orphans)
      : record(context),
        context_(context),
        plan_(plan),
        links_(links),
        late_orphans_(late_orphans),
        bounds_(common::edgeBounds(context.scenario)),
        supernodes_(static_cast<std::uint32_t>(context.shape.supernodes)),
        first_(context.first_tick) {
    deliveries.skipThrough(first_ - 1);
    handoffs.skipThrough(first_ - 2);
    orphans.skipThrough(first_ - 1);
  }

  void delivery(const wsn_msg_DeliveryBatch& batch) {
    const std::string topic = dds::topic_names::kDeliveryBatch;
    if (const auto why = common::checkBatchHeader(batch.run_id, context_.run_id, 0, 1, batch.tick, bounds_.ticks))
      return rejections.add(topic, *why);
    if (batch.supernode != context_.index) return rejections.add(topic, RejectReason::kMisaddressed);
    if (batch.tick < first_) return;  // before a restart: ticks this process takes no part in
    if (dds::packedCount(batch.observations) > bounds_.max_reports) return rejections.add(topic, RejectReason::kTooLong);
    if (!deliveries.accepts(batch.tick, 0)) return rejections.add(topic, RejectReason::kDuplicate);
    std::vector<common::Observation> observations;
    try {
      observations = dds::unpackObservations(batch.observations, batch.tick);
    } catch (const dds::PackingError&) {
      return rejections.add(topic, RejectReason::kMalformed);  // not filed: the network model's own batch still counts
    }
    common::dropRejected(observations, [&](const common::Observation& o) { return common::checkObservation(o, bounds_); },
                         topic, rejections);
    deliveries.put(batch.tick, 0, std::move(observations));
  }

  void handoff(const wsn_msg_HandoffBatch& batch) {
    const std::string topic = dds::topic_names::kHandoffBatch;
    if (const auto why = header(batch)) return rejections.add(topic, *why);
    if (!links_.borders(batch.from_supernode)) return rejections.add(topic, RejectReason::kMisaddressed);
    if (!plan_.supernodeLive(static_cast<std::int32_t>(batch.from_supernode), batch.tick)) return;  // the faults
    if (batch.tick < first_ - 1) return;  // before a restart
    if (!handoffs.accepts(batch.tick, batch.from_supernode)) return rejections.add(topic, RejectReason::kDuplicate);
    handoffs.put(batch.tick, batch.from_supernode, checked(batch, topic));
  }

  void rehome(const wsn_msg_HandoffBatch& batch) {
    const std::string topic = dds::topic_names::kRehomeBatch;
    if (const auto why = header(batch)) return rejections.add(topic, *why);
    if (batch.tick < first_) return;  // before a restart
    if (plan_.supernodeDies(static_cast<std::int32_t>(batch.from_supernode), batch.tick)) {
      if (!orphans.accepts(batch.tick, batch.from_supernode)) return rejections.add(topic, RejectReason::kDuplicate);
      orphans.put(batch.tick, batch.from_supernode, checked(batch, topic));
    } else {  // a supernode lost by hand
      late_orphans_.add(batch.from_supernode, checked(batch, topic));
    }
  }

  dds::TickInbox<std::vector<common::Observation>> deliveries;
  dds::TickInbox<std::vector<common::TrackHandoff>> handoffs;
  dds::TickInbox<std::vector<common::TrackHandoff>> orphans;
  dds::RejectionsRecord record;  // on disk also if the role fails
  common::RejectionLog& rejections = record.log();

 private:
  using RejectReason = common::RejectReason;

  std::optional<RejectReason> header(const wsn_msg_HandoffBatch& batch) const {
    return common::checkBatchHeader(batch.run_id, context_.run_id, batch.from_supernode, supernodes_, batch.tick,
                                    bounds_.ticks);
  }

  std::vector<common::TrackHandoff> checked(const wsn_msg_HandoffBatch& batch, const std::string& topic) {
    auto items = dds::decode(batch.handoffs);
    common::dropRejected(items, [&](const common::TrackHandoff& h) { return common::checkHandoff(h, bounds_, supernodes_); },
                         topic, rejections);
    return items;
  }

  const dds::RoleContext& context_;
  const common::FaultPlan& plan_;
  const HandoffLinks& links_;
  LateOrphans& late_orphans_;
  const common::EdgeBounds bounds_;
  const std::uint32_t supernodes_;
  const std::int32_t first_;
};

/// A restarted supernode's start barrier: its writers must reach the live processes, not the dead
/// ones whose endpoints linger until their lease ends, so it waits for their readers by name; its
/// producers wait for its own readers (RestartedReaders).
void waitForPeersOfRestart(const dds::Participant& participant, const dds::RoleContext& context,
                           const common::FaultPlan& plan, HandoffLinks& links, const dds::WriterBase& track_writer) {
  const std::int32_t first = context.first_tick;
  std::vector<std::string> peers;
  for (const auto j : plan.liveSupernodeIndices(first))
    if (links.borders(j))
      peers.push_back(dds::roleIdentity(
          "supernode", j, plan.incarnation(common::FaultRole::kSupernode, static_cast<std::int32_t>(j), first)));
  std::vector<std::pair<const dds::WriterBase*, std::vector<std::string>>> writers{
      {&track_writer, {dds::roleIdentity("aggregator", 0, 1)}}};
  if (links.writer) writers.push_back({&*links.writer, peers});
  dds::waitForRoleReaders(participant, writers, context);
}

/// The start barrier: at tick 1 every endpoint's peers by count; a restarted process's by name.
void waitForPeers(const dds::Participant& participant, const dds::RoleContext& context, const common::FaultPlan& plan,
                  HandoffLinks& links, const dds::WriterBase& track_writer,
                  const std::vector<std::pair<const dds::ReaderBase*, int>>& readers) {
  if (context.first_tick != 1) return waitForPeersOfRestart(participant, context, plan, links, track_writer);
  const int n = static_cast<int>(links.neighbours.size());
  std::vector<std::pair<const dds::WriterBase*, int>> writers{{&track_writer, 1}};
  if (links.writer) writers.push_back({&*links.writer, n});
  auto all_readers = readers;
  all_readers.push_back({&links.reader, n});
  dds::waitForDiscovery(participant, writers, all_readers, context);
}

}  // namespace

void runSupernodeRole(const dds::RoleContext& context) {
  using namespace wsn::dds;
  runRole(context, [&](const Participant& participant, const RunTopics& topics, StatusPublisher& status) {
    const auto& scenario = context.scenario;
    const std::uint32_t self = context.index;
    auto plan = context.faultPlan();
    // A restarted supernode starts afresh at its first tick; the others at tick 1.
    auto tracker = std::make_unique<SupernodeTracker>(supernodeConfig(scenario, self), context.first_tick);
    LateOrphans late_orphans;

    Reader<wsn_msg_DeliveryBatch> delivery_reader(participant, topics.delivery_batch,
                                                  Qos::reliableKeepAll().inPartition(topic_names::supernodePartition(self)));
    HandoffLinks links(participant, topics, self, tracker->neighbours());
    Reader<wsn_msg_HandoffBatch> rehome_reader(participant, topics.rehome_batch, Qos::reliableKeepAll());
    Writer<wsn_msg_TrackBatch> track_writer(participant, topics.track_batch, Qos::reliableKeepAll());
    RoleLoop loop(participant, context);
    PipelineProgress progress(participant, topics, context, loop);
    RestartedReaders restarted(participant, context, plan);

    // A restarted supernode reads from its first tick on: the handoffs of the tick before it, the
    // rest of that tick.
    const std::int32_t first = context.first_tick;
    CheckedInputs inputs(context, plan, links, late_orphans);
    loop.watch(delivery_reader, [&] { delivery_reader.take([&](const wsn_msg_DeliveryBatch& b) { inputs.delivery(b); }); });
    loop.watch(links.reader, [&] { links.reader.take([&](const wsn_msg_HandoffBatch& b) { inputs.handoff(b); }); });
    loop.watch(rehome_reader, [&] { rehome_reader.take([&](const wsn_msg_HandoffBatch& b) { inputs.rehome(b); }); });
    auto& deliveries = inputs.deliveries;
    auto& handoffs = inputs.handoffs;
    auto& orphans = inputs.orphans;
    // A neighbour killed by hand: its handoffs stop at the first tick that did not come. Another
    // supernode's loss changes nothing here (it never sends to this one), so its tick is now.
    std::int32_t t = first;
    LostProcesses lost(participant, topics, context, loop, [&](common::FaultRole role, std::int32_t index) {
      if (role != common::FaultRole::kSupernode) return;
      const auto j = static_cast<std::uint32_t>(index);
      plan.loseUnscheduled(role, index, links.borders(j) ? handoffs.firstMissing(j, t - 1) : t);
    });
    waitForPeers(participant, context, plan, links, track_writer,
                 {{&delivery_reader, 1}, {&rehome_reader, 1}, {&progress.reader(), 1}});
    status.ready();

    const std::int32_t ticks = scenario.run.ticks;
    std::uint64_t handoffs_lost_partition = 0;
    for (; t <= ticks; ++t) {
      if (const auto fault = plan.processFaultAt(common::FaultRole::kSupernode, static_cast<std::int32_t>(self), t)) {
        enactProcessFault(*fault, context, status, progress, loop);
        // Back from a pause: the supernodes that adopted the group meanwhile hand its tracks back.
        t = fault->lastTick();
        handoffs.skipThrough(t - 1);
        if (t < ticks) tracker = std::make_unique<SupernodeTracker>(supernodeConfig(scenario, self), t + 1);
        continue;
      }
      // The handoffs of t - 1 come from every neighbour live then (a loss announced meanwhile
      // changes which), the orphans of a scheduled death from the aggregator.
      const auto others = [&] {
        std::size_t count = 0;
        for (const auto j : plan.liveSupernodeIndices(t - 1)) count += links.borders(j) ? 1 : 0;
        return count;
      };
      const std::size_t dying = plan.dyingAt(t).size();
      loop.waitUntil(
          [&] {
            return deliveries.count(t) == 1 && (t == 1 || handoffs.count(t - 1) >= others()) && orphans.count(t) >= dying;
          },
          [&] {
            std::vector<std::uint32_t> senders;
            for (const auto j : plan.liveSupernodeIndices(t - 1))
              if (links.borders(j)) senders.push_back(j);
            return "deliveries of tick " + std::to_string(t) + (deliveries.count(t) == 1 ? " (in)" : " (missing)") +
                   ", the handoffs of tick " + std::to_string(t - 1) + " from " +
                   (t == 1 ? std::string("none") : handoffs.missing(t - 1, senders, "supernode")) +
                   (dying > 0 ? " and the aggregator's re-homed tracks" : "");
          });
      auto delivered = std::move(deliveries.take(t)[0]);
      auto handed = handoffs.take(t - 1);
      late_orphans.noteHandoffs(handed);
      auto incoming = incomingAt(t, self, plan, std::move(handed), orphans.take(t), handoffs_lost_partition);
      for (auto& orphan : late_orphans.takeFor(self))
        if (!tracker->tracks(orphan.track)) incoming.push_back(std::move(orphan));

      tracker->setLiveSupernodes(plan.liveSupernodes(std::min(t + 1, ticks)));
      auto output = tracker->step(t, delivered, incoming);
      if (t == ticks) {  // the last tick settles what is left in the window
        auto rest = tracker->settleRemaining();
        for (auto& tick_tracks : rest.by_tick) output.settled.by_tick.push_back(std::move(tick_tracks));
      }

      publishTick(track_writer, links.writerOrNull(), links.neighbours, restarted, context.run_id, self, output,
                  handoffs_lost_partition);
    }
    inputs.record.write();
    progress.waitForCompleted(ticks);
    status.done(ticks);
  });
}

}  // namespace wsn::supernode

#include "aggregator/role.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <stdexcept>

#include "aggregator/association.hpp"
#include "aggregator/fault_report.hpp"
#include "aggregator/run_files.hpp"
#include "aggregator/run_scorer.hpp"
#include "common/dds/codec.hpp"
#include "common/edge_checks.hpp"
#include "common/output.hpp"
#include "common/provenance.hpp"
#include "common/truth.hpp"
#include "supernode/rehome.hpp"

namespace wsn::aggregator {
namespace {

/// Why a track batch is refused before anything in it counts: its header, or more settled ticks
/// than a window holds, on which decodeSettled would throw and end this process (a forged batch
/// found by fuzz/samples_fuzzer.cpp).
std::optional<common::RejectReason> trackBatchRefusal(const wsn_msg_TrackBatch& batch, std::uint64_t run_id,
                                                      std::uint32_t supernodes, const common::EdgeBounds& bounds,
                                                      std::int32_t window) {
  if (const auto why = common::checkBatchHeader(batch.run_id, run_id, batch.supernode, supernodes, batch.tick, bounds.ticks))
    return why;
  if (!dds::settledSpanFits(batch.settled_first, batch.settled_last, window)) return common::RejectReason::kTooLong;
  return std::nullopt;
}

struct SupernodeBatch {
  std::vector<common::TrackEstimate> tracks;
  std::uint32_t observations_in_window = 0;
  std::uint32_t observations_dropped_stale = 0;
  std::uint32_t handoffs_lost_partition = 0;
  std::int32_t settled_first = 1;  ///< the ticks it settles: settled_first .. + settled.size() - 1
  std::vector<std::vector<common::TrackEstimate>> settled;
};

/// One tick's batches split by stream: the live tracks, and the settled tracks by the tick they
/// settle.
struct TickInputs {
  std::vector<SupernodeTracks> live;
  std::map<std::int32_t, std::vector<SupernodeTracks>> settled;
};

/// The settled stream: the supernodes' estimates of each tick once it left their windows,
/// associated by an associator of its own (its ids are its own), scored the same way as the live
/// stream and written to tracks_settled.csv.
class SettledStream {
 public:
  SettledStream(const common::Scenario& scenario, const std::string& run_dir, const common::FaultPlan& plan)
      : associator_(makeAssociator(associationContext(scenario))),
        scorer_(kSettledStream, scenario.metrics, scenario.supernodes),
        csv_(run_dir + "/tracks_settled.csv", globalTracksCsvHeader()),
        supernodes_(static_cast<std::uint32_t>(scenario.supernodes.size())),
        window_size_(scenario.tracker.window_size),
        ticks_(scenario.run.ticks),
        plan_(plan) {}

  /// The ticks that settled by tick t (every supernode settles the same ticks, one window size
  /// behind; a tick settles once), in order. Under faults a tick is settled by the supernodes live
  /// from it until it left their windows (FaultPlan::settles), and by none at all when no such
  /// supernode exists: it is scored with no tracks once the ticks around it settle.
  void add(std::int32_t t, std::map<std::int32_t, std::vector<SupernodeTracks>>& settled, const common::Truth& truth) {
    const std::int32_t leaving = t == ticks_ ? ticks_ : t - window_size_ + 1;
    std::int32_t through = leaving;
    if (!settled.empty()) through = std::max(through, settled.rbegin()->first);
    for (std::int32_t tick = settled_through_ + 1; tick <= through; ++tick) {
      const auto it = settled.find(tick);
      const std::size_t got = it == settled.end() ? 0 : it->second.size();
      const std::size_t expected = expectedAt(tick);
      if (got == 0 && expected == 0 && tick > leaving) break;  // not due yet
      if (got != expected || tick > t)
        throw std::runtime_error("settled tracks of tick " + std::to_string(tick) + " came from " + std::to_string(got) +
                                 " of " + std::to_string(expected) + " supernodes at tick " + std::to_string(t) +
                                 " (settled through " + std::to_string(settled_through_) + ")");
      std::vector<SupernodeTracks> none;
      auto settled_global = associator_->associate(tick, it == settled.end() ? none : it->second);
      scorer_.add(tick, truth.at(tick), settled_global);
      for (const auto& track : settled_global) csv_.row(globalTrackCsvRow(tick, track));
      settled_through_ = tick;
    }
  }

  /// Throws unless every tick up to `ticks` settled.
  void checkComplete(std::int32_t ticks) const {
    if (settled_through_ != ticks)
      throw std::runtime_error("the settled stream ends at tick " + std::to_string(settled_through_) + " of " +
                               std::to_string(ticks));
  }
  RunScores finish() const { return scorer_.finish(); }
  void close() { csv_.close(); }

 private:
  std::unique_ptr<TrackAssociator> associator_;
  RunScorer scorer_;
  common::CsvFile csv_;
  /// How many supernodes settle `tick`.
  std::size_t expectedAt(std::int32_t tick) const {
    if (plan_.empty()) return supernodes_;
    std::size_t n = 0;
    for (std::uint32_t j = 0; j < supernodes_; ++j)
      n += plan_.settles(static_cast<std::int32_t>(j), tick, window_size_, ticks_) ? 1 : 0;
    return n;
  }

  std::uint32_t supernodes_;
  std::int32_t window_size_;
  std::int32_t ticks_;
  const common::FaultPlan& plan_;  ///< the role's: a supernode lost by hand joins it during the run
  std::int32_t settled_through_ = 0;
};

/// Splits tick t's batches into the two streams, writes the supernodes' tracks to
/// tracks_supernode.csv and notes each supernode's running total of stale drops.
TickInputs splitBatches(std::map<std::uint32_t, SupernodeBatch> batches, std::int32_t t, common::CsvFile& supernode_csv,
                        std::map<std::uint32_t, std::uint64_t>& dropped_stale_by_supernode) {
  TickInputs inputs;
  for (auto& [supernode, batch] : batches) {
    for (const auto& track : batch.tracks) supernode_csv.row(supernodeTrackCsvRow(t, supernode, track));
    dropped_stale_by_supernode[supernode] = batch.observations_dropped_stale;
    inputs.live.push_back({supernode, std::move(batch.tracks)});
    for (std::size_t k = 0; k < batch.settled.size(); ++k)
      inputs.settled[batch.settled_first + static_cast<std::int32_t>(k)].push_back(
          {supernode, std::move(batch.settled[k])});
  }
  return inputs;
}

void publishGlobalTracks(dds::Writer<wsn_msg_GlobalTrackBatch>& writer, std::uint64_t run_id, std::int32_t t,
                         const std::vector<common::TrackEstimate>& global) {
  auto encoded = dds::encode(global);
  wsn_msg_GlobalTrackBatch sample{};
  sample.run_id = run_id;
  sample.tick = t;
  sample.tracks = dds::sequenceView<dds_sequence_wsn_msg_TrackEstimate>(encoded.items);
  writer.write(sample);
}

/// Every metric's live values by name: a new metric goes out without an IDL change.
void publishTickMetrics(dds::Writer<wsn_msg_TickMetrics>& writer, std::uint64_t run_id, std::int32_t t,
                        const TickScores& scores) {
  const auto live = scores.live();
  std::vector<wsn_msg_MetricValue> values;
  values.reserve(live.size());
  for (const auto& v : live) values.push_back({const_cast<char*>(v.name.c_str()), v.value});
  wsn_msg_TickMetrics sample{};
  sample.run_id = run_id;
  sample.tick = t;
  sample.values = dds::sequenceView<dds_sequence_wsn_msg_MetricValue>(values);
  writer.write(sample);
}

/// The aggregator's part in the scenario's faults: when a supernode dies at tick t + 1, its tracks
/// of tick t go to the supernodes adopting its group (the rehome topic), and what every fault did
/// is recorded for metrics.json.
class FaultsAtAggregator {
 public:
  FaultsAtAggregator(const common::FaultPlan& plan, const common::Scenario& scenario, std::uint64_t run_id,
                     dds::Writer<wsn_msg_HandoffBatch> writer, dds::RestartedReaders& restarted)
      : plan_(plan),
        report_(plan, scenario.tracker.window_size, scenario.run.ticks),
        context_{scenario.supernodes, {}, scenario.dynamics.delta, scenario.tracker.window_size},
        ticks_(scenario.run.ticks),
        run_id_(run_id),
        writer_(std::move(writer)),
        restarted_(restarted) {}

  const dds::Writer<wsn_msg_HandoffBatch>& writer() const { return writer_; }

  /// Keeps each supernode's running total of handoffs a partition cut.
  void noteHandoffsLost(const std::map<std::uint32_t, SupernodeBatch>& batches) {
    for (const auto& [supernode, batch] : batches) handoffs_lost_[supernode] = batch.handoffs_lost_partition;
  }

  void afterTick(std::int32_t t, const TickScores& scores, const std::vector<SupernodeTracks>& live) {
    std::uint64_t handoffs_lost = 0;
    for (const auto& [supernode, lost] : handoffs_lost_) handoffs_lost += lost;
    report_.addTick(t, {scores.find("truth_targets").value_or(0), scores.find("tracks").value_or(0),
                        scores.find("ospa").value_or(0)},
                    live, handoffs_lost);
    for (const auto& supernode : live) last_tracks_[supernode.supernode] = supernode.tracks;
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (it->second - 1 != t) {
        ++it;
        continue;
      }
      publishOrphans(it->first, it->second);
      it = pending_.erase(it);
    }
    if (t >= ticks_) return;
    for (const std::int32_t dead : plan_.dyingAt(t + 1)) publishOrphans(static_cast<std::uint32_t>(dead), t + 1);
  }

  /// A node tile lost by hand, announced while tick `current` was awaited: recorded, no more.
  void loseTile(std::int32_t tile, std::int32_t current) {
    report_.addUnscheduled(common::FaultSpec::kill(common::FaultRole::kNode, tile, current));
  }

  /// A supernode lost by hand, its tracks missing from tick `from` on, seen while tick `current`
  /// was awaited: its tracks of from - 1 go to the adopters at once when that tick is done, else
  /// once it is.
  void lose(std::uint32_t supernode, std::int32_t from, std::int32_t current) {
    report_.addUnscheduled(common::FaultSpec::kill(common::FaultRole::kSupernode, static_cast<std::int32_t>(supernode), from));
    if (from > ticks_) return;
    if (from == current)
      publishOrphans(supernode, from);
    else
      pending_[supernode] = from;
  }

  /// The "faults" block of metrics.json; null for a run without faults.
  Json json() const { return plan_.empty() ? Json(nullptr) : report_.json(); }

 private:
  /// The tracks `dead` reported at tick - 1, addressed to the supernodes live at `tick`.
  void publishOrphans(std::uint32_t dead, std::int32_t tick) {
    context_.live = plan_.liveSupernodes(tick);
    const auto orphans = supernode::orphanHandoffs(last_tracks_[dead], tick - 1, context_);
    report_.addOrphans(dead, tick, orphans);
    auto encoded = dds::encode(orphans);
    wsn_msg_HandoffBatch sample{};
    sample.run_id = run_id_;
    sample.from_supernode = dead;
    sample.tick = tick;
    sample.handoffs = dds::sequenceView<dds_sequence_wsn_msg_TrackHandoff>(encoded.items);
    restarted_.waitFor(writer_, tick);
    writer_.write(sample);
  }

  const common::FaultPlan& plan_;
  FaultReport report_;
  supernode::OrphanContext context_;
  std::int32_t ticks_;
  std::uint64_t run_id_;
  dds::Writer<wsn_msg_HandoffBatch> writer_;
  dds::RestartedReaders& restarted_;
  std::map<std::uint32_t, std::uint64_t> handoffs_lost_;
  std::map<std::uint32_t, std::vector<common::TrackEstimate>> last_tracks_;  ///< each supernode's latest
  std::map<std::uint32_t, std::int32_t> pending_;  ///< lost by hand -> the tick its orphans go out for
};

}  // namespace

void runAggregatorRole(const dds::RoleContext& context) {
  using namespace wsn::dds;
  using Clock = std::chrono::steady_clock;
  runRole(context, [&](const Participant& participant, const RunTopics& topics, StatusPublisher& status) {
    const auto& scenario = context.scenario;
    const common::Truth truth(truthConfig(scenario));
    const auto associator = makeAssociator(associationContext(scenario));
    // Read now, not after the run: a malformed run.json must not cost the run's metrics.json.
    const std::string provenance = common::readRunProvenance(context.run_dir + "/run.json");
    RunScorer scorer(kLiveStream, scenario.metrics, scenario.supernodes);
    auto plan = context.faultPlan();

    Reader<wsn_msg_TrackBatch> track_reader(participant, topics.track_batch, Qos::reliableKeepAll());
    Writer<wsn_msg_TickDone> tick_done_writer(participant, topics.tick_done, Qos::reliableKeepAll());
    // For live views only: not in waitForDiscovery, since nobody need be listening.
    Writer<wsn_msg_GlobalTrackBatch> global_writer(participant, topics.global_track_batch, Qos::reliableKeepAll());
    Writer<wsn_msg_TickMetrics> tick_metrics_writer(participant, topics.tick_metrics, Qos::reliableKeepAll());
    RestartedReaders restarted(participant, context, plan);
    FaultsAtAggregator faults(plan, scenario, context.run_id,
                              Writer<wsn_msg_HandoffBatch>(participant, topics.rehome_batch, Qos::reliableKeepAll()),
                              restarted);
    RoleLoop loop(participant, context);
    LiveRolesDone roles_done(participant, topics, context);
    TickInbox<SupernodeBatch> inbox;
    const auto supernodes = static_cast<std::uint32_t>(context.shape.supernodes);
    // Every batch and track is checked before it counts (common/edge_checks.hpp); refusals are
    // counted for rejected.json.
    const common::EdgeBounds bounds = common::edgeBounds(scenario);
    RejectionsRecord rejections_record(context);  // on disk also if the role fails
    common::RejectionLog& rejections = rejections_record.log();
    loop.watch(track_reader, [&] {
      track_reader.take([&](const wsn_msg_TrackBatch& batch) {
        const std::string topic = topic_names::kTrackBatch;
        if (const auto why = trackBatchRefusal(batch, context.run_id, supernodes, bounds, scenario.tracker.window_size))
          return rejections.add(topic, *why);
        if (!plan.supernodeLive(static_cast<std::int32_t>(batch.supernode), batch.tick)) return;  // the faults
        if (!inbox.accepts(batch.tick, batch.supernode)) return rejections.add(topic, common::RejectReason::kDuplicate);
        const auto check = [&](const common::TrackEstimate& track) { return common::checkTrack(track, bounds); };
        auto tracks = decode(batch.tracks);
        common::dropRejected(tracks, check, topic, rejections);
        auto settled = decodeSettled(batch.settled, batch.settled_first, batch.settled_last, scenario.tracker.window_size);
        for (auto& tick_tracks : settled) common::dropRejected(tick_tracks, check, topic, rejections);
        inbox.put(batch.tick, batch.supernode,
                  {std::move(tracks), batch.observations_in_window, batch.observations_dropped_stale,
                   batch.handoffs_lost_partition, batch.settled_first, std::move(settled)});
      });
    });
    // A supernode killed by hand: its tracks stop at the first tick that did not come, and its last
    // ones go to the adopters.
    std::int32_t current = 1;
    LostProcesses lost(participant, topics, context, loop, [&](common::FaultRole role, std::int32_t index) {
      if (role == common::FaultRole::kNode) {
        faults.loseTile(index, current);  // its reports stop at the network model, not here
        return;
      }
      const auto j = static_cast<std::uint32_t>(index);
      const std::int32_t from = inbox.firstMissing(j, current);
      plan.loseUnscheduled(role, index, from);
      faults.lose(j, from, current);
    });
    // Every role follows the end of each tick: the tiles for back-pressure, all for the end of run.
    const int tick_done_readers = context.shape.processes() - 1;
    waitForDiscovery(participant, {{&tick_done_writer, tick_done_readers}, {&faults.writer(), context.shape.supernodes}},
                     {{&track_reader, context.shape.supernodes}}, context);
    status.ready();

    common::CsvFile supernode_csv(context.run_dir + "/tracks_supernode.csv", supernodeTracksCsvHeader());
    common::CsvFile global_csv(context.run_dir + "/tracks.csv", globalTracksCsvHeader());
    SettledStream settled(scenario, context.run_dir, plan);
    common::CsvFile per_tick_csv(context.run_dir + "/metrics_per_tick.csv", scorer.csvHeader());
    // Each supernode reports its running total of stale drops; the run's total is the sum of
    // the last value of each.
    std::map<std::uint32_t, std::uint64_t> dropped_stale_by_supernode;
    std::optional<Clock::time_point> first_tick_at;
    const std::int32_t ticks = scenario.run.ticks;
    for (std::int32_t t = 1; t <= ticks; ++t) {
      current = t;
      loop.waitUntil([&] { return inbox.count(t) >= plan.liveSupernodeIndices(t).size(); },
                     [&] {
                       return "tracks of tick " + std::to_string(t) + " from " +
                              inbox.missing(t, plan.liveSupernodeIndices(t), "supernode");
                     });
      if (!first_tick_at) first_tick_at = Clock::now();
      auto batches = inbox.take(t);
      faults.noteHandoffsLost(batches);
      TickInputs inputs = splitBatches(std::move(batches), t, supernode_csv, dropped_stale_by_supernode);
      settled.add(t, inputs.settled, truth);
      auto global = associator->associate(t, inputs.live);
      const TickScores scores = scorer.add(t, truth.at(t), global);
      per_tick_csv.row(scorer.csvRow(scores));
      for (const auto& track : global) global_csv.row(globalTrackCsvRow(t, track));
      publishGlobalTracks(global_writer, context.run_id, t, global);
      publishTickMetrics(tick_metrics_writer, context.run_id, t, scores);
      restarted.waitFor(tick_done_writer, t);
      tick_done_writer.write(wsn_msg_TickDone{context.run_id, t});
      faults.afterTick(t, scores, inputs.live);
      status.running(t);
    }
    std::uint64_t dropped_stale_total = 0;
    for (const auto& [supernode, dropped] : dropped_stale_by_supernode) dropped_stale_total += dropped;
    // From the end of tick 1 to the end of tick T at the aggregator: T - 1 tick intervals of the
    // steady pipeline (start-up and discovery excluded; the launcher reports the total).
    const double wall_s = std::chrono::duration<double>(Clock::now() - first_tick_at.value_or(Clock::now())).count();
    const double ticks_per_s = wall_s > 0 ? (ticks - 1) / wall_s : 0.0;
    settled.checkComplete(ticks);
    const std::vector<RunScores> run_scores{scorer.finish(), settled.finish()};
    supernode_csv.close();
    global_csv.close();
    settled.close();
    per_tick_csv.close();

    // Everything but the "timing" line is a pure function of (scenario, seed).
    RunInfo info{scenario.name, scenario.run.seed, ticks, scenario.tracker.engine, truth.targetCount(),
                 dropped_stale_total, scenario.aggregator.association, provenance, faults.json()};
    common::writeTextFile(context.run_dir + "/metrics.json", metricsJson(info, run_scores, wall_s, ticks_per_s));
    rejections_record.write();
    status.done(ticks);
    roles_done.wait();
  });
}

}  // namespace wsn::aggregator

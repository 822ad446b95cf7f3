#include "aggregator/role.hpp"

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <stdexcept>

#include "aggregator/association.hpp"
#include "aggregator/run_files.hpp"
#include "aggregator/run_scorer.hpp"
#include "common/dds/codec.hpp"
#include "common/output.hpp"
#include "common/provenance.hpp"
#include "common/truth.hpp"

namespace wsn::aggregator {
namespace {

struct SupernodeBatch {
  std::vector<common::TrackEstimate> tracks;
  std::uint32_t observations_in_window = 0;
  std::uint32_t observations_dropped_stale = 0;
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
  SettledStream(const common::Scenario& scenario, const std::string& run_dir, std::uint32_t supernodes)
      : associator_(makeAssociator(associationContext(scenario))),
        scorer_(kSettledStream, scenario.metrics, scenario.supernodes),
        csv_(run_dir + "/tracks_settled.csv", globalTracksCsvHeader()),
        supernodes_(supernodes) {}

  /// The ticks that settled by tick t (every supernode settles the same ticks, one window size
  /// behind; a tick settles once), in order.
  void add(std::int32_t t, std::map<std::int32_t, std::vector<SupernodeTracks>>& settled, const common::Truth& truth) {
    for (auto& [tick, settled_tracks] : settled) {
      if (tick != settled_through_ + 1 || tick > t || settled_tracks.size() != supernodes_)
        throw std::runtime_error("settled tracks of tick " + std::to_string(tick) + " came from " +
                                 std::to_string(settled_tracks.size()) + " of " + std::to_string(supernodes_) +
                                 " supernodes at tick " + std::to_string(t) + " (settled through " +
                                 std::to_string(settled_through_) + ")");
      auto settled_global = associator_->associate(tick, settled_tracks);
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
  std::uint32_t supernodes_;
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

    Reader<wsn_msg_TrackBatch> track_reader(participant, topics.track_batch, Qos::reliableKeepAll());
    Writer<wsn_msg_GlobalTrackBatch> global_writer(participant, topics.global_track_batch, Qos::reliableKeepAll());
    // For live views only: not in waitForDiscovery, since nobody need be listening.
    Writer<wsn_msg_TickMetrics> tick_metrics_writer(participant, topics.tick_metrics, Qos::reliableKeepAll());
    RoleLoop loop(participant, context);
    TickInbox<SupernodeBatch> inbox;
    const auto supernodes = static_cast<std::uint32_t>(context.shape.supernodes);
    loop.watch(track_reader, [&] {
      track_reader.take([&](const wsn_msg_TrackBatch& batch) {
        if (batch.run_id != context.run_id || batch.supernode >= supernodes) return;
        inbox.put(batch.tick, batch.supernode,
                  {decode(batch.tracks), batch.observations_in_window, batch.observations_dropped_stale,
                   batch.settled_first,
                   decodeSettled(batch.settled, batch.settled_first, batch.settled_last, scenario.tracker.window_size)});
      });
    });
    // Every role reads the global batches: the tiles for back-pressure, all for the end of run.
    const int global_readers = context.shape.processes() - 1;
    waitForDiscovery(participant, {{&global_writer, global_readers}}, {{&track_reader, context.shape.supernodes}},
                     context);
    status.ready();

    common::CsvFile supernode_csv(context.run_dir + "/tracks_supernode.csv", supernodeTracksCsvHeader());
    common::CsvFile global_csv(context.run_dir + "/tracks.csv", globalTracksCsvHeader());
    SettledStream settled(scenario, context.run_dir, supernodes);
    common::CsvFile per_tick_csv(context.run_dir + "/metrics_per_tick.csv", scorer.csvHeader());
    // Each supernode reports its running total of stale drops; the run's total is the sum of
    // the last value of each.
    std::map<std::uint32_t, std::uint64_t> dropped_stale_by_supernode;
    std::optional<Clock::time_point> first_tick_at;
    const std::int32_t ticks = scenario.run.ticks;
    for (std::int32_t t = 1; t <= ticks; ++t) {
      loop.waitUntil([&] { return inbox.count(t) >= supernodes; },
                     [&] { return "tracks of tick " + std::to_string(t) + " from every supernode"; });
      if (!first_tick_at) first_tick_at = Clock::now();
      TickInputs inputs = splitBatches(inbox.take(t), t, supernode_csv, dropped_stale_by_supernode);
      settled.add(t, inputs.settled, truth);
      auto global = associator->associate(t, inputs.live);
      const TickScores scores = scorer.add(t, truth.at(t), global);
      per_tick_csv.row(scorer.csvRow(scores));
      for (const auto& track : global) global_csv.row(globalTrackCsvRow(t, track));
      publishGlobalTracks(global_writer, context.run_id, t, global);
      publishTickMetrics(tick_metrics_writer, context.run_id, t, scores);
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
    const RunInfo info{scenario.name, scenario.run.seed, ticks, scenario.tracker.engine, truth.targetCount(),
                       dropped_stale_total, scenario.aggregator.association, provenance};
    common::writeTextFile(context.run_dir + "/metrics.json", metricsJson(info, run_scores, wall_s, ticks_per_s));
    status.done(ticks);
    global_writer.waitForAcknowledgements(std::chrono::seconds(10));
  });
}

}  // namespace wsn::aggregator

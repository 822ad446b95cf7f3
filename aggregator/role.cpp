#include "aggregator/role.hpp"

#include <chrono>
#include <map>
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
    // The settled stream: the supernodes' estimates of each tick once it left their windows,
    // associated by an associator of its own (its ids are its own) and scored the same way.
    const auto settled_associator = makeAssociator(associationContext(scenario));
    RunScorer settled_scorer(kSettledStream, scenario.metrics, scenario.supernodes);
    std::int32_t settled_through = 0;

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
    common::CsvFile settled_csv(context.run_dir + "/tracks_settled.csv", globalTracksCsvHeader());
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
      std::vector<SupernodeTracks> inputs;
      std::map<std::int32_t, std::vector<SupernodeTracks>> settled_inputs;  // by settled tick
      for (auto& [supernode, batch] : inbox.take(t)) {
        for (const auto& track : batch.tracks)
          supernode_csv.row(supernodeTrackCsvRow(t, supernode, track));
        dropped_stale_by_supernode[supernode] = batch.observations_dropped_stale;
        inputs.push_back({supernode, std::move(batch.tracks)});
        for (std::size_t k = 0; k < batch.settled.size(); ++k)
          settled_inputs[batch.settled_first + static_cast<std::int32_t>(k)].push_back(
              {supernode, std::move(batch.settled[k])});
      }
      // Every supernode settles the same ticks (one window size); a tick settles once.
      for (auto& [tick, settled_tracks] : settled_inputs) {
        if (tick != settled_through + 1 || tick > t || settled_tracks.size() != supernodes)
          throw std::runtime_error("settled tracks of tick " + std::to_string(tick) + " came from " +
                                   std::to_string(settled_tracks.size()) + " of " + std::to_string(supernodes) +
                                   " supernodes at tick " + std::to_string(t) + " (settled through " +
                                   std::to_string(settled_through) + ")");
        auto settled_global = settled_associator->associate(tick, settled_tracks);
        settled_scorer.add(tick, truth.at(tick), settled_global);
        for (const auto& track : settled_global) settled_csv.row(globalTrackCsvRow(tick, track));
        settled_through = tick;
      }
      auto global = associator->associate(t, inputs);
      const TickScores scores = scorer.add(t, truth.at(t), global);
      per_tick_csv.row(scorer.csvRow(scores));
      for (const auto& track : global) global_csv.row(globalTrackCsvRow(t, track));

      auto encoded = encode(global);
      wsn_msg_GlobalTrackBatch sample{};
      sample.run_id = context.run_id;
      sample.tick = t;
      sample.tracks = sequenceView<dds_sequence_wsn_msg_TrackEstimate>(encoded.items);
      global_writer.write(sample);

      // Every metric's live values by name: a new metric goes out without an IDL change.
      const auto live = scores.live();
      std::vector<wsn_msg_MetricValue> values;
      values.reserve(live.size());
      for (const auto& v : live) values.push_back({const_cast<char*>(v.name.c_str()), v.value});
      wsn_msg_TickMetrics tick_sample{};
      tick_sample.run_id = context.run_id;
      tick_sample.tick = t;
      tick_sample.values = sequenceView<dds_sequence_wsn_msg_MetricValue>(values);
      tick_metrics_writer.write(tick_sample);
      status.running(t);
    }
    std::uint64_t dropped_stale_total = 0;
    for (const auto& [supernode, dropped] : dropped_stale_by_supernode) dropped_stale_total += dropped;
    // From the end of tick 1 to the end of tick T at the aggregator: T - 1 tick intervals of the
    // steady pipeline (start-up and discovery excluded; the launcher reports the total).
    const double wall_s = std::chrono::duration<double>(Clock::now() - first_tick_at.value_or(Clock::now())).count();
    const double ticks_per_s = wall_s > 0 ? (ticks - 1) / wall_s : 0.0;
    if (settled_through != ticks)
      throw std::runtime_error("the settled stream ends at tick " + std::to_string(settled_through) + " of " +
                               std::to_string(ticks));
    const std::vector<RunScores> run_scores{scorer.finish(), settled_scorer.finish()};
    supernode_csv.close();
    global_csv.close();
    settled_csv.close();
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

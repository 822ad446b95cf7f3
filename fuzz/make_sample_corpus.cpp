// Writes the sample fuzzer's seed corpus (fuzz/corpus/samples/): batches of every topic as the roles
// send them in a run of scenarios/oh_quadrants.yaml -- readings, reports and observations of every
// measurement kind, handoffs, tracks and settled ticks -- encoded by the codec and serialised by
// Cyclone, each file its topic's byte and the CDR bytes. Usage: wsn_fuzz_make_sample_corpus OUT_DIR
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/dds/codec.hpp"
#include "common/dds/packing.hpp"
#include "fuzz/sample_topics.hpp"

namespace {

using namespace wsn;
using fuzz::BatchTopic;

constexpr std::uint64_t kRunId = 1;  // samples_fuzzer.cpp's run

/// One measurement of each kind, well formed (common::wellFormed), at sensor position (x, y).
std::vector<common::Measurement> measurementsAt(double x, double y) {
  using common::MeasurementKind;
  const common::SensorPose pose{x, y, 0.5, 2.0};
  const std::vector<double> classes{0.7, 0.1, 0.1, 0.05, 0.05, 0.0};
  return {
      {MeasurementKind::position, {x + 0.4, y - 0.3}, {0.25, 0.0, 0.0, 0.25}, std::nullopt, {}, 0.01},
      {MeasurementKind::bearing, {0.3}, {0.01}, pose, classes, 0.2},
      {MeasurementKind::range_bearing_rate, {12.0, -0.4, 1.5}, {}, pose, {}, 0.001},
      {MeasurementKind::azimuth_elevation, {0.2, -0.1}, {0.001, 0.0, 0.0, 0.001}, pose, {}, 0.05},
      {MeasurementKind::signal_strength, {3.5}, {}, pose, {}, 0.0},
      {MeasurementKind::presence, {}, {}, pose, classes, 0.0},
  };
}

std::vector<common::Report> reports(std::int32_t tick) {
  std::vector<common::Report> out;
  out.push_back({tick, 1234, 34.5, 12.25, 3, 0, {}});  // a fused centre of mass (Oh eq. 6)
  out.push_back({tick, 77, 7.0, 0.0, common::kFalseAlarm, 2, {}});  // an acoustic detection (An eq. 4)
  for (auto& m : measurementsAt(50.0, 60.0)) {
    const double x = m.kind == common::MeasurementKind::position ? m.values[0] : 50.0;
    const double y = m.kind == common::MeasurementKind::position ? m.values[1] : 60.0;
    out.push_back({tick, 5060, x, y, 1, 0, common::MeasurementRef(std::move(m))});
  }
  return out;
}

common::TrackEstimate track(common::TrackId id, double x, double y, bool classified) {
  common::TrackEstimate t{id, x, y, 1.0, -0.5, {}, 7, {}, std::nullopt};
  for (std::size_t i = 0; i < 4; ++i) t.covariance[i * 5] = 1.0 + static_cast<double>(i);
  if (classified) {
    t.class_probabilities = {0.8, 0.1, 0.05, 0.05, 0.0, 0.0};
    t.stop_probability = 0.1;
  }
  return t;
}

class CorpusWriter {
 public:
  explicit CorpusWriter(std::filesystem::path dir) : dir_(std::move(dir)) { std::filesystem::create_directories(dir_); }

  template <typename Wire>
  void write(BatchTopic topic, const std::string& variant, const Wire& batch) {
    std::vector<std::uint8_t> bytes{static_cast<std::uint8_t>(topic)};
    const auto cdr = topics_.serialize(topic, &batch);
    bytes.insert(bytes.end(), cdr.begin(), cdr.end());
    std::ofstream out(dir_ / (std::string(fuzz::topicName(topic)) + "-" + variant), std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("cannot write the corpus in " + dir_.string());
    ++files_;
  }
  int files() const { return files_; }

 private:
  std::filesystem::path dir_;
  fuzz::SampleTopics topics_;
  int files_ = 0;
};

void writeNodeAndNetwork(CorpusWriter& corpus) {
  std::vector<common::SensorReading> readings{{101, 2.5}, {102, 0.75}, {9999, 12.0}};
  auto wire_readings = dds::encode(readings);
  corpus.write(BatchTopic::kSensorBoundary, "readings",
               wsn_msg_SensorBoundary{kRunId, 1, 5, dds::sequenceView<dds_sequence_wsn_msg_SensorReading>(wire_readings)});
  corpus.write(BatchTopic::kSensorBoundary, "empty", wsn_msg_SensorBoundary{kRunId, 2, 1, {}});

  auto packed = dds::packReports(reports(5));
  corpus.write(BatchTopic::kReportBatch, "every-kind", wsn_msg_ReportBatch{kRunId, 0, 5, packed.view()});
  corpus.write(BatchTopic::kReportBatch, "empty", wsn_msg_ReportBatch{kRunId, 3, 100, {}});

  std::vector<common::Observation> observations;
  for (const auto& r : reports(4)) observations.push_back(common::observationOf(r, 6));
  auto packed_observations = dds::packObservations(observations);
  corpus.write(BatchTopic::kDeliveryBatch, "every-kind", wsn_msg_DeliveryBatch{kRunId, 2, 6, packed_observations.view()});
}

void writeSupernodeAndAggregator(CorpusWriter& corpus) {
  common::TrackHandoff handoff;
  handoff.track = 0x0002000000000011ULL;
  handoff.to_supernode = 1;
  handoff.last_tick = 9;
  handoff.state = {49.0, 20.0, 1.2, 0.1};
  for (std::size_t i = 0; i < 4; ++i) handoff.covariance[i * 5] = 0.5;
  handoff.hits = 6;
  handoff.confirmed = true;
  auto plain = handoff;
  handoff.class_probabilities = {0.6, 0.2, 0.1, 0.1, 0.0, 0.0};
  auto handoffs = dds::encode(std::vector<common::TrackHandoff>{handoff, plain});
  corpus.write(BatchTopic::kHandoffBatch, "two",
               wsn_msg_HandoffBatch{kRunId, 0, 9, dds::sequenceView<dds_sequence_wsn_msg_TrackHandoff>(handoffs.items)});

  const std::vector<common::TrackEstimate> tracks{track(11, 20.0, 30.0, false), track(12, 80.0, 75.0, true)};
  auto wire_tracks = dds::encode(tracks);
  auto settled = dds::encodeSettled(3, {tracks, {}, {track(11, 18.0, 29.0, false)}});
  wsn_msg_TrackBatch batch{};
  batch.run_id = kRunId;
  batch.supernode = 3;
  batch.tick = 8;
  batch.observations_in_window = 40;
  batch.tracks = dds::sequenceView<dds_sequence_wsn_msg_TrackEstimate>(wire_tracks.items);
  batch.settled_first = 3;
  batch.settled_last = 5;
  batch.settled = dds::sequenceView<dds_sequence_wsn_msg_SettledTrack>(settled.items);
  corpus.write(BatchTopic::kTrackBatch, "settled", batch);
  batch.settled_last = 2;  // nothing settles yet
  batch.settled = {};
  corpus.write(BatchTopic::kTrackBatch, "unsettled", batch);

  corpus.write(BatchTopic::kGlobalTrackBatch, "two",
               wsn_msg_GlobalTrackBatch{kRunId, 8, dds::sequenceView<dds_sequence_wsn_msg_TrackEstimate>(wire_tracks.items)});
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    CorpusWriter corpus(argv[1]);
    writeNodeAndNetwork(corpus);
    writeSupernodeAndAggregator(corpus);
    std::printf("%d samples in %s\n", corpus.files(), argv[1]);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s: %s\n", argv[0], error.what());
    return 1;
  }
  return 0;
}

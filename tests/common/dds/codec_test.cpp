// The codec and the packed batches through Cyclone's own CDR serializer (no participant): a
// measurement of any kind, with its noise, pose and class likelihoods, comes back as it went, and
// bytes that are not a packed batch are refused.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include "common/dds/codec.hpp"
#include "common/dds/packing.hpp"
#include "dds/ddsi/ddsi_cdrstream.h"

namespace wsn::dds {
namespace {

/// A 1-D acoustic bearing with its variance, the antenna's pose and ONERA's 7 class likelihoods.
common::MeasurementRef bearing() {
  common::Measurement m;
  m.kind = common::MeasurementKind::bearing;
  m.values = {0.25};
  m.noise = {0.0027};  // (3 degrees)^2 in rad^2
  m.sensor = common::SensorPose{12.0, 34.0, 1.5};
  m.class_likelihoods = {0.6, 0.2 / 3, 0.2 / 3, 0.2 / 3, 0.05, 0.05, 0.0};
  return common::MeasurementRef(std::move(m));
}

/// Serializes `sample` with the topic type's ops as a writer would (the type's minimum XCDR
/// version), checks the bytes as a reader would, and deserializes them into a fresh sample.
template <typename Sample>
struct WireRoundTrip {
  WireRoundTrip(const Sample& sample, const dds_topic_descriptor_t& desc) : ops(desc.m_ops) {
    const std::uint32_t xcdr = dds_stream_minimum_xcdr_version(ops);
    dds_ostream_t os;
    dds_ostream_init(&os, 0, xcdr);
    const bool written = dds_stream_write(&os, reinterpret_cast<const char*>(&sample), ops) != nullptr;
    bytes.assign(os.m_buffer, os.m_buffer + os.m_index);
    dds_ostream_fini(&os);
    if (!written) return;
    std::uint32_t offset = 0;
    valid = dds_stream_normalize_data(reinterpret_cast<char*>(bytes.data()), &offset,
                                      static_cast<std::uint32_t>(bytes.size()), false, xcdr, ops) != nullptr;
    if (!valid) return;
    dds_istream_t is;
    dds_istream_init(&is, static_cast<std::uint32_t>(bytes.size()), bytes.data(), xcdr);
    dds_stream_read(&is, reinterpret_cast<char*>(&received), ops);
    dds_istream_fini(&is);
  }
  ~WireRoundTrip() { dds_stream_free_sample(&received, ops); }
  WireRoundTrip(const WireRoundTrip&) = delete;
  WireRoundTrip& operator=(const WireRoundTrip&) = delete;

  const std::uint32_t* ops;
  std::vector<unsigned char> bytes;
  bool valid = false;
  Sample received{};
};

TEST_CASE("a bearing report with noise, pose and class likelihoods crosses the wire unchanged", "[codec]") {
  common::Report position;
  position.tick = 7;
  position.sensor = 3;
  position.x = 10.5;
  position.y = -2.25;
  position.measurement = common::MeasurementRef(common::Measurement::position(10.5, -2.25));  // with its values
  const common::Report bearing_report{7, 12, 12.0, 34.0, common::kFalseAlarm, 0, bearing()};
  std::vector<common::Report> reports{position, bearing_report};

  auto packed = packReports(reports);
  wsn_msg_ReportBatch batch{};
  batch.run_id = 99;
  batch.tile = 1;
  batch.tick = 7;
  batch.reports = packed.view();
  reports.clear();  // the packed batch owns what the sample points at

  const WireRoundTrip wire(batch, wsn_msg_ReportBatch_desc);
  REQUIRE(wire.valid);
  CHECK(packedCount(wire.received.reports) == 2);
  const auto decoded = unpackReports(wire.received.reports, wire.received.tick);
  REQUIRE(decoded.size() == 2);
  CHECK(decoded[0] == position);
  CHECK(decoded[1] == bearing_report);
  CHECK(decoded[1].measurement->dimension() == 1);
  CHECK(decoded[1].measurement->hasNoise());
  CHECK(common::wellFormed(decoded[1]));
}

TEST_CASE("an observation keeps its generation tick and measurement through the wire", "[codec]") {
  const common::Observation sent{5, 9, 12, 12.0, 34.0, 2, 0, bearing()};
  const std::vector<common::Observation> observations{sent, common::Observation{4, 9, 3, 1.0, 2.0, 1}};
  auto packed = packObservations(observations);
  wsn_msg_DeliveryBatch batch{};
  batch.supernode = 0;
  batch.tick = 9;
  batch.observations = packed.view();

  const WireRoundTrip wire(batch, wsn_msg_DeliveryBatch_desc);
  REQUIRE(wire.valid);
  const auto decoded = unpackObservations(wire.received.observations, wire.received.tick);
  REQUIRE(decoded.size() == 2);
  CHECK(decoded[0] == sent);
  CHECK(decoded[1] == observations[1]);
}

TEST_CASE("a plain position report packs as x and y alone and comes back plain", "[codec]") {
  // Built the way the position sensors build it, from the position alone: no measurement object.
  const std::vector<common::Report> reports{common::Report{2, 4, 3.5, 4.5, 1, 2}};
  REQUIRE(reports[0].measurement.get() == nullptr);
  auto packed = packReports(reports);
  // Count, then sensor, x, y, target, power level and the plain-position marker.
  CHECK(packed.bytes.size() == 4 + 4 + 8 + 8 + 4 + 4 + 1);
  const auto decoded = unpackReports(packed.view(), 2);
  REQUIRE(decoded.size() == 1);
  CHECK(decoded[0] == reports[0]);
  CHECK(decoded[0].measurement.get() == nullptr);
}

TEST_CASE("a malformed or over-long measurement is refused when packing", "[codec]") {
  common::Measurement m = common::Measurement::position(0.0, 0.0);
  m.class_likelihoods.assign(common::kMaxClasses + 1, 0.1);
  common::Report r{1, 0, 0.0, 0.0, 0, 0, common::MeasurementRef(m)};
  CHECK_THROWS_AS(packReports(std::vector<common::Report>{r}), std::invalid_argument);
  m.class_likelihoods.clear();
  m.values.assign(common::kMaxMeasurementDimension + 1, 1.0);
  r.measurement = common::MeasurementRef(m);
  CHECK_THROWS_AS(packReports(std::vector<common::Report>{r}), std::invalid_argument);
  // An empty position would read back as something else.
  m.values.clear();
  r.measurement = common::MeasurementRef(m);
  CHECK_THROWS_AS(packReports(std::vector<common::Report>{r}), std::invalid_argument);
}

TEST_CASE("the largest measurement of any kind crosses the wire unchanged", "[codec]") {
  // Range, bearing and range rate: the largest dimension of any kind (3), its full 3 x 3 R, the
  // radar's pose and kMaxClasses class likelihoods.
  common::Measurement m;
  m.kind = common::MeasurementKind::range_bearing_rate;
  m.values = {120.0, 0.3, -4.5};
  m.noise = {25.0, 0.0, 0.0, 0.0, 0.0004, 0.0, 0.0, 0.0, 1.0};
  m.sensor = common::SensorPose{5.0, 6.0, 0.75, 4.0};
  m.class_likelihoods.assign(common::kMaxClasses, 1.0 / static_cast<double>(common::kMaxClasses));
  m.clutter_density = 0.2 / (1000.0 * 1.5707963267948966 * 40.0);  // 0.2 per scan over range x 90 deg x +-20 m/s
  REQUIRE(common::wellFormed(m));
  const std::vector<common::Report> reports{common::Report{3, 8, 5.0, 6.0, 1, 0, common::MeasurementRef(m)}};
  auto packed = packReports(reports);
  wsn_msg_ReportBatch batch{};
  batch.tick = 3;
  batch.reports = packed.view();
  const WireRoundTrip wire(batch, wsn_msg_ReportBatch_desc);
  REQUIRE(wire.valid);
  const auto decoded = unpackReports(wire.received.reports, wire.received.tick);
  REQUIRE(decoded.size() == 1);
  CHECK(decoded[0] == reports[0]);
}

TEST_CASE("bytes that are not a packed batch are refused with PackingError, never read past their end", "[codec]") {
  const std::vector<common::Report> reports{common::Report{1, 3, 1.0, 2.0, 0, 0, bearing()}};
  const auto good = packReports(reports).bytes;
  const auto unpack = [](std::vector<std::uint8_t> bytes) {
    dds_sequence_octet seq{};
    seq._length = seq._maximum = static_cast<std::uint32_t>(bytes.size());
    seq._buffer = bytes.data();
    return unpackReports(seq, 1);
  };
  REQUIRE(unpack(good).size() == 1);
  // Every truncation, including no bytes at all.
  for (std::size_t n = 0; n < good.size(); ++n)
    CHECK_THROWS_AS(unpack(std::vector<std::uint8_t>(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n))), PackingError);
  // A byte after the last item.
  auto longer = good;
  longer.push_back(0);
  CHECK_THROWS_WITH(unpack(longer), Catch::Contains("1 bytes after its last item"));
  // A count far beyond what the bytes can hold is refused before anything is allocated for it.
  auto huge = good;
  huge[0] = huge[1] = huge[2] = huge[3] = 0xff;
  CHECK_THROWS_WITH(unpack(huge), Catch::Contains("4294967295 items claimed"));
  dds_sequence_octet huge_view{};
  huge_view._length = huge_view._maximum = static_cast<std::uint32_t>(huge.size());
  huge_view._buffer = huge.data();
  CHECK(packedCount(huge_view) == 4294967295u);
  // A kind beyond the last (byte 4 + 4 + 8 + 8 + 4 + 4 = 32 is the measurement's kind).
  auto kind = good;
  kind[32] = static_cast<std::uint8_t>(common::MeasurementKind::presence) + 1;
  CHECK_THROWS_WITH(unpack(kind), Catch::Contains("measurement kind 6"));
  // More values than any kind has.
  auto values = good;
  values[33] = static_cast<std::uint8_t>(common::kMaxMeasurementDimension + 1);
  CHECK_THROWS_WITH(unpack(values), Catch::Contains("beyond what the wire holds"));
}

TEST_CASE("a track and a handoff carry their class vector, a track its stop probability, across the wire", "[codec]") {
  common::TrackEstimate classified{(2ULL << 48) | 5, 1.0, 2.0, 0.5, -0.5, {}, 3, {0.7, 0.1, 0.1, 0.05, 0.05, 0.0}, 0.25};
  classified.covariance[5] = 0.5;
  const common::TrackEstimate unclassified{(1ULL << 48) | 9, 4.0, 5.0, 0.0, 0.0, {}, 4, {}, {}};
  const std::vector<common::TrackEstimate> tracks{classified, unclassified};
  auto encoded = encode(tracks);
  wsn_msg_GlobalTrackBatch batch{};
  batch.tracks = sequenceView<dds_sequence_wsn_msg_TrackEstimate>(encoded.items);
  const WireRoundTrip track_wire(batch, wsn_msg_GlobalTrackBatch_desc);
  REQUIRE(track_wire.valid);
  CHECK(decode(track_wire.received.tracks) == tracks);
  // None goes as NaN; a value that is no probability reads as none, as a malformed beta does.
  CHECK(std::isnan(encoded.items[1].stop_probability));
  encoded.items[0].stop_probability = 1.5;
  CHECK_FALSE(decode(sequenceView<dds_sequence_wsn_msg_TrackEstimate>(encoded.items))[0].stop_probability);

  common::TrackHandoff handoff;
  handoff.track = classified.track;
  handoff.to_supernode = 1;
  handoff.last_tick = 3;
  handoff.class_probabilities = classified.class_probabilities;
  const std::vector<common::TrackHandoff> handoffs{handoff, common::TrackHandoff{}};
  auto encoded_handoffs = encode(handoffs);
  wsn_msg_HandoffBatch handoff_batch{};
  handoff_batch.handoffs = sequenceView<dds_sequence_wsn_msg_TrackHandoff>(encoded_handoffs.items);
  const WireRoundTrip handoff_wire(handoff_batch, wsn_msg_HandoffBatch_desc);
  REQUIRE(handoff_wire.valid);
  CHECK(decode(handoff_wire.received.handoffs) == handoffs);

  // More classes than the wire's bound would only fail at the write: refused at the encoding.
  common::TrackEstimate too_many = classified;
  too_many.class_probabilities.assign(common::kMaxClasses + 1, 1.0 / static_cast<double>(common::kMaxClasses + 1));
  CHECK_THROWS_AS(encode(std::vector<common::TrackEstimate>{too_many}), std::length_error);
}

}  // namespace
}  // namespace wsn::dds

TEST_CASE("the settled tracks of several ticks cross the wire by tick, empty ticks included") {
  wsn::common::TrackEstimate a{7, 1.0, 2.0, 0.5, -0.5, {}, 3, {0.5, 0.5}, {}};
  a.covariance[0] = 0.25;
  const wsn::common::TrackEstimate b{9, 4.0, 5.0, 0.0, 0.0, {}, 4, {}, {}};
  const std::vector<std::vector<wsn::common::TrackEstimate>> by_tick{{a, b}, {}, {b}};
  auto encoded = wsn::dds::encodeSettled(3, by_tick);
  auto& items = encoded.items;
  REQUIRE(items.size() == 3);
  CHECK(items[0].tick == 3);
  CHECK(items[2].tick == 5);
  const auto seq = wsn::dds::sequenceView<dds_sequence_wsn_msg_SettledTrack>(items);
  const auto back = wsn::dds::decodeSettled(seq, 3, 5, 10);
  REQUIRE(back.size() == 3);
  CHECK(back[0] == by_tick[0]);
  CHECK(back[1].empty());
  CHECK(back[2] == by_tick[2]);
  // An empty range (last < first) decodes to no ticks; one wider than the window is refused.
  CHECK(wsn::dds::decodeSettled(seq, 6, 5, 10).empty());
  CHECK_THROWS_AS(wsn::dds::decodeSettled(seq, 1, 11, 10), std::length_error);
}

TEST_CASE("a track batch settling more ticks than a window is refused before it is decoded") {
  // Found by fuzz/samples_fuzzer.cpp: a TrackBatch with settled ticks 0 .. 121638912 made the
  // aggregator's decodeSettled throw, which ended the aggregator and the run. Receivers now check
  // settledSpanFits first and count the batch as too long. Window 10: ticks 3 .. 12 are 10 ticks.
  CHECK(wsn::dds::settledSpanFits(3, 12, 10));
  CHECK_FALSE(wsn::dds::settledSpanFits(3, 13, 10));
  CHECK_FALSE(wsn::dds::settledSpanFits(0, 121638912, 10));
  // The widest span the wire can say, which 32-bit arithmetic would overflow: 2^32 ticks.
  CHECK_FALSE(wsn::dds::settledSpanFits(INT32_MIN, INT32_MAX, 10));
  // Nothing settles (last < first), whatever the numbers.
  CHECK(wsn::dds::settledSpanFits(INT32_MAX, INT32_MIN, 10));
  CHECK(wsn::dds::settledSpanFits(6, 5, 0));
  const dds_sequence_wsn_msg_SettledTrack none{};
  CHECK_THROWS_AS(wsn::dds::decodeSettled(none, 0, 121638912, 10), std::length_error);
}

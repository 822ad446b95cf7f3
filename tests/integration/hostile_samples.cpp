// A program that is not a role of the run joins its domain and writes, as a role would, the batches
// the supernodes and the aggregator read: deliveries to supernode 0 (as the network model), handoffs
// from supernode 1 to supernode 0, and supernode 2's tracks (to the aggregator). Each batch of ticks
// FIRST..LAST holds four items each wrong in one way, and four more batches are wrong as a whole (tick
// 0, tick T + 5, a producer the run does not have, another run's id). The cluster tests check that
// with security off every item and batch is refused and counted in rejected.json and nothing
// non-finite reaches the outputs, and that with security on the program is refused (its writer is
// not allowed, or without credentials no reader ever matches it). Joins as the example viewer does
// (CYCLONEDDS_URI, WSN_PARTICIPANT_INDEX).
//
// Usage: wsn_hostile_samples deliveries|handoffs|tracks DOMAIN RUN_ID TICKS FIRST_TICK LAST_TICK [WAIT_S]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "common/dds/codec.hpp"
#include "common/dds/packing.hpp"
#include "common/dds/entity.hpp"
#include "common/dds/role_runtime.hpp"

namespace {

namespace dds = wsn::dds;

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

/// What a batch says about itself: run, producer (or addressee, for deliveries) and tick.
struct Header {
  std::uint64_t run_id;
  std::uint32_t producer;
  std::int32_t tick;
};

/// Writes one topic's batches: a forged batch of four bad items for each header `good`, and the
/// plausible-item batches of the headers `bad`.
template <typename Batch>
struct Forger {
  std::function<Batch(const Header&, bool)> make;  // (header, bad items?) -> batch

  int run(const dds::Participant& participant, const char* topic_name, dds::Qos qos, const std::vector<Header>& good,
          const std::vector<Header>& bad, int wait_s) const {
    const dds::Topic<Batch> topic(participant, topic_name);
    dds::Writer<Batch> writer(participant, topic, std::move(qos));
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(wait_s);
    while (writer.matchedReaders() < 1) {
      if (std::chrono::steady_clock::now() > deadline)
        throw std::runtime_error(std::string("no ") + topic_name + " reader within " + std::to_string(wait_s) + " s");
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    for (const auto& h : good) writer.write(make(h, true));
    for (const auto& h : bad) writer.write(make(h, false));
    writer.waitForAcknowledgements(std::chrono::seconds(10));
    return writer.matchedReaders();
  }
};

wsn::common::Observation observation(std::int32_t generated, std::uint32_t sensor, double x, double y) {
  wsn::common::Observation o;
  o.tick_generated = generated;
  o.sensor = sensor;
  o.x = x;
  o.y = y;
  o.target = wsn::common::kFalseAlarm;
  return o;
}

wsn_msg_TrackHandoff handoff(std::uint32_t to, std::int32_t last_tick, double x, double y) {
  wsn_msg_TrackHandoff h{};
  h.track = 77;
  h.to_supernode = to;
  h.last_tick = last_tick;
  h.state[0] = x;
  h.state[1] = y;
  for (int i = 0; i < 4; ++i) h.covariance[5 * i] = 1.0;
  return h;
}

wsn_msg_TrackEstimate track(double x, double y, double covariance, std::int32_t last_seen) {
  wsn_msg_TrackEstimate t{};
  t.track = std::numeric_limits<std::uint64_t>::max();
  t.x = x;
  t.y = y;
  for (int i = 0; i < 4; ++i) t.covariance[5 * i] = covariance;
  t.last_seen_tick = last_seen;
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 7 && argc != 8) {
    std::fprintf(stderr, "usage: wsn_hostile_samples deliveries|handoffs|tracks DOMAIN RUN_ID TICKS FIRST_TICK LAST_TICK [WAIT_S]\n");
    return 2;
  }
  try {
    const std::string what = argv[1];
    const auto domain = static_cast<dds_domainid_t>(std::stol(argv[2]));
    const std::uint64_t run_id = std::stoull(argv[3], nullptr, 16);
    const std::int32_t ticks = std::stoi(argv[4]), first = std::stoi(argv[5]), last = std::stoi(argv[6]);
    const int wait_s = argc == 8 ? std::stoi(argv[7]) : 30;
    const std::uint32_t producer = what == "deliveries" ? 0 : what == "handoffs" ? 1 : 2;
    std::vector<Header> good, bad{{run_id, producer, 0}, {run_id, producer, ticks + 5}, {run_id, 99, first},
                                  {run_id ^ 1, producer, first}};
    for (std::int32_t t = first; t <= last; ++t) good.push_back({run_id, producer, t});
    const dds::Participant participant(domain);
    // Storage the batches' sequences point into, alive until the writes are acknowledged.
    dds::Packed observations;
    std::vector<wsn_msg_TrackHandoff> handoffs;
    std::vector<wsn_msg_TrackEstimate> tracks;
    int readers = 0;
    if (what == "deliveries") {
      Forger<wsn_msg_DeliveryBatch> forger{[&](const Header& h, bool bad_items) {
        observations = dds::packObservations(
            bad_items ? std::vector{observation(h.tick, 1, kNaN, 10.0), observation(h.tick, 2, 1e308, 10.0),
                                    observation(h.tick, 2000000000u, 10.0, 10.0), observation(h.tick + 1, 3, 10.0, 10.0)}
                      : std::vector{observation(1, 1, 10.0, 10.0)});
        wsn_msg_DeliveryBatch b{};
        b.run_id = h.run_id;
        b.supernode = h.producer;
        b.tick = h.tick;
        b.observations = observations.view();
        return b;
      }};
      readers = forger.run(participant, dds::topic_names::kDeliveryBatch,
                           dds::Qos::reliableKeepAll().inPartition(dds::topic_names::supernodePartition(0)), good, bad, wait_s);
    } else if (what == "handoffs") {
      Forger<wsn_msg_HandoffBatch> forger{[&](const Header& h, bool bad_items) {
        handoffs = bad_items ? std::vector{handoff(99, h.tick, 10.0, 10.0), handoff(0, h.tick, kNaN, 10.0),
                                           handoff(0, h.tick, 1e308, 10.0), handoff(0, 0, 10.0, 10.0)}
                             : std::vector{handoff(0, 1, 10.0, 10.0)};
        wsn_msg_HandoffBatch b{};
        b.run_id = h.run_id;
        b.from_supernode = h.producer;
        b.tick = h.tick;
        b.handoffs = dds::sequenceView<dds_sequence_wsn_msg_TrackHandoff>(handoffs);
        return b;
      }};
      readers = forger.run(participant, dds::topic_names::kHandoffBatch,
                           dds::Qos::reliableKeepAll().inPartition(dds::topic_names::handoffPartition(0)), good, bad, wait_s);
    } else if (what == "tracks") {
      Forger<wsn_msg_TrackBatch> forger{[&](const Header& h, bool bad_items) {
        tracks = bad_items ? std::vector{track(kNaN, 10.0, 1.0, h.tick), track(10.0, 10.0, kInf, h.tick),
                                         track(1e308, -1e308, 1.0, h.tick), track(10.0, 10.0, 1.0, ticks + 5)}
                           : std::vector{track(10.0, 10.0, 1.0, 1)};
        wsn_msg_TrackBatch b{};
        b.run_id = h.run_id;
        b.supernode = h.producer;
        b.tick = h.tick;
        b.tracks = dds::sequenceView<dds_sequence_wsn_msg_TrackEstimate>(tracks);
        return b;
      }};
      readers = forger.run(participant, dds::topic_names::kTrackBatch, dds::Qos::reliableKeepAll(), good, bad, wait_s);
    } else {
      throw std::invalid_argument("the first argument is deliveries, handoffs or tracks, got '" + what + "'");
    }
    std::printf("wrote %zu forged %s batches to %d readers\n", good.size() + bad.size(), what.c_str(), readers);
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "wsn_hostile_samples: %s\n", error.what());
    return 1;
  }
}

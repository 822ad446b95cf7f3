// A program that is not a role of the run joins its domain with security off and writes report
// batches as a node tile would, each with something wrong: non-finite and absurd positions, a
// sensor the run does not have, a tick outside the run, a tile the run does not have, another run's
// id, bytes that are no packed batch. The cluster test `hostile_reports` checks that none of it
// reaches the outputs and that the network model counts every refusal in rejected.json. Joins as
// the example viewer does (CYCLONEDDS_URI, WSN_PARTICIPANT_INDEX).
//
// Usage: wsn_hostile_reports DOMAIN RUN_ID TICKS FIRST_TICK LAST_TICK [WAIT_S]
#include <chrono>
#include <cstdio>
#include <cstdlib>
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
namespace common = wsn::common;

common::Report report(std::uint32_t sensor, double x, double y) {
  common::Report r;
  r.sensor = sensor;
  r.x = x;
  r.y = y;
  r.target = common::kFalseAlarm;
  return r;
}

void write(dds::Writer<wsn_msg_ReportBatch>& writer, std::uint64_t run_id, std::uint32_t tile, std::int32_t tick,
           const std::vector<common::Report>& reports) {
  auto packed = dds::packReports(reports);
  wsn_msg_ReportBatch batch{};
  batch.run_id = run_id;
  batch.tile = tile;
  batch.tick = tick;
  batch.reports = packed.view();
  writer.write(batch);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6 && argc != 7) {
    std::fprintf(stderr, "usage: wsn_hostile_reports DOMAIN RUN_ID TICKS FIRST_TICK LAST_TICK [WAIT_S]\n");
    return 2;
  }
  try {
    const auto domain = static_cast<dds_domainid_t>(std::stol(argv[1]));
    const std::uint64_t run_id = std::stoull(argv[2], nullptr, 16);
    const std::int32_t ticks = std::stoi(argv[3]), first = std::stoi(argv[4]), last = std::stoi(argv[5]);
    const int wait_s = argc == 7 ? std::stoi(argv[6]) : 30;
    const dds::Participant participant(domain);
    const dds::Topic<wsn_msg_ReportBatch> topic(participant, dds::topic_names::kReportBatch);
    dds::Writer<wsn_msg_ReportBatch> writer(participant, topic, dds::Qos::reliableKeepAll());
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(wait_s);
    while (writer.matchedReaders() < 1) {
      if (std::chrono::steady_clock::now() > deadline) throw std::runtime_error("no wsn_report_batch reader within " + std::to_string(wait_s) + " s");
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    // Tile 0's batches of FIRST_TICK .. LAST_TICK, ahead of the tile's own: four bad reports each.
    const std::vector<common::Report> bad{report(1, nan, 10.0), report(2, 10.0, -inf), report(3, 1e308, -1e308),
                                    report(2000000000u, 10.0, 10.0)};
    for (std::int32_t t = first; t <= last; ++t) write(writer, run_id, 0, t, bad);
    // One batch each that is wrong as a whole.
    const std::vector<common::Report> plausible{report(1, 10.0, 10.0)};
    write(writer, run_id, 0, 0, plausible);           // before the first tick
    write(writer, run_id, 0, ticks + 5, plausible);   // after the last
    write(writer, run_id, 999, first, plausible);     // a tile the run does not have
    write(writer, run_id ^ 1, 0, first, plausible);   // another run
    // Bytes that are no packed batch (a count of 3 items, then too few bytes for them), for the tick
    // after the forged ones: refused as malformed and not filed, so the tile's own batch still counts.
    std::vector<std::uint8_t> garbage{3, 0, 0, 0, 0xde, 0xad, 0xbe, 0xef};
    wsn_msg_ReportBatch malformed{};
    malformed.run_id = run_id;
    malformed.tile = 0;
    malformed.tick = last + 1;
    malformed.reports = dds::sequenceView<dds_sequence_octet>(garbage);
    writer.write(malformed);
    writer.waitForAcknowledgements(std::chrono::seconds(10));
    std::printf("wrote %d forged report batches to %d readers\n", last - first + 1 + 5, writer.matchedReaders());
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "wsn_hostile_reports: %s\n", error.what());
    return 1;
  }
}

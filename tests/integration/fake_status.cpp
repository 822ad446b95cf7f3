// A program that is not a role of the run yet joins its domain (as any local program that can read
// the run directory can) and claims, on the status topic, that a role FAILED, with terminal escape
// sequences in the claim: the cluster test `fake_status` checks that the run neither stops for it
// nor prints the escapes. Joins as the example viewer does: CYCLONEDDS_URI names the run's
// cyclonedds.xml and WSN_PARTICIPANT_INDEX one of its viewer slots. Under DDS Security the run's
// file gives it the viewer's credentials, which may not write status (exit 1, "not allowed"); a copy
// of the file without them gives it none, and no role's reader ever matches it (exit 1 after
// WAIT_S seconds, "no status reader").
//
// Usage: wsn_fake_status DOMAIN RUN_ID ROLE INDEX MESSAGE [WAIT_S]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "common/dds/entity.hpp"
#include "common/dds/role_runtime.hpp"

int main(int argc, char** argv) {
  if (argc != 6 && argc != 7) {
    std::fprintf(stderr, "usage: wsn_fake_status DOMAIN RUN_ID ROLE INDEX MESSAGE [WAIT_S]\n");
    return 2;
  }
  namespace dds = wsn::dds;
  try {
    const auto domain = static_cast<dds_domainid_t>(std::stol(argv[1]));
    const std::uint64_t run_id = std::stoull(argv[2], nullptr, 16);
    const int wait_s = argc == 7 ? std::stoi(argv[6]) : 30;
    const dds::Participant participant(domain);
    const dds::Topic<wsn_msg_ProcessStatus> status_topic(participant, dds::topic_names::kProcessStatus);
    // A role's QoS and role marker: as like a real role's status writer as a stranger can make it.
    dds::Writer<wsn_msg_ProcessStatus> writer(participant, status_topic, dds::Qos::lastValueTransientLocal());
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(wait_s);
    while (writer.matchedReaders() < 1) {
      if (std::chrono::steady_clock::now() > deadline)
        throw std::runtime_error("no status reader within " + std::to_string(wait_s) + " s");
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    wsn_msg_ProcessStatus sample{};
    sample.run_id = run_id;
    sample.role = argv[3];
    sample.index = static_cast<std::uint32_t>(std::stoul(argv[4]));
    sample.state = wsn_msg_FAILED;
    sample.tick = 1;
    sample.message = argv[5];
    writer.write(sample);
    writer.waitForAcknowledgements(std::chrono::seconds(10));
    std::printf("wrote a FAILED status for %s %s to %d readers\n", argv[3], argv[4], writer.matchedReaders());
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "wsn_fake_status: %s\n", error.what());
    return 1;
  }
}

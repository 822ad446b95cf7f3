// A program that is not a role of the run yet joins its domain (as any local program that can read
// the run directory can) and makes claims on the status topic in a role's name: by default that it
// FAILED, with terminal escape sequences in the claim; with CLAIMS, each STATE:TICK in turn, 300 ms
// apart (FAULTED:0 says the process is lost, FAULTED:7 that it reached a fault the scenario lacks,
// DONE:T that it finished). The cluster test `fake_status` checks that the run neither stops nor
// changes for them and prints no escape. Joins as the example viewer does: CYCLONEDDS_URI names the
// run's cyclonedds.xml and WSN_PARTICIPANT_INDEX one of its viewer slots. Under DDS Security the
// run's file gives it the viewer's credentials, which may not write status (exit 1, "not
// allowed"); a copy of the file without them gives it none, and no role's reader ever matches it
// (exit 1 after WAIT_S seconds, "no status reader").
//
// Usage: wsn_fake_status DOMAIN RUN_ID ROLE INDEX MESSAGE [WAIT_S [CLAIMS]]   CLAIMS: STATE:TICK,...
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "common/dds/entity.hpp"
#include "common/dds/role_runtime.hpp"

namespace {

/// "FAILED:1,FAULTED:0" -> {(FAILED, 1), (FAULTED, 0)}.
std::vector<std::pair<wsn_msg_ProcessState, std::int32_t>> parseClaims(const std::string& text) {
  static const std::map<std::string, wsn_msg_ProcessState> kStates = {
      {"STARTING", wsn_msg_STARTING}, {"READY", wsn_msg_READY}, {"RUNNING", wsn_msg_RUNNING},
      {"DONE", wsn_msg_DONE},         {"FAILED", wsn_msg_FAILED}, {"FAULTED", wsn_msg_FAULTED}};
  std::vector<std::pair<wsn_msg_ProcessState, std::int32_t>> claims;
  std::istringstream in(text);
  for (std::string claim; std::getline(in, claim, ',');) {
    const auto colon = claim.find(':');
    if (colon == std::string::npos || !kStates.contains(claim.substr(0, colon)))
      throw std::invalid_argument("a claim is STATE:TICK with STATE one of STARTING READY RUNNING DONE FAILED FAULTED, got '" +
                                  claim + "'");
    claims.emplace_back(kStates.at(claim.substr(0, colon)), std::stoi(claim.substr(colon + 1)));
  }
  return claims;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6 || argc > 8) {
    std::fprintf(stderr, "usage: wsn_fake_status DOMAIN RUN_ID ROLE INDEX MESSAGE [WAIT_S [STATE:TICK,...]]\n");
    return 2;
  }
  namespace dds = wsn::dds;
  try {
    const auto domain = static_cast<dds_domainid_t>(std::stol(argv[1]));
    const std::uint64_t run_id = std::stoull(argv[2], nullptr, 16);
    const int wait_s = argc >= 7 ? std::stoi(argv[6]) : 30;
    const auto claims = parseClaims(argc == 8 ? argv[7] : "FAILED:1");
    const dds::Participant participant(domain);
    const dds::Topic<wsn_msg_ProcessStatus> status_topic(participant, dds::topic_names::kProcessStatus);
    // A role's QoS and role marker: as like a real role's status writer as a stranger can make it,
    // but keeping every claim it wrote for late joiners, not each process's last: the launcher's
    // reader may match after the first claim was written (a role's matched first; CI under ASan
    // once counted 6 of 7 so), and the test counts every claim the launcher refused.
    dds::Writer<wsn_msg_ProcessStatus> writer(participant, status_topic, dds::Qos::lastValueTransientLocal().keepingAll());
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(wait_s);
    while (writer.matchedReaders() < 1) {
      if (std::chrono::steady_clock::now() > deadline)
        throw std::runtime_error("no status reader within " + std::to_string(wait_s) + " s");
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    for (std::size_t i = 0; i < claims.size(); ++i) {
      // Apart, so that even a reader that keeps only an instance's last sample acts on each.
      if (i > 0) std::this_thread::sleep_for(std::chrono::milliseconds(300));
      wsn_msg_ProcessStatus sample{};  // its mac all zeros: the stranger has no key
      sample.run_id = run_id;
      sample.role = argv[3];
      sample.index = static_cast<std::uint32_t>(std::stoul(argv[4]));
      sample.state = claims[i].first;
      sample.tick = claims[i].second;
      sample.message = argv[5];
      writer.write(sample);
      writer.waitForAcknowledgements(std::chrono::seconds(10));
    }
    std::printf("wrote %zu status claims for %s %s to %d readers\n", claims.size(), argv[3], argv[4], writer.matchedReaders());
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "wsn_fake_status: %s\n", error.what());
    return 1;
  }
}

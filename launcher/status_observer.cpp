// The launcher's observer of the status topic (status_observer.hpp).
#include "launcher/status_observer.hpp"

#include <algorithm>
#include <cstring>

#include "common/dds/cyclone_config.hpp"
#include "common/dds/process_main.hpp"
#include "common/dds/security.hpp"
#include "common/printable.hpp"
#include "launcher/hosts.hpp"

namespace wsn::launcher {

StatusObserver::StatusObserver(const ClusterOptions& options, int participant_index)
    : domain_(static_cast<dds_domainid_t>(options.identity.domain),
              dds::cycloneConfigFor(dds::readConfigFile(hostConfigFile(options.run_dir, options.hosts, 0)),
                                    participant_index,
                                    options.in_process ? dds::kInProcessIdentity : dds::kLauncherIdentity)),
      participant_(domain_.id()),
      // Its own topic only: under DDS Security a participant may create only the topics its
      // identity may read or write.
      status_topic_(participant_, dds::topic_names::kProcessStatus),
      // Every sample, not the last of each process: each refused one is counted.
      reader_(participant_, status_topic_, dds::Qos::lastValueTransientLocal(dds::Endpoint::kViewer).keepingAll()),
      writer_(participant_, status_topic_, dds::Qos::lastValueTransientLocal(dds::Endpoint::kViewer)),
      condition_(reader_),
      waitset_(participant_),
      key_(options.status_key),
      run_dir_(options.run_dir),
      run_id_(options.identity.run_id) {
  waitset_.attach(condition_.handle(), 0);
}

void StatusObserver::poll(std::chrono::milliseconds timeout, std::int32_t& aggregator_tick,
                          std::map<std::string, std::string>& failed_messages, std::vector<Faulted>& faulted) {
  waitset_.wait(timeout);
  reader_.take([&](const wsn_msg_ProcessStatus& s) {
    if (s.run_id != run_id_) return;
    if (!key_.authentic(s)) {
      rejections_.add(dds::topic_names::kProcessStatus, common::RejectReason::kUnauthenticated);
      return;
    }
    if (s.state == wsn_msg_FAILED)
      failed_messages.emplace(common::printable(s.role) + " " + std::to_string(s.index), common::printable(s.message));
    if (s.state == wsn_msg_FAULTED) faulted.push_back({s.role, s.index, s.tick});
    if (std::strcmp(s.role, "aggregator") == 0 && (s.state == wsn_msg_RUNNING || s.state == wsn_msg_DONE))
      aggregator_tick = std::max(aggregator_tick, s.tick);
  });
}

void StatusObserver::announceLost(const std::string& role, std::uint32_t index, const std::string& why) {
  wsn_msg_ProcessStatus sample{};
  sample.run_id = run_id_;
  sample.role = const_cast<char*>(role.c_str());
  sample.index = index;
  sample.state = wsn_msg_FAULTED;
  sample.tick = 0;
  sample.message = const_cast<char*>(why.c_str());
  key_.sign(sample);
  writer_.write(sample);
}

void StatusObserver::writeRejections() const { dds::writeRejections(run_dir_, "launcher", 0, rejections_); }

}  // namespace wsn::launcher

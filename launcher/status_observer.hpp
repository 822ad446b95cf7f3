// The launcher's own DDS observer of the status topic: the aggregator's progress, the faults the
// roles announce for the launcher to enact, the reasons of failures, and the loss of a process
// announced to the roles; only samples signed with the run's status key count.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/dds/entity.hpp"
#include "common/dds/role_runtime.hpp"
#include "common/dds/status_auth.hpp"
#include "common/edge_checks.hpp"
#include "launcher/cluster.hpp"

namespace wsn::launcher {

class StatusObserver {
 public:
  /// Joins with the configuration the run directory holds for the launcher's host, as the
  /// launcher's own identity (a secured run's in-process roles share its participant's domain,
  /// and so the identity with every role's rights).
  StatusObserver(const ClusterOptions& options, int participant_index);

  /// A role that reached a kill or pause of the scenario's faults, for the launcher to enact.
  struct Faulted {
    std::string role;
    std::uint32_t index = 0;
    std::int32_t tick = 0;
  };

  /// Waits up to `timeout` for status samples; returns the aggregator's latest tick and collects
  /// the roles that announced a fault and, by role name ("supernode 2"), the messages of FAILED
  /// samples, made printable. Only samples signed with the run's status key count; the others are
  /// counted in RUN_DIR/rejected (writeRejections). Even a signed FAILED sample is only the reason:
  /// the run fails when the named process does.
  void poll(std::chrono::milliseconds timeout, std::int32_t& aggregator_tick,
            std::map<std::string, std::string>& failed_messages, std::vector<Faulted>& faulted);

  /// Tells the roles that `role` `index` is gone outside the scenario's faults (FAULTED at tick 0,
  /// under the lost role's key): they go on without it (dds::LostProcesses).
  void announceLost(const std::string& role, std::uint32_t index, const std::string& why);

  /// Leaves the count of refused status samples in the run directory, for rejected.json.
  void writeRejections() const;

 private:
  dds::Domain domain_;
  dds::Participant participant_;
  dds::Topic<wsn_msg_ProcessStatus> status_topic_;
  dds::Reader<wsn_msg_ProcessStatus> reader_;
  dds::Writer<wsn_msg_ProcessStatus> writer_;
  dds::ReadCondition condition_;
  dds::WaitSet waitset_;
  dds::StatusKey key_;
  std::string run_dir_;
  common::RejectionLog rejections_;
  std::uint64_t run_id_;
};

}  // namespace wsn::launcher

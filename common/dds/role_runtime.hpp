// What every role process shares: the run's topics, process-status publishing, discovery
// and start barriers, and the per-tick inbox that implements self-clocking lockstep (a
// consumer handles tick t once it holds tick t from every producer; DESIGN.md principle 3).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <stop_token>
#include <string>
#include <vector>

#include "common/dds/entity.hpp"
#include "common/dds/status_auth.hpp"
#include "common/edge_checks.hpp"
#include "common/scenario_config.hpp"
#include "wsntrack.h"

namespace wsn::dds {

/// Topic names of a run (the run is isolated by its domain and discovery tag; run_id in the
/// data also rejects stale samples of a previous run).
namespace topic_names {
inline constexpr const char* kSensorBoundary = "wsn_sensor_boundary";
inline constexpr const char* kReportBatch = "wsn_report_batch";
inline constexpr const char* kDeliveryBatch = "wsn_delivery_batch";
inline constexpr const char* kHandoffBatch = "wsn_handoff_batch";
inline constexpr const char* kTrackBatch = "wsn_track_batch";
/// HandoffBatch samples the aggregator writes when the scenario's faults kill or pause a
/// supernode: its last tracks, addressed to the supernodes adopting its group (from_supernode:
/// the dead one; tick: the tick the adopters take over).
inline constexpr const char* kRehomeBatch = "wsn_rehome_batch";
inline constexpr const char* kGlobalTrackBatch = "wsn_global_track_batch";
inline constexpr const char* kTickMetrics = "wsn_tick_metrics";
inline constexpr const char* kTickDone = "wsn_tick_done";
inline constexpr const char* kProcessStatus = "wsn_process_status";
/// The partition of what one supernode alone reads (its deliveries): the network model writes
/// each supernode's batches into its partition, so they cross the wire to that supernode only
/// rather than to all of them (64 x 64 samples a tick at 64 supernodes).
inline std::string supernodePartition(std::uint32_t supernode) { return "supernode-" + std::to_string(supernode); }
/// The partition of the handoffs addressed to one supernode: its reader's; a supernode's writer
/// is in those of its neighbours, so a handoff batch reaches the bordering groups only.
inline std::string handoffPartition(std::uint32_t supernode) { return "handoffs-to-" + std::to_string(supernode); }
}  // namespace topic_names

/// The one binding of each IDL sample type to its generated descriptor: Topic<S>, Writer<S> and
/// Reader<S> take the descriptor from here, so a type cannot be paired with another's descriptor
/// or topic.
template <>
struct TopicType<wsn_msg_SensorBoundary> {
  static constexpr const dds_topic_descriptor_t& descriptor = wsn_msg_SensorBoundary_desc;
};
template <>
struct TopicType<wsn_msg_ReportBatch> {
  static constexpr const dds_topic_descriptor_t& descriptor = wsn_msg_ReportBatch_desc;
};
template <>
struct TopicType<wsn_msg_DeliveryBatch> {
  static constexpr const dds_topic_descriptor_t& descriptor = wsn_msg_DeliveryBatch_desc;
};
template <>
struct TopicType<wsn_msg_HandoffBatch> {
  static constexpr const dds_topic_descriptor_t& descriptor = wsn_msg_HandoffBatch_desc;
};
template <>
struct TopicType<wsn_msg_TrackBatch> {
  static constexpr const dds_topic_descriptor_t& descriptor = wsn_msg_TrackBatch_desc;
};
template <>
struct TopicType<wsn_msg_GlobalTrackBatch> {
  static constexpr const dds_topic_descriptor_t& descriptor = wsn_msg_GlobalTrackBatch_desc;
};
template <>
struct TopicType<wsn_msg_TickMetrics> {
  static constexpr const dds_topic_descriptor_t& descriptor = wsn_msg_TickMetrics_desc;
};
template <>
struct TopicType<wsn_msg_TickDone> {
  static constexpr const dds_topic_descriptor_t& descriptor = wsn_msg_TickDone_desc;
};
template <>
struct TopicType<wsn_msg_ProcessStatus> {
  static constexpr const dds_topic_descriptor_t& descriptor = wsn_msg_ProcessStatus_desc;
};

/// The processes of a cluster: one per tile, the network, one per supernode, the aggregator.
struct ClusterShape {
  std::int32_t tiles = 2;
  std::int32_t supernodes = 1;
  std::int32_t processes() const { return tiles + supernodes + 2; }
};

/// Identity and settings of one role instance.
struct RoleContext {
  std::string role;           ///< "node", "network", "supernode", "aggregator"
  std::uint32_t index = 0;    ///< tile or supernode index; 0 for singletons
  std::uint64_t run_id = 0;
  dds_domainid_t domain = 0;
  std::string run_dir;
  common::Scenario scenario;  ///< resolved
  ClusterShape shape;
  /// Give up when no sample arrived for this long while waiting (a producer died).
  std::chrono::milliseconds stall_timeout{60000};
  /// `wsntrack run --tick-interval`: the sources start at most one tick per interval, so that a
  /// run can be watched in real time; zero runs as fast as the pipeline goes. Timing only: no
  /// output depends on it.
  std::chrono::microseconds tick_interval{0};
  /// Requested from outside (the signal thread of a role process, the in-process launcher) to
  /// make the role stop: every wait of the role wakes at once through a guard condition.
  std::stop_token stop;
  /// True for a role process that `wsntrack run` started: the launcher enacts the scenario's
  /// kills and pauses of it with real signals (SIGKILL; SIGSTOP, then SIGCONT) once the role
  /// announces them. False for a role thread (--in-process), which ends or waits by itself.
  bool signalled_faults = false;
  /// The first tick this process takes part in: 1, or the tick of the scenario's `restart` that
  /// started it (a supernode that a kill took, back afresh).
  std::int32_t first_tick = 1;
  /// A participant shared by the role threads of one process (a group of supernodes, started with
  /// --count), or null: the role makes its own.
  const Participant* shared_participant = nullptr;
  /// The run's status key (status_auth.hpp): signs this role's status samples, and a status sample
  /// that is not signed with it is not acted on. None for a role started by hand.
  StatusKey status_key;

  /// The scenario's faults as every role applies them (common/faults.hpp).
  common::FaultPlan faultPlan() const { return {scenario.faults, shape.tiles, shape.supernodes}; }
};

/// "supernode 2 from 60": the name of one process incarnation, carried by its endpoints
/// (Participant::identity), so that peers can wait for a restarted process's readers.
std::string roleIdentity(const std::string& role, std::uint32_t index, std::int32_t first_tick);

/// Thrown when a role stops before finishing: stopped from outside or stalled.
class RoleAborted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Thrown by a role thread where the scenario's faults kill it (in-process runs): the launcher
/// counts it as the fault it is, not as a failure.
class ScheduledDeath : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// All topics of a run on one participant.
struct RunTopics {
  explicit RunTopics(const Participant& participant);
  Topic<wsn_msg_SensorBoundary> sensor_boundary;
  Topic<wsn_msg_ReportBatch> report_batch;
  Topic<wsn_msg_DeliveryBatch> delivery_batch;
  Topic<wsn_msg_HandoffBatch> handoff_batch;
  Topic<wsn_msg_TrackBatch> track_batch;
  Topic<wsn_msg_HandoffBatch> rehome_batch;
  Topic<wsn_msg_GlobalTrackBatch> global_track_batch;
  Topic<wsn_msg_TickMetrics> tick_metrics;
  Topic<wsn_msg_TickDone> tick_done;
  Topic<wsn_msg_ProcessStatus> process_status;
};

/// Publishes this role's lifecycle on the status topic.
class StatusPublisher {
 public:
  StatusPublisher(const Participant& participant, const RunTopics& topics, const RoleContext& context);
  void starting();
  void ready();
  void running(std::int32_t tick);
  void done(std::int32_t tick);
  void failed(const std::string& message);
  /// The role reached a kill or pause of the scenario's faults at `tick` (`what` says which).
  void faulted(std::int32_t tick, const std::string& what);

 private:
  void publish(int state, std::int32_t tick, const std::string& message);
  Writer<wsn_msg_ProcessStatus> writer_;
  StatusKey key_;
  std::uint64_t run_id_;
  std::string role_;
  std::uint32_t index_;
};

/// Batches held per tick and producer until a tick is complete.
template <typename BatchT>
class TickInbox {
 public:
  /// Files a batch; returns false for a duplicate or a tick already consumed (the role counts it in
  /// its common::RejectionLog, with the reason).
  bool put(std::int32_t tick, std::uint32_t producer, BatchT batch) {
    if (tick <= consumed_through_ || pending_[tick].count(producer) != 0) {
      return false;
    }
    pending_[tick].emplace(producer, std::move(batch));
    return true;
  }
  std::size_t count(std::int32_t tick) const {
    const auto it = pending_.find(tick);
    return it == pending_.end() ? 0 : it->second.size();
  }
  bool has(std::int32_t tick, std::uint32_t producer) const {
    const auto it = pending_.find(tick);
    return it != pending_.end() && it->second.count(producer) != 0;
  }
  /// Removes tick's batches, in producer order (canonical, whatever the arrival order).
  std::map<std::uint32_t, BatchT> take(std::int32_t tick) {
    auto node = pending_.extract(tick);
    consumed_through_ = std::max(consumed_through_, tick);
    return node.empty() ? std::map<std::uint32_t, BatchT>{} : std::move(node.mapped());
  }
  /// Whether a batch of `tick` from `producer` would be filed: the first of its producer and tick,
  /// and of a tick not yet taken or skipped.
  bool accepts(std::int32_t tick, std::uint32_t producer) const { return tick > consumed_through_ && !has(tick, producer); }
  /// The first tick from `from` on whose batch of `producer` has not arrived.
  std::int32_t firstMissing(std::uint32_t producer, std::int32_t from) const {
    std::int32_t t = std::max(from, consumed_through_ + 1);
    while (has(t, producer)) ++t;
    return t;
  }
  /// "node 0, node 3": the producers among `expected` whose batch of `tick` has not arrived, each
  /// named `role` and its index, for the message of a wait that stalled.
  std::string missing(std::int32_t tick, const std::vector<std::uint32_t>& expected, const std::string& role) const {
    std::string out;
    for (const auto producer : expected)
      if (!has(tick, producer)) out += (out.empty() ? "" : ", ") + role + " " + std::to_string(producer);
    return out.empty() ? "none" : out;
  }
  /// Forgets every tick up to `tick` unread (a role that was paused skips them); later batches of
  /// those ticks are rejected like consumed ones.
  void skipThrough(std::int32_t tick) {
    pending_.erase(pending_.begin(), pending_.upper_bound(tick));
    consumed_through_ = std::max(consumed_through_, tick);
  }

 private:
  std::map<std::int32_t, std::map<std::uint32_t, BatchT>> pending_;
  std::int32_t consumed_through_ = 0;
};

/// A guard condition triggered when `stop` is requested (at once if it already was): attached to a
/// waitset, it wakes the wait on a stop request instead of the wait having to poll for one.
class StopCondition {
 public:
  StopCondition(const Participant& participant, std::stop_token stop);
  dds_entity_t handle() const { return guard_.handle(); }

 private:
  // Runs on the requesting thread; std::stop_callback needs it noexcept.
  struct Trigger {
    dds_entity_t guard;
    void operator()() const noexcept;
  };
  GuardCondition guard_;
  // Declared after guard_, so destroyed first: its destructor waits for a trigger running on
  // another thread, and no trigger can reach a deleted guard.
  std::stop_callback<Trigger> callback_;
};

/// A role's event loop: a waitset over its readers; each arrival is drained into inboxes by
/// the callback registered with the reader.
class RoleLoop {
 public:
  RoleLoop(const Participant& participant, const RoleContext& context);
  /// Registers a reader and the function that takes its samples.
  void watch(const ReaderBase& reader, std::function<void()> drain);
  /// Stops watching a reader; a reader that dies before the loop must be unwatched first,
  /// since deleting it deletes its read condition too.
  void unwatch(const ReaderBase& reader);
  /// Blocks until done() holds, draining readers as samples arrive. Throws RoleAborted as soon
  /// as a stop is requested, or when nothing arrives for the stall timeout (describe() says
  /// what was still missing).
  void waitUntil(const std::function<bool()>& done, const std::function<std::string()>& describe);
  /// Blocks until `deadline`, draining readers as samples arrive. Throws RoleAborted as soon as
  /// a stop is requested; waiting for the clock is never a stall.
  void waitUntilTime(std::chrono::steady_clock::time_point deadline);

 private:
  const RoleContext& context_;
  WaitSet waitset_;
  StopCondition stop_;
  std::vector<ReadCondition> conditions_;
  std::vector<dds_entity_t> watched_readers_;  // parallel to conditions_
  std::vector<std::function<void()>> drains_;
};

/// The subdirectory of the run directory where each role leaves what it refused.
inline constexpr const char* kRejectionsDirectory = "rejected";

/// Writes `log` to RUN_DIR/rejected/ROLE-INDEX.json when it counted anything (the launcher gathers
/// the files into rejected.json at the end of the run).
void writeRejections(const RoleContext& context, const common::RejectionLog& log);
/// A role's record of refusals that reaches the run directory however the role ends: write() at
/// the end of a run (an error fails the role), or the destructor when the role fails first, so that
/// a failed run's rejected.json still counts what was refused before it failed.
class RejectionsRecord {
 public:
  explicit RejectionsRecord(const RoleContext& context) : context_(context) {}
  RejectionsRecord(const RejectionsRecord&) = delete;
  RejectionsRecord& operator=(const RejectionsRecord&) = delete;
  ~RejectionsRecord();
  common::RejectionLog& log() { return log_; }
  void write();

 private:
  const RoleContext& context_;
  common::RejectionLog log_;
  bool written_ = false;
};

/// As above, for a writer that is not a role (the launcher, which counts forged status samples).
void writeRejections(const std::string& run_dir, const std::string& role, std::uint32_t index,
                     const common::RejectionLog& log);

/// Blocks until every writer matched `expected` role readers (viewers do not count: see
/// Endpoint) and every reader matched `expected` writers, so that nothing published afterwards
/// can miss a consumer. Throws when that takes longer than the stall timeout (--stall-timeout): how
/// long a role waits for its peers, whether before the first tick or between two.
void waitForDiscovery(const Participant& participant, const std::vector<std::pair<const WriterBase*, int>>& writers,
                      const std::vector<std::pair<const ReaderBase*, int>>& readers, const RoleContext& context);

/// Before a writer writes what the supernodes live at a tick read: waits until it matched the
/// readers of every restarted supernode live then (a new process, which must not miss a sample of
/// that tick; its predecessor's readers may still be matched until their lease ends, so counts do
/// not tell). Passes at once without restarts, and for a restart once it has been seen matched.
class RestartedReaders {
 public:
  RestartedReaders(const Participant& participant, const RoleContext& context, const common::FaultPlan& plan)
      : participant_(participant), context_(context), plan_(plan) {}
  void waitFor(const WriterBase& writer, std::int32_t tick);
  /// The same for a writer that only supernode `reader` reads (its partition's).
  void waitFor(const WriterBase& writer, std::int32_t tick, std::uint32_t reader);
  /// The same for a writer that only the supernodes `readers` read (their partitions').
  void waitFor(const WriterBase& writer, std::int32_t tick, const std::vector<std::uint32_t>& readers);

 private:
  const Participant& participant_;
  const RoleContext& context_;
  const common::FaultPlan& plan_;
  void waitForAny(const WriterBase& writer, std::int32_t tick, const std::function<bool(std::uint32_t)>& reads);
  std::set<std::pair<dds_entity_t, std::string>> matched_;
};

/// Blocks until each writer matched the readers of the role processes named (roleIdentity) beside
/// it: a restarted process's start barrier, where the counts of waitForDiscovery would also count
/// the endpoints of dead processes that linger until their lease ends.
void waitForRoleReaders(const Participant& participant,
                        const std::vector<std::pair<const WriterBase*, std::vector<std::string>>>& writers,
                        const RoleContext& context);

/// Blocks until every process of the cluster reported READY (or later) on the status topic.
void waitForClusterReady(const Participant& participant, const RunTopics& topics, const RoleContext& context,
                         std::chrono::milliseconds timeout);

}  // namespace wsn::dds

namespace wsn::dds {

/// Follows the aggregator's TickDone ticks: the pipeline's end. Sources use it for
/// back-pressure (at most max_ticks_in_flight ticks ahead); every role waits for the last tick
/// before leaving so that nothing it wrote is still in flight when its writers are deleted. A
/// restarted process follows them from its first tick (RoleContext::first_tick).
class PipelineProgress {
 public:
  PipelineProgress(const Participant& participant, const RunTopics& topics, const RoleContext& context,
                   RoleLoop& loop);
  /// Highest tick t such that the aggregator finished every tick <= t.
  std::int32_t completedThrough() const { return completed_through_; }
  void waitForCompleted(std::int32_t tick);
  /// A source's wall-clock pacing (RoleContext::tick_interval), called before each tick: returns
  /// one interval after the previous tick's scheduled start, at once when the interval is zero. A
  /// late tick restarts the schedule rather than being made up by a burst.
  void paceTick();
  Reader<wsn_msg_TickDone>& reader() { return reader_; }
  PipelineProgress(const PipelineProgress&) = delete;
  PipelineProgress& operator=(const PipelineProgress&) = delete;
  ~PipelineProgress() { loop_.unwatch(reader_); }

 private:
  const RoleContext& context_;
  RoleLoop& loop_;
  Reader<wsn_msg_TickDone> reader_;
  std::set<std::int32_t> arrived_;
  std::int32_t completed_through_ = 0;
  std::optional<std::chrono::steady_clock::time_point> paced_at_;
};

/// Where the scenario's faults kill or pause this role at `fault.tick`: once the pipeline finished
/// that tick (so every consumer took what the role wrote before it: a consumer of a supernode
/// needs its handoffs of fault.tick - 1 to finish fault.tick), the role announces the fault on its
/// status, then
/// - kill: a process waits for the launcher's SIGKILL (and fails, naming the fault, if none
///   comes within the stall timeout); a thread throws ScheduledDeath;
/// - pause: it waits until the pipeline has finished the paused ticks (the launcher holds a
///   process stopped meanwhile) and returns; the caller resumes at fault.lastTick() + 1.
/// Consumers never wait for a faulted role's outputs of those ticks, so no output depends on
/// when the signals land.
void enactProcessFault(const common::FaultSpec& fault, const RoleContext& context, StatusPublisher& status,
                       PipelineProgress& progress, RoleLoop& loop);

/// The aggregator's last wait before its writers go: until every role the scenario's faults left
/// live at the last tick reported DONE (each does once it saw the last TickDone), or the
/// stall timeout passed. Counted in roles rather than in DDS acknowledgements, which a killed
/// process's reader would hold back until its lease expired. Made before the run, so that it
/// holds the DONE of a role that left before the wait began.
class LiveRolesDone {
 public:
  LiveRolesDone(const Participant& participant, const RunTopics& topics, const RoleContext& context);
  void wait();

 private:
  const RoleContext& context_;
  Reader<wsn_msg_ProcessStatus> reader_;
  ReadCondition condition_;
  WaitSet waitset_;
  StopCondition stop_;
};

/// Processes of the cluster lost outside the scenario's faults (a node tile or supernode killed by
/// hand): the launcher announces each on the status topic (FAULTED at tick 0, for the lost role's
/// key), and `on_lost` is called once per process from the role's loop, to decide from which tick
/// the role goes on without it (the first tick whose input from it the role does not hold).
class LostProcesses {
 public:
  using OnLost = std::function<void(common::FaultRole role, std::int32_t index)>;
  LostProcesses(const Participant& participant, const RunTopics& topics, const RoleContext& context, RoleLoop& loop,
                OnLost on_lost);
  LostProcesses(const LostProcesses&) = delete;
  LostProcesses& operator=(const LostProcesses&) = delete;
  ~LostProcesses() { loop_.unwatch(reader_); }

 private:
  RoleLoop& loop_;
  Reader<wsn_msg_ProcessStatus> reader_;
  std::set<std::pair<std::string, std::uint32_t>> seen_;
};

/// True for the status sample by which the launcher announces a process lost outside the scenario.
inline bool announcesLoss(const wsn_msg_ProcessStatus& s) { return s.state == wsn_msg_FAULTED && s.tick == 0; }

/// A status sample a role may act on: of this run, and signed with its status key (a program on the
/// domain without the key can write status samples too).
inline bool fromThisRun(const wsn_msg_ProcessStatus& s, const RoleContext& context) {
  return s.run_id == context.run_id && context.status_key.authentic(s);
}

/// Runs `body`, publishing READY-to-FAILED status around it: any exception is reported on the
/// status topic (so the launcher and peers learn why) and rethrown.
void runWithStatus(StatusPublisher& status, const std::function<void()>& body);

/// The frame of every role: joins the run's domain, creates its topics and status publisher,
/// reports STARTING, and runs `body` under runWithStatus.
void runRole(const RoleContext& context,
             const std::function<void(const Participant&, const RunTopics&, StatusPublisher&)>& body);

}  // namespace wsn::dds

#include "common/dds/role_runtime.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include "common/output.hpp"
#include "wsntrack.h"

namespace wsn::dds {
namespace {

using Clock = std::chrono::steady_clock;

// The waitset token of a StopCondition; the others are indices of RoleLoop's drains.
constexpr dds_attach_t kStopToken = -1;

// The start barrier re-checks the matched endpoints at least this often: matched-status changes
// wake it, but whether a matched reader is a role's (its user data) is read, not signalled. 200 ms
// made the default scenario's start-up 0.28 s (0.71 s with DDS Security); 20 ms makes it 0.20 s
// (0.49 s), and costs a few dozen wake-ups of a waiting process.
constexpr std::chrono::milliseconds kDiscoveryRecheck{20};

void throwIfStopped(const RoleContext& context) {
  if (context.stop.stop_requested()) throw RoleAborted(context.role + " stopped on request");
}

// The wait left until `deadline`, rounded up so that the wake-up is not before it.
std::chrono::milliseconds until(Clock::time_point deadline) {
  return std::max(std::chrono::milliseconds(0), std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now()));
}

}  // namespace

RunTopics::RunTopics(const Participant& participant)
    : sensor_boundary(participant, topic_names::kSensorBoundary),
      report_batch(participant, topic_names::kReportBatch),
      delivery_batch(participant, topic_names::kDeliveryBatch),
      handoff_batch(participant, topic_names::kHandoffBatch),
      track_batch(participant, topic_names::kTrackBatch),
      rehome_batch(participant, topic_names::kRehomeBatch),
      global_track_batch(participant, topic_names::kGlobalTrackBatch),
      tick_metrics(participant, topic_names::kTickMetrics),
      tick_done(participant, topic_names::kTickDone),
      process_status(participant, topic_names::kProcessStatus) {}

StatusPublisher::StatusPublisher(const Participant& participant, const RunTopics& topics, const RoleContext& context)
    : writer_(participant, topics.process_status, Qos::lastValueTransientLocal()),
      key_(context.status_key),
      run_id_(context.run_id),
      role_(context.role),
      index_(context.index) {}

void StatusPublisher::publish(int state, std::int32_t tick, const std::string& message) {
  wsn_msg_ProcessStatus sample{};
  sample.run_id = run_id_;
  sample.role = const_cast<char*>(role_.c_str());
  sample.index = index_;
  sample.state = static_cast<wsn_msg_ProcessState>(state);
  sample.tick = tick;
  sample.message = const_cast<char*>(message.c_str());
  key_.sign(sample);
  writer_.write(sample);
}

void StatusPublisher::starting() { publish(wsn_msg_STARTING, 0, ""); }
void StatusPublisher::ready() { publish(wsn_msg_READY, 0, ""); }
void StatusPublisher::running(std::int32_t tick) { publish(wsn_msg_RUNNING, tick, ""); }
void StatusPublisher::done(std::int32_t tick) { publish(wsn_msg_DONE, tick, ""); }
void StatusPublisher::failed(const std::string& message) { publish(wsn_msg_FAILED, 0, message); }
void StatusPublisher::faulted(std::int32_t tick, const std::string& what) { publish(wsn_msg_FAULTED, tick, what); }

StopCondition::StopCondition(const Participant& participant, std::stop_token stop)
    : guard_(participant), callback_(std::move(stop), Trigger{guard_.handle()}) {}

void StopCondition::Trigger::operator()() const noexcept {
  // Cannot fail while the guard exists, and callback_ is gone before it is deleted; the flag
  // is set anyway, so a failure would only delay the stop to the next wake-up.
  dds_set_guardcondition(guard, true);
}

RoleLoop::RoleLoop(const Participant& participant, const RoleContext& context)
    : context_(context), waitset_(participant), stop_(participant, context.stop) {
  waitset_.attach(stop_.handle(), kStopToken);
}

void RoleLoop::watch(const ReaderBase& reader, std::function<void()> drain) {
  conditions_.emplace_back(reader);
  watched_readers_.push_back(reader.handle());
  drains_.push_back(std::move(drain));
  waitset_.attach(conditions_.back().handle(), static_cast<dds_attach_t>(drains_.size() - 1));
}

void RoleLoop::unwatch(const ReaderBase& reader) {
  for (std::size_t i = 0; i < conditions_.size(); ++i) {
    if (watched_readers_[i] != reader.handle()) continue;
    // Deleting the condition also detaches it from the waitset; the slot stays (tokens are
    // indices) with a drain that does nothing.
    static_cast<Entity&>(conditions_[i]) = Entity{};
    watched_readers_[i] = 0;
    drains_[i] = [] {};
  }
}

void RoleLoop::waitUntil(const std::function<bool()>& done, const std::function<std::string()>& describe) {
  // The stall deadline is the waitset's timeout: only data or a stop request wakes it before.
  auto stall_deadline = Clock::now() + context_.stall_timeout;
  while (!done()) {
    throwIfStopped(context_);
    const auto triggered = waitset_.wait(until(stall_deadline));
    throwIfStopped(context_);
    if (triggered.empty()) {
      if (Clock::now() >= stall_deadline) {
        throw RoleAborted(context_.role + " " + std::to_string(context_.index) + " stalled: no data for " +
                          std::to_string(context_.stall_timeout.count() / 1000) + " s while waiting for " + describe());
      }
      continue;
    }
    stall_deadline = Clock::now() + context_.stall_timeout;
    for (dds_attach_t token : triggered)
      if (token != kStopToken) drains_[static_cast<std::size_t>(token)]();
  }
}

void RoleLoop::waitUntilTime(Clock::time_point deadline) {
  while (true) {
    throwIfStopped(context_);
    if (Clock::now() >= deadline) return;
    for (dds_attach_t token : waitset_.wait(until(deadline)))
      if (token != kStopToken) drains_[static_cast<std::size_t>(token)]();
  }
}

namespace {

/// Blocks until `missing()` says nothing is missing; matched-status changes of `endpoints` and a
/// stop request wake it, and it rechecks every kDiscoveryRecheck. Throws RoleAborted with what is
/// still missing at the stall timeout.
void waitUntilMatched(const Participant& participant, const std::vector<dds_entity_t>& endpoints,
                      const RoleContext& context, const std::function<std::string()>& missing) {
  WaitSet waitset(participant);
  const StopCondition stop(participant, context.stop);
  waitset.attach(stop.handle(), kStopToken);
  for (const auto endpoint : endpoints) waitset.attach(endpoint, 0);
  const auto deadline = Clock::now() + context.stall_timeout;
  while (!missing().empty()) {
    throwIfStopped(context);
    if (Clock::now() > deadline)
      throw RoleAborted(context.role + " " + std::to_string(context.index) + ": discovery incomplete:" + missing());
    waitset.wait(std::min(kDiscoveryRecheck, until(deadline)));
  }
}

}  // namespace

void waitForDiscovery(const Participant& participant, const std::vector<std::pair<const WriterBase*, int>>& writers,
                      const std::vector<std::pair<const ReaderBase*, int>>& readers, const RoleContext& context) {
  std::vector<dds_entity_t> endpoints;
  for (const auto& [writer, expected] : writers) endpoints.push_back(writer->handle());
  for (const auto& [reader, expected] : readers) endpoints.push_back(reader->handle());
  waitUntilMatched(participant, endpoints, context, [&]() {
    std::ostringstream out;
    for (const auto& [writer, expected] : writers) {
      // Readers of any kind first: a cheap status, and a role count can only be lower.
      const auto matched = writer->matchedReaders() < expected ? writer->matchedReaders() : writer->matchedRoleReaders();
      if (matched < expected) out << " writer " << writer->handle() << " has " << matched << "/" << expected << " readers;";
    }
    for (const auto& [reader, expected] : readers)
      if (reader->matchedWriters() < expected)
        out << " reader " << reader->handle() << " has " << reader->matchedWriters() << "/" << expected << " writers;";
    return out.str();
  });
}

std::string roleIdentity(const std::string& role, std::uint32_t index, std::int32_t first_tick) {
  return role + " " + std::to_string(index) + " from " + std::to_string(first_tick);
}

void waitForRoleReaders(const Participant& participant,
                        const std::vector<std::pair<const WriterBase*, std::vector<std::string>>>& writers,
                        const RoleContext& context) {
  std::vector<dds_entity_t> endpoints;
  for (const auto& [writer, identities] : writers) endpoints.push_back(writer->handle());
  waitUntilMatched(participant, endpoints, context, [&]() {
    std::string out;
    for (const auto& [writer, identities] : writers)
      for (const auto& identity : identities)
        if (!writer->matchesReaderOf(identity))
          out += " writer " + std::to_string(writer->handle()) + " has not matched the reader of " + identity + ";";
    return out;
  });
}

void RestartedReaders::waitFor(const WriterBase& writer, std::int32_t tick) {
  waitForAny(writer, tick, [](std::uint32_t) { return true; });
}

void RestartedReaders::waitFor(const WriterBase& writer, std::int32_t tick, std::uint32_t reader) {
  waitForAny(writer, tick, [reader](std::uint32_t j) { return j == reader; });
}

void RestartedReaders::waitFor(const WriterBase& writer, std::int32_t tick, const std::vector<std::uint32_t>& readers) {
  waitForAny(writer, tick, [&](std::uint32_t j) { return std::find(readers.begin(), readers.end(), j) != readers.end(); });
}

void RestartedReaders::waitForAny(const WriterBase& writer, std::int32_t tick,
                                  const std::function<bool(std::uint32_t)>& reads) {
  if (!plan_.hasRestarts()) return;  // every tick of every run without restarts
  std::vector<std::string> identities;
  for (const auto j : plan_.liveSupernodeIndices(tick)) {
    if (!reads(j)) continue;
    const std::int32_t first = plan_.incarnation(common::FaultRole::kSupernode, static_cast<std::int32_t>(j), tick);
    if (first <= 1) continue;
    auto identity = roleIdentity("supernode", j, first);
    if (matched_.count({writer.handle(), identity}) == 0) identities.push_back(std::move(identity));
  }
  if (identities.empty()) return;
  waitForRoleReaders(participant_, {{&writer, identities}}, context_);
  for (auto& identity : identities) matched_.emplace(writer.handle(), std::move(identity));
}

void waitForClusterReady(const Participant& participant, const RunTopics& topics, const RoleContext& context,
                         std::chrono::milliseconds timeout) {
  Reader<wsn_msg_ProcessStatus> reader(participant, topics.process_status, Qos::lastValueTransientLocal());
  ReadCondition condition(reader);
  WaitSet waitset(participant);
  waitset.attach(condition.handle(), 0);
  const StopCondition stop(participant, context.stop);
  waitset.attach(stop.handle(), kStopToken);
  std::set<std::pair<std::string, std::uint32_t>> ready;
  const auto expected = static_cast<std::size_t>(context.shape.processes());
  const auto deadline = Clock::now() + timeout;
  while (ready.size() < expected) {
    throwIfStopped(context);
    if (Clock::now() > deadline)
      throw RoleAborted(context.role + ": only " + std::to_string(ready.size()) + " of " + std::to_string(expected) +
                        " processes became ready");
    waitset.wait(until(deadline));  // status samples and a stop request wake it
    throwIfStopped(context);
    reader.take([&](const wsn_msg_ProcessStatus& s) {
      // A FAILED sample is only a claim: a role that really failed ends its process or thread, and
      // the launcher stops the others.
      if (s.state == wsn_msg_FAILED || !fromThisRun(s, context)) return;
      if (s.state != wsn_msg_STARTING) ready.emplace(s.role, s.index);
    });
  }
}

LiveRolesDone::LiveRolesDone(const Participant& participant, const RunTopics& topics, const RoleContext& context)
    : context_(context),
      reader_(participant, topics.process_status, Qos::lastValueTransientLocal()),
      condition_(reader_),
      waitset_(participant),
      stop_(participant, context.stop) {
  waitset_.attach(condition_.handle(), 0);
  waitset_.attach(stop_.handle(), kStopToken);
}

void LiveRolesDone::wait() {
  const auto& context = context_;
  const auto plan = context.faultPlan();
  const std::int32_t last = context.scenario.run.ticks;
  std::set<std::pair<std::string, std::uint32_t>> waiting{{"network", 0}};
  for (std::int32_t i = 0; i < context.shape.tiles; ++i)
    if (plan.tileLive(i, last)) waiting.emplace("node", static_cast<std::uint32_t>(i));
  for (std::int32_t j = 0; j < context.shape.supernodes; ++j)
    if (plan.supernodeLive(j, last)) waiting.emplace("supernode", static_cast<std::uint32_t>(j));
  const auto deadline = Clock::now() + context.stall_timeout;
  while (!waiting.empty() && Clock::now() < deadline && !context.stop.stop_requested()) {
    waitset_.wait(until(deadline));
    reader_.take([&](const wsn_msg_ProcessStatus& s) {
      if ((s.state == wsn_msg_DONE || announcesLoss(s)) && fromThisRun(s, context)) waiting.erase({s.role, s.index});
    });
  }
}

}  // namespace wsn::dds

namespace wsn::dds {

PipelineProgress::PipelineProgress(const Participant& participant, const RunTopics& topics,
                                   const RoleContext& context, RoleLoop& loop)
    : context_(context),
      loop_(loop),
      reader_(participant, topics.tick_done, Qos::reliableKeepAll()),
      completed_through_(std::max(context.first_tick - 1, 0)) {
  loop_.watch(reader_, [this] {
    reader_.take([this](const wsn_msg_TickDone& done) {
      if (done.run_id != context_.run_id || done.tick <= completed_through_) return;
      arrived_.insert(done.tick);
      while (!arrived_.empty() && *arrived_.begin() == completed_through_ + 1) {
        completed_through_ = *arrived_.begin();
        arrived_.erase(arrived_.begin());
      }
    });
  });
}

void PipelineProgress::waitForCompleted(std::int32_t tick) {
  loop_.waitUntil([&] { return completed_through_ >= tick; },
                  [&] { return "the aggregator's end of tick " + std::to_string(completed_through_ + 1); });
}

void PipelineProgress::paceTick() {
  const auto interval = context_.tick_interval;
  if (interval.count() <= 0) return;
  const auto now = Clock::now();
  if (paced_at_) loop_.waitUntilTime(*paced_at_ + interval);
  // On time: the schedule, not the wake-up, is the reference, so wake-up latency does not add up.
  paced_at_ = paced_at_ && now <= *paced_at_ + interval ? *paced_at_ + interval : Clock::now();
}

void enactProcessFault(const common::FaultSpec& fault, const RoleContext& context, StatusPublisher& status,
                       PipelineProgress& progress, RoleLoop& loop) {
  progress.waitForCompleted(std::min(fault.tick, context.scenario.run.ticks));
  status.faulted(fault.tick, fault.describe());
  if (fault.action == common::FaultAction::kPause) {
    progress.waitForCompleted(std::min(fault.lastTick(), context.scenario.run.ticks));
    return;
  }
  if (!context.signalled_faults) throw ScheduledDeath(fault.describe());
  loop.waitUntil([] { return false; }, [&] { return "the launcher's SIGKILL (" + fault.describe() + ")"; });
}

LostProcesses::LostProcesses(const Participant& participant, const RunTopics& topics, const RoleContext& context,
                             RoleLoop& loop, OnLost on_lost)
    : loop_(loop), reader_(participant, topics.process_status, Qos::lastValueTransientLocal()) {
  loop_.watch(reader_, [this, &context, on_lost = std::move(on_lost)] {
    reader_.take([&](const wsn_msg_ProcessStatus& s) {
      if (!announcesLoss(s) || !fromThisRun(s, context)) return;
      const std::string role = s.role;
      if ((role != "node" && role != "supernode") || !seen_.emplace(role, s.index).second) return;
      on_lost(role == "node" ? common::FaultRole::kNode : common::FaultRole::kSupernode, static_cast<std::int32_t>(s.index));
    });
  });
}

void runWithStatus(StatusPublisher& status, const std::function<void()>& body) {
  try {
    body();
  } catch (const ScheduledDeath&) {
    throw;  // announced as FAULTED already: not a failure
  } catch (const std::exception& error) {
    try {
      status.failed(error.what());
    } catch (...) {
      // Reporting is best effort: the original error is the one that matters.
    }
    throw;
  }
}

void runRole(const RoleContext& context,
             const std::function<void(const Participant&, const RunTopics&, StatusPublisher&)>& body) {
  const std::string identity = roleIdentity(context.role, context.index, context.first_tick);
  const Participant participant = context.shared_participant != nullptr ? Participant(*context.shared_participant, identity)
                                                                        : Participant(context.domain, identity);
  RunTopics topics(participant);
  StatusPublisher status(participant, topics, context);
  status.starting();
  runWithStatus(status, [&] { body(participant, topics, status); });
}

void writeRejections(const RoleContext& context, const common::RejectionLog& log) {
  writeRejections(context.run_dir, context.role, context.index, log);
}

void RejectionsRecord::write() {
  written_ = true;
  writeRejections(context_, log_);
}

RejectionsRecord::~RejectionsRecord() {
  if (written_) return;
  try {
    writeRejections(context_, log_);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s %u: could not record its refusals: %s\n", context_.role.c_str(), context_.index, error.what());
  }
}

void writeRejections(const std::string& run_dir, const std::string& role, std::uint32_t index,
                     const common::RejectionLog& log) {
  if (log.total() == 0) return;
  const std::string dir = run_dir + "/" + kRejectionsDirectory;
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw std::runtime_error(dir + ": cannot create (" + error.message() + ")");
  common::writeTextFile(dir + "/" + role + "-" + std::to_string(index) + ".json", log.json(role, index));
}

}  // namespace wsn::dds

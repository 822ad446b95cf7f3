// The role runtime on loopback participants: a stop request wakes a waiting role through its guard
// condition at once, the stall timeout is the wait's deadline, and a writer waits for the readers
// of a restarted process by the identity its endpoints carry.
#include <atomic>
#include <chrono>
#include <future>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>

#include <catch2/catch.hpp>

#include "common/dds/cyclone_config.hpp"
#include "common/dds/role_runtime.hpp"
#include "launcher/run_directory.hpp"

namespace wsn::dds {
namespace {

using Clock = std::chrono::steady_clock;
using Millis = std::chrono::duration<double, std::milli>;

/// A domain of its own with the project's loopback-only configuration (never Cyclone's default)
/// and one participant in it.
struct LoopbackParticipant {
  LoopbackParticipant() : LoopbackParticipant(launcher::newRunId()) {}
  explicit LoopbackParticipant(std::uint64_t run_id)
      : domain(static_cast<dds_domainid_t>(launcher::pickFreeDomain(run_id, 1)),
               cycloneConfigFor(cycloneConfigTemplate(run_id, 1), 0)),
        participant(domain.id()) {}
  Domain domain;
  Participant participant;
};

RoleContext contextFor(const Domain& domain, std::stop_token stop) {
  RoleContext context;
  context.role = "test";
  context.domain = domain.id();
  context.stall_timeout = std::chrono::minutes(10);
  context.stop = std::move(stop);
  return context;
}

/// Runs `wait` on a thread, requests the stop `delay` after the thread began waiting and returns
/// how long after the request the wait ended; the wait must end with RoleAborted, "stopped on request".
template <typename Wait>
Millis stopLatency(std::stop_source& stop, std::chrono::milliseconds delay, Wait wait) {
  std::promise<void> waiting;
  std::promise<Clock::time_point> ended;
  std::string message;
  std::thread waiter([&] {
    try {
      waiting.set_value();
      wait();
    } catch (const RoleAborted& error) {
      message = error.what();
    }
    ended.set_value(Clock::now());
  });
  waiting.get_future().wait();
  std::this_thread::sleep_for(delay);
  const auto requested = Clock::now();
  stop.request_stop();
  const auto end = ended.get_future().get();
  waiter.join();
  CHECK(message == "test stopped on request");
  return end - requested;
}

TEST_CASE("a stop request wakes a role waiting for data without waiting for a poll interval", "[dds]") {
  // A stop requested 20 ms into the wait: the former 200 ms poll noticed it about 180 ms later.
  // The guard condition wakes the wait at once (well under 1 ms here); the fastest of three
  // requests must take under 100 ms, a bound the poll never met and a loaded machine still does.
  Millis fastest{1e9};
  for (int attempt = 0; attempt < 3; ++attempt) {
    LoopbackParticipant dds;
    std::stop_source stop;
    const RoleContext context = contextFor(dds.domain, stop.get_token());
    RoleLoop loop(dds.participant, context);
    const auto latency = stopLatency(stop, std::chrono::milliseconds(20), [&] {
      loop.waitUntil([] { return false; }, [] { return std::string("nothing"); });
    });
    fastest = std::min(fastest, latency);
  }
  CHECK(fastest.count() < 100.0);
}

TEST_CASE("a stop request wakes a role waiting for the clock", "[dds]") {
  // waitUntilTime toward a deadline an hour away: only the stop can end it (see the case above
  // for the bound).
  LoopbackParticipant dds;
  std::stop_source stop;
  const RoleContext context = contextFor(dds.domain, stop.get_token());
  RoleLoop loop(dds.participant, context);
  const auto latency = stopLatency(stop, std::chrono::milliseconds(20),
                                   [&] { loop.waitUntilTime(Clock::now() + std::chrono::hours(1)); });
  CHECK(latency.count() < 1000.0);
}

TEST_CASE("a stop request wakes a role waiting for the cluster to become ready", "[dds]") {
  // No other process runs, so only the stop can end the wait before its 10-minute timeout.
  LoopbackParticipant dds;
  std::stop_source stop;
  const RoleContext context = contextFor(dds.domain, stop.get_token());
  const RunTopics topics(dds.participant);
  const auto latency = stopLatency(stop, std::chrono::milliseconds(20), [&] {
    waitForClusterReady(dds.participant, topics, context, std::chrono::minutes(10));
  });
  CHECK(latency.count() < 1000.0);
}

TEST_CASE("a stop requested before the wait ends it at once", "[dds]") {
  LoopbackParticipant dds;
  std::stop_source stop;
  stop.request_stop();
  const RoleContext context = contextFor(dds.domain, stop.get_token());
  RoleLoop loop(dds.participant, context);
  CHECK_THROWS_WITH(loop.waitUntil([] { return false; }, [] { return std::string("nothing"); }),
                    "test stopped on request");
}

TEST_CASE("a role without data gives up at the stall timeout and not before", "[dds]") {
  // Nothing is ever written, so the wait ends at the stall deadline: no sooner than the timeout,
  // and without a stop request.
  LoopbackParticipant dds;
  std::stop_source stop;
  RoleContext context = contextFor(dds.domain, stop.get_token());
  context.stall_timeout = std::chrono::milliseconds(300);
  RoleLoop loop(dds.participant, context);
  const auto started = Clock::now();
  CHECK_THROWS_WITH(loop.waitUntil([] { return false; }, [] { return std::string("tick 1"); }),
                    Catch::Contains("stalled") && Catch::Contains("while waiting for tick 1"));
  CHECK(Millis(Clock::now() - started).count() >= 300.0);
}

TEST_CASE("data arriving postpones the stall deadline", "[dds]") {
  // A sample every 100 ms for 600 ms, with a 300 ms stall timeout: the wait must survive until
  // done() holds (five samples), although it lasts longer than the timeout.
  LoopbackParticipant dds;
  std::stop_source stop;
  RoleContext context = contextFor(dds.domain, stop.get_token());
  context.stall_timeout = std::chrono::milliseconds(300);
  const RunTopics topics(dds.participant);
  Writer<wsn_msg_ProcessStatus> writer(dds.participant, topics.process_status, Qos::reliableKeepAll());
  Reader<wsn_msg_ProcessStatus> reader(dds.participant, topics.process_status, Qos::reliableKeepAll());
  RoleLoop loop(dds.participant, context);
  int received = 0;
  loop.watch(reader, [&] { reader.take([&](const wsn_msg_ProcessStatus&) { ++received; }); });
  std::thread producer([&] {
    for (int i = 1; i <= 6; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      wsn_msg_ProcessStatus sample{};
      sample.role = const_cast<char*>("producer");
      sample.message = const_cast<char*>("");
      sample.tick = i;
      writer.write(sample);
    }
  });
  CHECK_NOTHROW(loop.waitUntil([&] { return received >= 5; }, [] { return std::string("samples"); }));
  producer.join();
  loop.unwatch(reader);
}

TEST_CASE("a writer tells the readers of one role process from another's and a viewer's by identity", "[dds]") {
  const auto run_id = launcher::newRunId();
  LoopbackParticipant dds(run_id);  // no identity: a viewer
  const Participant network(dds.domain.id(), roleIdentity("network", 0, 1));
  const Participant restarted(dds.domain.id(), roleIdentity("supernode", 2, 60));
  const RunTopics network_topics(network);
  const RunTopics restarted_topics(restarted);
  const RunTopics viewer_topics(dds.participant);
  std::stop_source stop;
  RoleContext context = contextFor(dds.domain, stop.get_token());
  context.stall_timeout = std::chrono::milliseconds(400);
  Writer<wsn_msg_DeliveryBatch> writer(network, network_topics.delivery_batch, Qos::reliableKeepAll());
  const Reader<wsn_msg_DeliveryBatch> viewer(dds.participant, viewer_topics.delivery_batch,
                                             Qos::reliableKeepAll(Endpoint::kViewer));
  // Only a viewer: no reader of supernode 2's restarted process, and the wait says whose is missing.
  CHECK_THROWS_WITH(waitForRoleReaders(network, {{&writer, {"supernode 2 from 60"}}}, context),
                    Catch::Contains("discovery incomplete") &&
                        Catch::Contains("has not matched the reader of supernode 2 from 60"));
  // Its reader appears 200 ms into the wait: the wait ends then, well before the timeout.
  context.stall_timeout = std::chrono::seconds(30);
  std::optional<Reader<wsn_msg_DeliveryBatch>> reader;
  std::thread joiner([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    reader.emplace(restarted, restarted_topics.delivery_batch, Qos::reliableKeepAll());
  });
  const auto started = Clock::now();
  const common::FaultPlan plan({common::FaultSpec::kill(common::FaultRole::kSupernode, 2, 40),
                                common::FaultSpec::restart(common::FaultRole::kSupernode, 2, 60)},
                               1, 3);
  RestartedReaders restarted_readers(network, context, plan);
  restarted_readers.waitFor(writer, 59);  // before the restart: nobody to wait for
  CHECK(Millis(Clock::now() - started).count() < 150.0);
  restarted_readers.waitFor(writer, 60);
  const double waited = Millis(Clock::now() - started).count();
  joiner.join();
  CHECK(waited >= 200.0);
  CHECK(waited < 10000.0);
  CHECK(writer.matchesReaderOf("supernode 2 from 60"));
  // The same supernode's first process, or another supernode, is another identity.
  CHECK_FALSE(writer.matchesReaderOf("supernode 2 from 1"));
  CHECK_FALSE(writer.matchesReaderOf("supernode 1 from 60"));
  CHECK(reader->matchesWriterOf("network 0 from 1"));
  // Role readers count with their identity; the viewer does not.
  CHECK(writer.matchedRoleReaders() == 1);
  CHECK(writer.matchedReaders() == 2);
  // Later ticks of the same process pass at once.
  const auto again = Clock::now();
  restarted_readers.waitFor(writer, 61);
  CHECK(Millis(Clock::now() - again).count() < 150.0);
}

TEST_CASE("a delivery writer in one supernode's partition reaches that supernode's reader only", "[dds]") {
  const auto run_id = launcher::newRunId();
  LoopbackParticipant dds(run_id);
  const Participant network(dds.domain.id(), roleIdentity("network", 0, 1));
  const Participant supernode1(dds.domain.id(), roleIdentity("supernode", 1, 1));
  const Participant supernode2(dds.domain.id(), roleIdentity("supernode", 2, 1));
  const RunTopics network_topics(network), topics1(supernode1), topics2(supernode2);
  Writer<wsn_msg_DeliveryBatch> to1(network, network_topics.delivery_batch,
                                    Qos::reliableKeepAll().inPartition(topic_names::supernodePartition(1)));
  Reader<wsn_msg_DeliveryBatch> reader1(supernode1, topics1.delivery_batch,
                                        Qos::reliableKeepAll().inPartition(topic_names::supernodePartition(1)));
  Reader<wsn_msg_DeliveryBatch> reader2(supernode2, topics2.delivery_batch,
                                        Qos::reliableKeepAll().inPartition(topic_names::supernodePartition(2)));
  std::stop_source stop;
  const RoleContext context = contextFor(dds.domain, stop.get_token());
  waitForRoleReaders(network, {{&to1, {"supernode 1 from 1"}}}, context);
  wsn_msg_DeliveryBatch sample{};
  sample.run_id = run_id;
  sample.supernode = 1;
  sample.tick = 7;
  to1.write(sample);
  std::size_t received = 0;
  const auto deadline = Clock::now() + std::chrono::seconds(10);
  while (received == 0 && Clock::now() < deadline) {
    received += reader1.take([&](const wsn_msg_DeliveryBatch& batch) { CHECK(batch.tick == 7); });
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  CHECK(received == 1);
  // Supernode 2's reader in its own partition never matched the writer, and got nothing.
  CHECK(to1.matchedReaders() == 1);
  CHECK_FALSE(to1.matchesReaderOf("supernode 2 from 1"));
  CHECK(reader2.matchedWriters() == 0);
  CHECK(reader2.take([](const wsn_msg_DeliveryBatch&) {}) == 0);
}

}  // namespace
}  // namespace wsn::dds

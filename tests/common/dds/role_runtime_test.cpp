// The role runtime's stop and stall handling on one loopback participant: a stop request wakes a
// waiting role through its guard condition at once, and the stall timeout is the wait's deadline.
#include <atomic>
#include <chrono>
#include <future>
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

}  // namespace
}  // namespace wsn::dds

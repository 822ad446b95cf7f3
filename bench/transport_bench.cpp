// The DDS path of wsntrack against its limits (the scale-out issue, item 4), with the project's own
// sample type, QoS, wrappers and loopback Cyclone configuration, so that it can be set beside
// `ddsperf` on the same configuration (bench/transport.py, docs/PERFORMANCE.md):
//
//   throughput  one process publishes ReportBatch samples of a fixed serialized size as fast as the
//               reliable writer lets it, a forked process takes (and decodes) them; prints samples/s
//               and MB/s, the median of the subscriber's whole one-second intervals. --sample
//               boundary does the same with the flat SensorBoundary, to compare.
//   barrier     one of N processes of a plain publish/subscribe barrier: each writes "done tick t"
//               (an empty ReportBatch) on one topic, waits until it holds tick t of all N, goes on to
//               t + 1; prints ticks/s after the warm-up ticks.
//   size        the serialized size of a batch of --items items, or the batch nearest --bytes.
//   config      the Cyclone XML of process --index of --processes (so that ddsperf runs on the very
//               configuration of a run: CYCLONEDDS_URI=file://...).
//   domains     the domain ids whose ports a cluster of --processes finds free now, one a line.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "common/dds/codec.hpp"
#include "common/dds/packing.hpp"
#include "common/dds/cyclone_config.hpp"
#include "launcher/run_directory.hpp"
#include "common/dds/entity.hpp"
#include "common/dds/role_runtime.hpp"
#include "dds/ddsi/ddsi_cdrstream.h"

namespace wsn::bench {
namespace {

using Clock = std::chrono::steady_clock;
using dds::Qos;
using dds::Reader;
using dds::Topic;
using dds::Writer;

/// The barrier's topic: the report batch's type under a name of its own, so that a barrier never
/// matches a run's report readers even if both shared a domain.
constexpr const char* kBarrierTopic = "wsn_bench_barrier";
/// Tick of the sample that ends a throughput run.
constexpr std::int32_t kEndTick = -1;

/// Cyclone's participant for process `index` of `participants`, on the project's configuration.
struct Node {
  Node(int domain_id, std::uint64_t run_id, int participants, int index)
      : domain(domain_id, dds::cycloneConfigFor(dds::cycloneConfigTemplate(run_id, participants), index)),
        participant(domain_id) {}
  dds::Domain domain;
  dds::Participant participant;
};

/// The throughput's sample: the report batch of a node tile, N fused reports of Oh et al. eq. 6
/// (position, the engine's noise), packed as the roles pack them (common/dds/packing.hpp).
struct ReportPayload {
  using Sample = wsn_msg_ReportBatch;
  static constexpr const char* kTopic = dds::topic_names::kReportBatch;
  std::vector<common::Report> items;
  explicit ReportPayload(int n) {
    for (int i = 0; i < n; ++i)
      items.push_back({1, static_cast<common::SensorId>(1000 + i), 10.0 + i, 20.0 - i, i % 3 == 0 ? common::kFalseAlarm : i});
  }
  /// Encodes the items into `sample`; the result owns what the sample points at.
  auto fill(Sample& sample) const {
    auto packed = dds::packReports(items);
    sample.reports = packed.view();
    return packed;
  }
  static void clear(Sample& sample) { sample.reports = {}; }
  static std::size_t decode(const Sample& sample) { return dds::unpackReports(sample.reports, sample.tick).size(); }
};

/// A flat counterpart for comparison: a tile's boundary readings, plain {sensor, z} items, so that
/// the cost of the packed reports shows beside that of a plain IDL sequence.
struct BoundaryPayload {
  using Sample = wsn_msg_SensorBoundary;
  static constexpr const char* kTopic = dds::topic_names::kSensorBoundary;
  std::vector<common::SensorReading> items;
  explicit BoundaryPayload(int n) {
    for (int i = 0; i < n; ++i) items.push_back({static_cast<common::SensorId>(1000 + i), 2.5 + i});
  }
  auto fill(Sample& sample) const {
    auto encoded = dds::encode(items);
    sample.readings = dds::sequenceView<dds_sequence_wsn_msg_SensorReading>(encoded);
    return encoded;
  }
  static void clear(Sample& sample) { sample.readings = {}; }
  static std::size_t decode(const Sample& sample) { return dds::decode(sample.readings).size(); }
};

/// Bytes of a batch of n items' CDR serialization as the writer makes it (the type's minimum XCDR
/// version, without the 4-byte encapsulation header), the size ddsperf's "size" counts.
template <typename Payload>
std::size_t batchBytes(int n) {
  typename Payload::Sample sample{};
  const auto storage = Payload(n).fill(sample);
  const std::uint32_t* ops = dds::TopicType<typename Payload::Sample>::descriptor.m_ops;
  dds_ostream_t os;
  dds_ostream_init(&os, 0, dds_stream_minimum_xcdr_version(ops));
  dds_stream_write(&os, reinterpret_cast<const char*>(&sample), ops);
  const std::size_t bytes = os.m_index;
  dds_ostream_fini(&os);
  return bytes;
}

/// The number of items whose batch comes nearest `bytes` serialized.
template <typename Payload>
int itemsForBytes(std::size_t bytes) {
  const auto distance = [&](int n) {
    const auto size = batchBytes<Payload>(n);
    return std::max(size, bytes) - std::min(size, bytes);
  };
  int best = 0;
  for (int n = 1; n < 100000 && batchBytes<Payload>(n - 1) <= bytes; ++n)
    if (distance(n) < distance(best)) best = n;
  return best;
}

/// The domain ids in 1 .. 100 (ports below Linux's ephemeral range) whose ports for every index
/// the configuration of `participants` processes lets Cyclone probe are free right now.
std::vector<int> freeDomains(int participants) {
  std::vector<int> domains;
  for (int domain = 1; domain <= 100; ++domain) {
    bool free = true;
    for (int index = 0; index <= participants + dds::kViewerSlots + 1 && free; ++index)
      free = dds::cyclonePortsFree(domain, index);
    if (free) domains.push_back(domain);
  }
  return domains;
}

/// Polls `ready` (discovery only: the measured loops never poll) until it holds or `timeout` passes.
template <typename F>
void waitFor(F ready, std::chrono::milliseconds timeout, const std::string& what) {
  const auto deadline = Clock::now() + timeout;
  while (!ready()) {
    if (Clock::now() > deadline) throw std::runtime_error("timed out waiting for " + what);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

struct ThroughputOptions {
  int items = 16;
  double seconds = 5.0;
  int domain = 0;
  std::uint64_t run_id = 0;
  bool decode = true;
  bool batching = false;
  std::chrono::milliseconds timeout{30000};
};

/// The subscriber: counts each whole second's samples from the first sample on, until the end
/// marker; prints the median of those counts. Decodes each batch as the network model does.
template <typename Payload>
int subscribe(const ThroughputOptions& options, std::size_t bytes) {
  using Sample = typename Payload::Sample;
  Node node(options.domain, options.run_id, 2, 1);
  Topic<Sample> topic(node.participant, Payload::kTopic);
  Reader<Sample> reader(node.participant, topic, Qos::reliableKeepAll());
  dds::ReadCondition condition(reader);
  dds::WaitSet waitset(node.participant);
  waitset.attach(condition.handle(), 0);

  std::vector<std::uint64_t> per_second;
  std::uint64_t total = 0;
  std::size_t decoded_items = 0;
  std::optional<Clock::time_point> first;
  bool ended = false;
  while (!ended) {
    if (waitset.wait(options.timeout).empty())
      throw std::runtime_error("subscriber: no sample for " + std::to_string(options.timeout.count()) + " ms");
    reader.take([&](const Sample& batch) {
      if (batch.run_id != options.run_id) return;
      if (batch.tick == kEndTick) {
        ended = true;
        return;
      }
      const auto now = Clock::now();
      if (!first) first = now;
      const auto second = static_cast<std::size_t>(std::chrono::duration<double>(now - *first).count());
      if (per_second.size() <= second) per_second.resize(second + 1, 0);
      ++per_second[second];
      ++total;
      if (options.decode) decoded_items += Payload::decode(batch);
    });
  }
  if (per_second.size() < 3) throw std::runtime_error("subscriber: under 3 s of samples; give --seconds 3 or more");
  // The first second holds the writer's start, the last one its end: only whole steady seconds count.
  std::vector<std::uint64_t> steady(per_second.begin() + 1, per_second.end() - 1);
  std::sort(steady.begin(), steady.end());
  const double median = steady.size() % 2 == 1 ? static_cast<double>(steady[steady.size() / 2])
                                                : 0.5 * static_cast<double>(steady[steady.size() / 2 - 1] + steady[steady.size() / 2]);
  std::printf("samples %llu items_decoded %zu seconds %zu\n", static_cast<unsigned long long>(total), decoded_items,
              steady.size());
  std::printf("samples/s %.0f MB/s %.2f size %zu items %d\n", median, median * static_cast<double>(bytes) / 1e6, bytes,
              options.items);
  std::fflush(stdout);
  return 0;
}

/// The publisher: a node tile's writer, one freshly encoded batch per write, as fast as the
/// reliable KEEP_ALL writer accepts them (it blocks while its history is full).
template <typename Payload>
void publish(const ThroughputOptions& options) {
  using Sample = typename Payload::Sample;
  Node node(options.domain, options.run_id, 2, 0);
  // Before the writer exists: a writer takes the setting when it is made. ddsperf's publisher has
  // Cyclone pack samples into datagrams until a flush; the roles' writers do not (one batch per
  // tick, latency first). --batching does as ddsperf, to tell the two apart.
  if (options.batching) dds_write_set_batch(true);
  Topic<Sample> topic(node.participant, Payload::kTopic);
  Writer<Sample> writer(node.participant, topic, Qos::reliableKeepAll());
  waitFor([&] { return writer.matchedRoleReaders() >= 1; }, options.timeout, "the subscriber");
  const Payload payload(options.items);
  const auto stop_at = Clock::now() + std::chrono::duration<double>(options.seconds);
  Sample sample{};
  sample.run_id = options.run_id;
  for (std::int32_t t = 1; Clock::now() < stop_at; ++t) {
    sample.tick = t;
    const auto storage = payload.fill(sample);
    writer.write(sample);
  }
  sample.tick = kEndTick;
  Payload::clear(sample);
  writer.write(sample);
  dds_write_flush(writer.handle());
  writer.waitForAcknowledgements(options.timeout);
}

/// Forks the subscriber (before either side touches Cyclone), publishes, and returns the
/// subscriber's exit status.
template <typename Payload>
int throughput(ThroughputOptions options) {
  if (options.run_id == 0) options.run_id = static_cast<std::uint64_t>(::getpid()) << 16 | 0x7b;
  // As `wsntrack run` picks and reserves its own (the lock is held until this process ends).
  if (options.domain == 0) options.domain = launcher::pickFreeDomain(options.run_id, 2);
  const std::size_t bytes = batchBytes<Payload>(options.items);
  std::fflush(stdout);
  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("fork failed");
  if (child == 0) {
    int status = 1;
    try {
      status = subscribe<Payload>(options, bytes);
    } catch (const std::exception& e) {
      std::cerr << "wsn_transport_bench subscriber: " << e.what() << "\n";
    }
    std::fflush(stdout);
    ::_exit(status);
  }
  try {
    publish<Payload>(options);
  } catch (...) {
    ::kill(child, SIGTERM);  // its own child, by pid
    ::waitpid(child, nullptr, 0);
    throw;
  }
  // The subscriber ends by itself once it took the end marker; a hung one is killed, by its pid.
  int status = 0;
  const auto deadline = Clock::now() + options.timeout;
  while (::waitpid(child, &status, WNOHANG) == 0) {
    if (Clock::now() > deadline) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      throw std::runtime_error("the subscriber did not end within the timeout; killed");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

struct BarrierOptions {
  int processes = 2;
  int index = 0;
  int ticks = 200;
  int warmup = 20;
  int domain = 0;
  std::uint64_t run_id = 1;
  std::chrono::milliseconds timeout{60000};
};

/// One process of the plain barrier: write tick t, wait for all N of t, next.
int barrier(const BarrierOptions& options) {
  // Participant indices 1 .. N as the launcher gives its roles; 0 stays the (absent) launcher's.
  Node node(options.domain, options.run_id, options.processes + 1, options.index + 1);
  Topic<wsn_msg_ReportBatch> topic(node.participant, kBarrierTopic);
  Writer<wsn_msg_ReportBatch> writer(node.participant, topic, Qos::reliableKeepAll());
  Reader<wsn_msg_ReportBatch> reader(node.participant, topic, Qos::reliableKeepAll());
  dds::ReadCondition condition(reader);
  dds::WaitSet waitset(node.participant);
  waitset.attach(condition.handle(), 0);
  const auto n = options.processes;
  // Every process's writer and reader, its own included, so that tick 1 reaches everyone.
  waitFor([&] { return writer.matchedRoleReaders() >= n && reader.matchedWriters() >= n; }, options.timeout,
          "discovery of " + std::to_string(n) + " processes");

  std::map<std::int32_t, int> arrived;
  wsn_msg_ReportBatch sample{};
  sample.run_id = options.run_id;
  sample.tile = static_cast<std::uint32_t>(options.index);
  auto started = Clock::now();
  const int last = options.warmup + options.ticks;
  for (std::int32_t t = 1; t <= last; ++t) {
    sample.tick = t;
    writer.write(sample);
    while (arrived[t] < n) {
      if (waitset.wait(options.timeout).empty())
        throw std::runtime_error("tick " + std::to_string(t) + ": " + std::to_string(arrived[t]) + " of " +
                                 std::to_string(n) + " after " + std::to_string(options.timeout.count()) + " ms");
      reader.take([&](const wsn_msg_ReportBatch& batch) {
        if (batch.run_id == options.run_id) ++arrived[batch.tick];
      });
    }
    arrived.erase(t);
    if (t == options.warmup) started = Clock::now();
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
  // The others may still need this process's last sample: it leaves once they acknowledged it.
  writer.waitForAcknowledgements(options.timeout);
  std::printf("barrier processes %d index %d ticks %d seconds %.4f ticks/s %.1f\n", n, options.index, options.ticks,
              seconds, options.ticks / seconds);
  return 0;
}

namespace po = boost::program_options;

int run(int argc, char** argv) {
  std::string mode;
  std::string sample;
  ThroughputOptions tp;
  BarrierOptions bp;
  std::size_t bytes = 0;
  int timeout_s = 60;
  po::options_description visible(
      "wsn_transport_bench MODE [options]: the DDS path of wsntrack (ReportBatch, reliable KEEP_ALL,\n"
      "the run's loopback Cyclone configuration). MODE: throughput | barrier | size | config | domains");
  visible.add_options()("help,h", "this text")(
      "bytes", po::value(&bytes), "throughput/size: the batch nearest this many serialized bytes (overrides --reports)")(
      "items", po::value(&tp.items)->default_value(16), "throughput/size: reports (or readings) per batch")(
      "sample", po::value(&sample)->default_value("report"),
      "throughput/size: report (ReportBatch, a tile's reports) or boundary (SensorBoundary: flat readings, to compare)")(
      "seconds", po::value(&tp.seconds)->default_value(5.0), "throughput: how long to publish (at least 3)")(
      "raw", "throughput: count samples without decoding them (as ddsperf does)")(
      "batching", "throughput: writer batching, as ddsperf's publisher has (the roles do not)")(
      "processes", po::value(&bp.processes)->default_value(2), "barrier/config/domains: N, the processes")(
      "index", po::value(&bp.index)->default_value(0), "barrier: this process, 0 .. N - 1; config: its participant index")(
      "ticks", po::value(&bp.ticks)->default_value(200), "barrier: ticks measured")(
      "warmup", po::value(&bp.warmup)->default_value(20), "barrier: ticks before the measured ones")(
      "domain", po::value(&tp.domain)->default_value(0), "DDS domain; 0: throughput picks a free one, barrier needs one")(
      "run-id", po::value<std::uint64_t>(), "discovery tag and the run_id of the samples (barrier: the same in all N)")(
      "timeout", po::value(&timeout_s)->default_value(60), "seconds any one wait may take before giving up");
  po::options_description all;
  all.add(visible).add_options()("mode", po::value(&mode));
  po::positional_options_description positional;
  positional.add("mode", 1);
  po::variables_map vm;
  po::store(po::command_line_parser(argc, argv).options(all).positional(positional).run(), vm);
  po::notify(vm);
  if (vm.count("help") || mode.empty()) {
    std::cout << visible << "\n";
    return mode.empty() && !vm.count("help") ? 2 : 0;
  }
  if (sample != "report" && sample != "boundary") throw std::invalid_argument("--sample must be report or boundary");
  const bool reports = sample == "report";
  if (bytes > 0) tp.items = reports ? itemsForBytes<ReportPayload>(bytes) : itemsForBytes<BoundaryPayload>(bytes);
  tp.decode = vm.count("raw") == 0;
  tp.batching = vm.count("batching") != 0;
  tp.timeout = bp.timeout = std::chrono::milliseconds(1000 * timeout_s);
  bp.domain = tp.domain;
  if (vm.count("run-id")) tp.run_id = bp.run_id = vm["run-id"].as<std::uint64_t>();

  if (mode == "domains") {
    for (const int domain : freeDomains(bp.processes)) std::cout << domain << "\n";
    return 0;
  }
  if (mode == "config") {
    std::cout << dds::cycloneConfigFor(dds::cycloneConfigTemplate(bp.run_id, bp.processes), bp.index);
    return 0;
  }
  if (mode == "size") {
    std::printf("items %d size %zu\n", tp.items, reports ? batchBytes<ReportPayload>(tp.items) : batchBytes<BoundaryPayload>(tp.items));
    return 0;
  }
  if (mode == "throughput") {
    if (tp.seconds < 3) throw std::invalid_argument("--seconds must be at least 3 (the first and last seconds do not count)");
    return reports ? throughput<ReportPayload>(tp) : throughput<BoundaryPayload>(tp);
  }
  if (mode == "barrier") {
    if (bp.domain <= 0 || bp.domain > dds::kMaxDomainId) throw std::invalid_argument("barrier needs --domain in [1, 230]");
    if (bp.processes < 1 || bp.index < 0 || bp.index >= bp.processes) throw std::invalid_argument("--index must be in [0, N)");
    return barrier(bp);
  }
  std::cerr << "wsn_transport_bench: unknown mode '" << mode << "' (throughput, barrier, size, config or domains)\n";
  return 2;
}

}  // namespace
}  // namespace wsn::bench

int main(int argc, char** argv) {
  try {
    return wsn::bench::run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "wsn_transport_bench: " << e.what() << "\n";
    return 1;
  }
}

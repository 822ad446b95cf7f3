#include "common/dds/process_main.hpp"
#include "common/dds/security.hpp"

#include <pthread.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <boost/program_options.hpp>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stop_token>
#include <thread>

#include "common/dds/cyclone_config.hpp"

namespace wsn::dds {
namespace {

/// Turns SIGINT and SIGTERM into a stop request of the role. A signal handler must not make the
/// request itself: std::stop_source::request_stop takes a lock, and so does the guard condition it
/// triggers (dds_set_guardcondition locks the guard's entity and observer mutexes; Cyclone does not
/// document it as async-signal-safe), so a handler interrupting a thread that holds one would
/// deadlock. Instead the signals are blocked in every thread (from the constructor on, before
/// Cyclone starts its threads, which inherit the mask) and a thread of its own takes them with
/// sigwait, where any call is allowed. (A self-pipe would still need a thread to read it, since a
/// waitset cannot wait on a file descriptor.)
class StopSignals {
 public:
  StopSignals(std::stop_source source, std::string role_name) : role_name_(std::move(role_name)) {
    sigemptyset(&signals_);
    sigaddset(&signals_, SIGINT);
    sigaddset(&signals_, SIGTERM);
    if (const int rc = pthread_sigmask(SIG_BLOCK, &signals_, nullptr); rc != 0)
      throw std::runtime_error(std::string("pthread_sigmask: ") + std::strerror(rc));
    thread_ = std::thread([this, source]() mutable {
      int signal_number = 0;
      while (sigwait(&signals_, &signal_number) != 0) {
      }
      if (closing_.load()) return;
      source.request_stop();
      awaitEnd(signal_number);
    });
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  /// Wakes the thread with a signal of its own and joins it. The signals stay blocked: a stop
  /// that arrives while the process leaves is ignored, as a stop after the role's end always was.
  ~StopSignals() {
    closing_.store(true);
    pthread_kill(thread_.native_handle(), SIGTERM);
    thread_.join();
  }

  /// How long a role may take to end after a stop request before the process ends without it.
  static constexpr int kStopGraceMs = 2000;

 private:
  /// A role in its loop ends well within the grace; one still in set-up (a Topology or Truth of
  /// 10^7 items being built) never looks at the request, so the process ends here, with the
  /// status a death by the signal would give (the launcher's SIGKILL would follow a second later).
  /// A second signal ends it at once.
  void awaitEnd(int signal_number) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kStopGraceMs);
    int again = -1;
    while (again < 0 && std::chrono::steady_clock::now() < deadline) {
      const auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(deadline - std::chrono::steady_clock::now());
      const timespec wait{static_cast<time_t>(left.count() / 1000000000), static_cast<long>(left.count() % 1000000000)};
      again = sigtimedwait(&signals_, nullptr, &wait);  // -1: EAGAIN at the deadline, or EINTR
    }
    if (closing_.load()) return;
    std::fprintf(stderr, "%s: %s %s; ending the process\n", role_name_.c_str(),
                 signal_number == SIGINT ? "SIGINT" : "SIGTERM",
                 again > 0 ? "received twice" : "not honoured within 2 s (still in set-up?)");
    std::fflush(stderr);
    std::_Exit(128 + signal_number);
  }

  std::string role_name_;
  sigset_t signals_;
  std::atomic<bool> closing_{false};
  std::thread thread_;
};

/// Ends the process as SIGTERM would (a stop request) once its standard input reaches its end: a
/// role started on another host through ssh keeps the connection as its lifeline, so that it ends
/// when the launcher, or the launcher's end of the connection, does. The thread is left to the
/// process's end: a blocking read cannot be interrupted portably.
void endWithStandardInput() {
  std::thread([] {
    char buffer[256];
    while (true) {
      const ssize_t n = ::read(0, buffer, sizeof buffer);
      if (n == 0 || (n < 0 && errno != EINTR)) break;
    }
    std::fprintf(stderr, "standard input (the launcher's lifeline) closed: stopping\n");
    std::fflush(stderr);
    ::kill(::getpid(), SIGTERM);  // to the process: the StopSignals thread takes it
  }).detach();
}

/// What a process the launcher started reads from its standard input: the run's status key first,
/// then, for a process on another host, nothing but its end (its lifeline).
void readStandardInput(RoleContext& context, bool status_key_on_stdin, bool stdin_lifeline) {
  if (status_key_on_stdin) context.status_key = StatusKey::readLine(0);
  if (stdin_lifeline) endWithStandardInput();
}

/// A group (--count) takes only indices the scenario has, and none whose process the scenario's
/// faults kill or pause: those are enacted on the whole process.
void checkGroup(const RoleContext& context, int count, const std::string& role) {
  const auto last = static_cast<long long>(context.index) + count - 1;
  const long long available = role == "supernode" ? context.shape.supernodes : context.shape.tiles;
  if (last >= available)
    throw std::invalid_argument("--index " + std::to_string(context.index) + " --count " + std::to_string(count) +
                                " runs " + role + " " + std::to_string(last) + ", but the scenario has " +
                                std::to_string(available));
  for (const auto& fault : context.scenario.faults) {
    const auto our_role = role == "supernode" ? common::FaultRole::kSupernode : common::FaultRole::kNode;
    if (fault.stopsProcess() && fault.role == our_role && fault.index >= static_cast<std::int32_t>(context.index) &&
        fault.index <= last)
      throw std::invalid_argument("--index " + std::to_string(context.index) + " --count " + std::to_string(count) +
                                  " groups " + role + " " + std::to_string(fault.index) +
                                  ", which the scenario's faults stop (" + fault.describe() +
                                  "): it needs a process of its own");
  }
}

/// Runs roles index .. index + count - 1 as threads on one shared participant. The first failure
/// stops the others and is the process's; the process fails if any role does.
void runGroup(const RoleContext& context, int count, std::stop_source& stop_source, const std::string& role,
              const RoleRunner& runner) {
  const Participant shared(context.domain);
  std::vector<std::string> errors(static_cast<std::size_t>(count));
  {
    std::vector<std::jthread> threads;
    for (int k = 0; k < count; ++k)
      threads.emplace_back([&, k] {
        RoleContext member = context;
        member.index = context.index + static_cast<std::uint32_t>(k);
        member.shared_participant = &shared;
        try {
          runner(member);
        } catch (const std::exception& error) {
          errors[static_cast<std::size_t>(k)] = role + " " + std::to_string(member.index) + ": " + error.what();
          stop_source.request_stop();
        }
      });
  }
  for (const auto& error : errors)
    if (!error.empty()) throw std::runtime_error(error);
}

}  // namespace

std::string readConfigTemplate(const std::string& run_dir) { return readConfigFile(run_dir + "/cyclonedds.xml"); }

std::string readConfigFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read the run's Cyclone DDS configuration");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

int runRoleProcess(int argc, char** argv, const std::string& role, const std::string& summary, bool indexed,
                   ScenarioLoader load_scenario, const RoleRunner& runner) {
  namespace po = boost::program_options;
  RoleContext context;
  context.role = role;
  int participant_index = 0;
  long long index = 0;
  int count = 1;
  int domain = 0;
  std::string run_id_hex;
  double stall_timeout_s = 60.0;
  double tick_interval_s = 0.0;
  std::string cyclone_config;
  bool faults_in_role = false;
  bool stdin_lifeline = false;
  bool status_key_on_stdin = false;

  po::options_description options("Options");
  options.add_options()("help,h", "show this help and exit")(
      "run-dir", po::value(&context.run_dir)->required(),
      "run directory prepared by 'wsntrack run' (holds scenario.yaml and cyclonedds.xml)")(
      "run-id", po::value(&run_id_hex)->required(), "run id (hex) that tags every sample of this run")(
      "domain", po::value(&domain)->required(), "Cyclone DDS domain id of the run")(
      "participant-index", po::value(&participant_index)->required(),
      "this process's Cyclone participant index (unique within the run)")(
      "tiles", po::value(&context.shape.tiles)->required(), "number of sensor-node processes in the cluster")(
      "stall-timeout", po::value(&stall_timeout_s)->default_value(60.0),
      "seconds without any input after which the role gives up (a producer died)")(
      "tick-interval", po::value(&tick_interval_s)->default_value(0.0),
      "sources start at most one tick per this many seconds (0: as fast as possible)")(
      "cyclone-config", po::value(&cyclone_config),
      "the Cyclone DDS configuration template of this host (default RUN_DIR/cyclonedds.xml; a run over "
      "several hosts has one per host)")(
      "faults-in-role", "enact the scenario's kills and pauses of this process in the role itself (exit status 3 "
      "for a kill) instead of awaiting the launcher's signals: for a process the launcher cannot signal")(
      "stdin-lifeline", "end, as for SIGTERM, when standard input reaches its end: a process started over ssh "
      "ends with the launcher's connection")(
      "status-key-on-stdin", "read the run's status key (64 hex digits) from the first line of standard input: "
      "status samples are signed with it, and only samples signed with it are acted on");
  if (indexed)
    options.add_options()("index", po::value(&index)->required(), "tile or supernode index of this process")(
        "first-tick", po::value(&context.first_tick)->default_value(1),
        "the first tick this process takes part in: 1, or the tick of the scenario's `restart` of this supernode")(
        "count", po::value(&count)->default_value(1),
        "run indices --index .. --index + count - 1 as threads of this process on one shared DDS participant "
        "(the launcher groups supernodes so that a large cluster has fewer participants to discover)");

  try {
    po::variables_map vm;
    po::store(po::parse_command_line(argc, argv, options), vm);
    if (vm.count("help")) {
      std::cout << "Usage: wsntrack-" << role << " [options]\n\n" << summary << "\n\n"
                << "Normally started by 'wsntrack run', which prepares the run directory and gives\n"
                << "every process its participant index.\n\n"
                << options << "\n";
      return 0;
    }
    po::notify(vm);
    faults_in_role = vm.count("faults-in-role") != 0;
    stdin_lifeline = vm.count("stdin-lifeline") != 0;
    status_key_on_stdin = vm.count("status-key-on-stdin") != 0;
    if (cyclone_config.empty()) cyclone_config = context.run_dir + "/cyclonedds.xml";
    const char* end = run_id_hex.data() + run_id_hex.size();
    const auto [stop, error] = std::from_chars(run_id_hex.data(), end, context.run_id, 16);
    if (run_id_hex.empty() || error != std::errc() || stop != end)
      throw std::invalid_argument("--run-id must be a 64-bit hexadecimal number, got '" + run_id_hex + "'");
    if (index < 0 || index > 1000000) throw std::invalid_argument("--index must be in [0, 1000000]");
    if (count < 1 || count > 1024) throw std::invalid_argument("--count must be in [1, 1024]");
    if (count > 1 && context.first_tick != 1)
      throw std::invalid_argument("--count above 1 with --first-tick: a restart brings back one supernode");
    context.index = static_cast<std::uint32_t>(index);
    if (context.shape.tiles < 1 || context.shape.tiles > 64) throw std::invalid_argument("--tiles must be in [1, 64]");
    if (participant_index < 0 || participant_index > 1000)
      throw std::invalid_argument("--participant-index must be in [0, 1000]");
    if (!std::isfinite(stall_timeout_s) || stall_timeout_s <= 0 || stall_timeout_s > 604800)
      throw std::invalid_argument("--stall-timeout must be in (0, 604800] seconds");
    if (!std::isfinite(tick_interval_s) || tick_interval_s < 0 || tick_interval_s >= stall_timeout_s)
      throw std::invalid_argument("--tick-interval must be in [0, --stall-timeout) seconds");
  } catch (const std::exception& error) {
    std::cerr << "wsntrack-" << role << ": " << error.what() << "\n(try --help)\n";
    return 2;
  }
  if (domain < 0 || domain > kMaxDomainId) {
    std::cerr << "wsntrack-" << role << ": --domain must be in [0, " << kMaxDomainId << "], got " << domain << "\n";
    return 2;
  }

  std::stop_source stop_source;
  context.stop = stop_source.get_token();
  context.stall_timeout = std::chrono::milliseconds(static_cast<long>(stall_timeout_s * 1000));
  context.tick_interval = std::chrono::microseconds(std::llround(tick_interval_s * 1e6));
  context.domain = static_cast<dds_domainid_t>(domain);
  context.signalled_faults = !faults_in_role;

  try {
    // Before the domain: Cyclone's threads must inherit the blocked signals.
    const StopSignals stop_signals(stop_source, "wsntrack-" + role + " " + std::to_string(context.index));
    readStandardInput(context, status_key_on_stdin, stdin_lifeline);
    context.scenario = load_scenario(context.run_dir + "/scenario.yaml");
    context.shape.supernodes = static_cast<std::int32_t>(context.scenario.supernodes.size());
    if (context.first_tick != 1) {
      const auto restarts = context.faultPlan().restartsAt(context.first_tick);
      if (role != "supernode" || std::find(restarts.begin(), restarts.end(), context.index) == restarts.end())
        throw std::invalid_argument("--first-tick " + std::to_string(context.first_tick) + ": the scenario's faults have no "
                                    "restart of " + role + " " + std::to_string(context.index) + " at that tick");
    }
    if (count > 1) checkGroup(context, count, role);
    Domain domain_handle(context.domain, cycloneConfigFor(readConfigFile(cyclone_config), participant_index, roleIdentity(role)));
    if (count == 1) runner(context);
    else runGroup(context, count, stop_source, role, runner);
    return 0;
  } catch (const ScheduledDeath& death) {
    std::cerr << "wsntrack-" << role << " " << context.index << ": ended as the scenario's faults asked (" << death.what()
              << ")\n";
    return kExitScheduledDeath;
  } catch (const std::exception& error) {
    std::cerr << "wsntrack-" << role << " " << context.index << ": " << error.what() << "\n";
    return 1;
  }
}

}  // namespace wsn::dds

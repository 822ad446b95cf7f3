#include "launcher/run_directory.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "common/dds/cyclone_config.hpp"
#include "common/output.hpp"
#include "common/rng.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "launcher/install_layout.hpp"

extern char** environ;

namespace wsn::launcher {

std::uint64_t newRunId() {
  static std::atomic<std::uint64_t> counter{0};
  const auto now = static_cast<std::uint64_t>(std::chrono::system_clock::now().time_since_epoch().count());
  std::uint64_t id = common::mix64(now ^ common::mix64(static_cast<std::uint64_t>(::getpid()) + (counter++ << 32)));
  return id == 0 ? 1 : id;
}

std::vector<int> domainsOutsideEphemeralPorts(int ephemeral_first, int ephemeral_last) {
  std::vector<int> domains;
  for (int domain = 1; domain <= dds::kMaxDomainId; ++domain) {
    const int first = dds::cyclonePorts(domain, 0).first - 10;  // 7400 + 250 d
    const int last = first + 249;
    if (last < ephemeral_first || first > ephemeral_last) domains.push_back(domain);
  }
  return domains;
}

std::pair<int, int> ephemeralPortRange() {
  std::ifstream in("/proc/sys/net/ipv4/ip_local_port_range");
  int first = 0;
  int last = 0;
  if (in >> first >> last && 0 < first && first <= last && last < 65536) return {first, last};
  return {32768, 60999};
}

int pickFreeDomain(std::uint64_t run_id, int participants) {
  const auto [ephemeral_first, ephemeral_last] = ephemeralPortRange();
  const std::vector<int> domains = domainsOutsideEphemeralPorts(ephemeral_first, ephemeral_last);
  if (domains.empty())
    throw std::runtime_error("every Cyclone DDS domain's ports overlap the ephemeral port range " +
                             std::to_string(ephemeral_first) + "-" + std::to_string(ephemeral_last) +
                             " (/proc/sys/net/ipv4/ip_local_port_range)");
  const std::size_t start = static_cast<std::size_t>(run_id % domains.size());
  for (std::size_t attempt = 0; attempt < domains.size(); ++attempt) {
    const int domain = domains[(start + attempt) % domains.size()];
    bool free = true;
    // Every index up to MaxAutoParticipantIndex, both the discovery and the data port.
    for (int index = 0; index <= participants + dds::kViewerSlots + 1 && free; ++index)
      free = dds::cyclonePortsFree(domain, index);
    if (free) return domain;
  }
  throw std::runtime_error("no Cyclone DDS domain with free loopback ports found");
}

std::string defaultRunDirectory(const common::Scenario& scenario) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &utc);
  return "runs/" + scenario.name + "-seed" + std::to_string(scenario.run.seed) + "-" + stamp + "-" +
         std::to_string(::getpid());
}

void createRunDirectory(const std::string& path, bool overwrite) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(path, error)) {
    if (!fs::is_directory(path, error)) throw std::runtime_error(path + ": exists and is not a directory");
    if (!fs::is_empty(path, error)) {
      if (!overwrite) throw std::runtime_error(path + ": run directory exists and is not empty (use --overwrite)");
      // Only what a previous run left may be cleared: never a directory of the user's own.
      if (!fs::exists(fs::path(path) / "cyclonedds.xml") || !fs::exists(fs::path(path) / "scenario.yaml"))
        throw std::runtime_error(path + ": not a wsntrack run directory (no cyclonedds.xml and scenario.yaml); "
                                        "--overwrite only replaces an earlier run");
      for (const auto& entry : fs::directory_iterator(path, error)) {
        fs::remove_all(entry.path(), error);
        if (error) break;
      }
      if (error) throw std::runtime_error(path + ": cannot clear (" + error.message() + ")");
    }
  }
  fs::create_directories(path + "/logs", error);
  if (error) throw std::runtime_error(path + ": cannot create (" + error.message() + ")");
}

void writeRunInputs(const std::string& run_dir, const common::Scenario& scenario, const RunIdentity& identity,
                    int participants) {
  common::writeTextFile(run_dir + "/scenario.yaml", common::resolvedScenarioYaml(scenario));
  common::writeTextFile(run_dir + "/cyclonedds.xml", dds::cycloneConfigTemplate(identity.run_id, participants));

  const common::Truth truth(scenario);
  common::CsvFile csv(run_dir + "/truth.csv", "tick,target,x,y,vx,vy");
  for (std::int32_t t = 1; t <= scenario.run.ticks; ++t)
    for (const auto& target : truth.at(t))
      csv.row(std::to_string(t) + "," + std::to_string(target.id) + "," + common::fixed6(target.x) + "," +
              common::fixed6(target.y) + "," + common::fixed6(target.vx) + "," + common::fixed6(target.vy));
  csv.close();

  if (scenario.sensors.kind == common::SensorLayoutConfig::Kind::kRandom) {
    const common::SensorLayout layout(scenario);
    common::CsvFile sensors(run_dir + "/sensors.csv", "sensor,x,y");
    for (common::SensorId id = 0; id < layout.size(); ++id) {
      const auto p = layout.truePosition(id);
      sensors.row(std::to_string(id) + "," + common::fixed6(p.x) + "," + common::fixed6(p.y));
    }
    sensors.close();
  }
}

namespace {

/// The last non-empty line of a (small) log file, for a one-line report.
std::string lastLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::string last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  return last;
}

}  // namespace

PlotJob::PlotJob(const std::string& plot_script, const std::string& run_dir, const std::string& format)
    : log_(run_dir + "/logs/plot.log"), files_(run_dir + "/plots/{tracks,cardinality,ospa}." + format) {
  const std::string python = kPlotPython;
  const std::string& script = plot_script;
  if (::access(python.c_str(), X_OK) != 0) {
    outcome_.message = python + " not found (plots need Debian's python3-matplotlib)";
    return;
  }
  if (::access(script.c_str(), R_OK) != 0) {
    outcome_.message = script + " not found (the build copies it beside wsntrack; an install puts it in share/wsntrack/tools)";
    return;
  }
  // Close-on-exec, so that no process of the cluster holds the pipe open.
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
    outcome_.status = PlotOutcome::Status::kFailed;
    outcome_.message = std::string("cannot create a pipe: ") + std::strerror(errno);
    return;
  }
  std::vector<std::string> args{python, script, run_dir, "--format", format, "--wait"};
  std::vector<char*> argv;
  for (auto& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, python.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[0]);
  if (spawned != 0) {
    ::close(pipe_fds[1]);
    outcome_.status = PlotOutcome::Status::kFailed;
    outcome_.message = "cannot start " + python + ": " + std::strerror(spawned);
    return;
  }
  pid_ = pid;
  to_script_ = pipe_fds[1];
}

PlotJob::~PlotJob() {
  if (pid_ > 0) finish(false);
}

PlotOutcome PlotJob::finish(bool go) {
  if (pid_ <= 0) return outcome_;
  // The script may be gone (killed): block SIGPIPE for the write and swallow it if it came.
  sigset_t pipe_signal;
  sigset_t previous;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &previous);
  const auto start = std::chrono::steady_clock::now();
  if (go && ::write(to_script_, "go\n", 3) < 0 && errno == EPIPE) {
    const timespec no_wait{};
    sigtimedwait(&pipe_signal, nullptr, &no_wait);
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  ::close(to_script_);
  to_script_ = -1;

  int status = 0;
  pid_t reaped;
  while ((reaped = ::waitpid(pid_, &status, 0)) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  outcome_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The exit status plot_run.py gives when matplotlib cannot be imported.
  constexpr int kNoMatplotlib = 3;
  if (reaped < 0) {
    // The cluster's supervisor reaps every child it sees exit: the script ended during the run.
    outcome_.status = PlotOutcome::Status::kFailed;
    outcome_.message = "plot_run.py ended during the run (see " + log_ + ")";
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    outcome_.status = go ? PlotOutcome::Status::kDrawn : PlotOutcome::Status::kSkipped;
    outcome_.message = go ? files_ : "not drawn";
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == kNoMatplotlib) {
    outcome_.status = PlotOutcome::Status::kSkipped;
    outcome_.message = "matplotlib is not available to /usr/bin/python3 (apt-get install python3-matplotlib)";
  } else {
    outcome_.status = PlotOutcome::Status::kFailed;
    const std::string why = lastLine(log_);
    outcome_.message = (WIFSIGNALED(status) ? "plot_run.py killed by signal " + std::to_string(WTERMSIG(status))
                                            : "plot_run.py exit " + std::to_string(WEXITSTATUS(status))) +
                       (why.empty() ? "" : ": " + why) + " (see " + log_ + ")";
  }
  return outcome_;
}

// run.json: what a viewer needs to join a run (wsntrack watch, examples/watch_tracks.c). One key
// per line, so that a shell script can pick a value with sed as well as a JSON parser can.
void writeRunDescription(const std::string& run_dir, const RunDescription& run) {
  std::ostringstream json;
  json << "{\n"
       << "  \"run_id\": \"" << std::hex << run.identity.run_id << std::dec << "\",\n"
       << "  \"domain\": " << run.identity.domain << ",\n"
       << "  \"participants\": " << run.participants << ",\n"
       << "  \"viewer_participant_indices\": [" << run.first_viewer_index << ", "
       << run.first_viewer_index + run.viewer_slots - 1 << "],\n"
       << "  \"scenario\": \"" << run.scenario << "\",\n"
       << "  \"ticks\": " << run.ticks << ",\n"
       << "  \"processes\": " << run.processes << ",\n"
       << "  \"tick_interval_s\": " << common::fixed6(run.tick_interval_s) << ",\n"
       << "  \"in_process\": " << (run.in_process ? "true" : "false") << ",\n"
       << "  \"launcher_pid\": " << run.launcher_pid << (run.provenance_json.empty() ? "\n" : ",\n");
  if (!run.provenance_json.empty()) json << "  \"provenance\": " << run.provenance_json << "\n";
  json << "}\n";
  // Written whole and renamed into place: a viewer never reads half a file.
  const std::string path = run_dir + "/run.json";
  common::writeTextFile(path + ".tmp", json.str());
  std::error_code error;
  std::filesystem::rename(path + ".tmp", path, error);
  if (error) throw std::runtime_error(path + ": cannot write (" + error.message() + ")");
}

RunDescription readRunDescription(const std::string& run_dir) {
  const std::string path = run_dir + "/run.json";
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string json = buffer.str();
  auto field = [&](const std::string& key, const std::string& value_pattern) {
    std::smatch match;
    if (!std::regex_search(json, match, std::regex("\"" + key + "\"\\s*:\\s*" + value_pattern)))
      throw std::runtime_error(path + ": no valid \"" + key + "\"");
    return match;
  };
  auto integer = [&](const std::string& key) { return std::stoll(field(key, "(-?[0-9]+)")[1].str()); };
  RunDescription run;
  run.identity.run_id = std::stoull(field("run_id", "\"([0-9a-fA-F]{1,16})\"")[1].str(), nullptr, 16);
  run.identity.domain = static_cast<int>(integer("domain"));
  run.participants = static_cast<int>(integer("participants"));
  const auto viewers = field("viewer_participant_indices", "\\[\\s*([0-9]+)\\s*,\\s*([0-9]+)\\s*\\]");
  run.first_viewer_index = std::stoi(viewers[1].str());
  run.viewer_slots = std::stoi(viewers[2].str()) - run.first_viewer_index + 1;
  run.scenario = field("scenario", "\"([^\"]*)\"")[1].str();
  run.ticks = static_cast<std::int32_t>(integer("ticks"));
  run.processes = static_cast<std::int32_t>(integer("processes"));
  run.tick_interval_s = std::stod(field("tick_interval_s", "([0-9.eE+-]+)")[1].str());
  run.in_process = field("in_process", "(true|false)")[1].str() == "true";
  run.launcher_pid = integer("launcher_pid");
  if (run.identity.domain < 0 || run.identity.domain > dds::kMaxDomainId || run.viewer_slots < 1 || run.ticks < 1)
    throw std::runtime_error(path + ": values out of range");
  return run;
}

}  // namespace wsn::launcher

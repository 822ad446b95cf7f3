#include "launcher/run_directory.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "common/dds/cyclone_config.hpp"
#include "common/output.hpp"
#include "common/rng.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "launcher/cluster.hpp"
#include "launcher/run_credentials.hpp"
#include "scenario/writer.hpp"

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

namespace {

/// Reserves `domain` for this process's lifetime with an exclusive flock on a file per domain, so
/// that two launchers starting at the same instant never choose the same domain: a port probe
/// alone leaves a window between one launcher's check and its roles' bind in which another
/// launcher can choose the same ports. The lock goes with the process (exit or crash). True when
/// reserved, or when locks cannot be used here at all (then the port probe alone decides).
bool reserveDomain(int domain) {
  static const std::filesystem::path directory = [] {
    std::error_code error;
    const auto dir = std::filesystem::temp_directory_path(error) / "wsntrack-domain-locks";
    if (std::filesystem::create_directory(dir, error)) ::chmod(dir.c_str(), 01777);  // any user's runs
    return dir;
  }();
  const auto file = directory / ("domain-" + std::to_string(domain) + ".lock");
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) return true;
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const bool taken = errno == EWOULDBLOCK;
    ::close(fd);
    return !taken;
  }
  return true;  // fd stays open, and the lock held, until the process ends
}

}  // namespace

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
    if (free && reserveDomain(domain)) return domain;
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

namespace {

/// Why `path` cannot be taken: a run is live there, named by the pid its run.json gives.
std::string liveRunError(const std::string& path) {
  std::string pid = "pid unknown: its run.json is not written yet";
  try {
    pid = "pid " + std::to_string(readRunDescription(path).launcher_pid);
  } catch (const std::exception&) {
  }
  return path + ": a run is still live there (wsntrack launcher " + pid + "); wait for it to end, stop it, or choose "
         "another --out";
}

/// Takes the run directory's lock and returns its descriptor, or throws the live-run error. The
/// descriptor of a run stays open (and the lock held) until the process ends; O_CLOEXEC keeps it
/// out of the role processes, whose lifetime the launcher already bounds.
int lockRunDirectory(const std::string& path) {
  const std::string file = path + "/" + kRunLockFile;
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(file + ": cannot create the run's lock (" + std::strerror(errno) + ")");
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd);
    if (error == EWOULDBLOCK) throw std::runtime_error(liveRunError(path));
    throw std::runtime_error(file + ": cannot lock (" + std::strerror(error) + ")");
  }
  return fd;
}

/// Whether the directory holds anything but its lock file.
bool holdsMoreThanLock(const std::string& path) {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(path, error))
    if (entry.path().filename() != kRunLockFile) return true;
  return false;
}

}  // namespace

void createRunDirectory(const std::string& path, bool overwrite) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(path, error) && !fs::is_directory(path, error))
    throw std::runtime_error(path + ": exists and is not a directory");
  int lock = -1;
  // The lock is released on every refusal: a caller that goes on (a test) must not keep it.
  const auto refuse = [&](const std::string& why) {
    if (lock >= 0) ::close(lock);
    throw std::runtime_error(path + ": " + why);
  };
  if (fs::exists(path, error) && holdsMoreThanLock(path)) {
    // A live run is named as such whatever the options: it is the first thing the user must know.
    if (fs::exists(fs::path(path) / kRunLockFile)) lock = lockRunDirectory(path);
    if (!overwrite) refuse("run directory exists and is not empty (use --overwrite)");
    // Only what a previous run left may be cleared: never a directory of the user's own. A launcher
    // stopped in its first milliseconds has left only its lock file (and logs/): that is a run's too.
    const bool has_inputs = fs::exists(fs::path(path) / "cyclonedds.xml") && fs::exists(fs::path(path) / "scenario.yaml");
    if (!has_inputs && lock < 0)
      refuse("not a wsntrack run directory (no cyclonedds.xml and scenario.yaml, no " + std::string(kRunLockFile) +
             "); --overwrite only replaces an earlier run");
  }
  fs::create_directories(path, error);
  if (error) refuse("cannot create (" + error.message() + ")");
  if (lock < 0) lock = lockRunDirectory(path);
  // Checked again under the lock: another launcher may have filled the directory since.
  if (holdsMoreThanLock(path)) {
    if (!overwrite) refuse("run directory exists and is not empty (use --overwrite)");
    for (const auto& entry : fs::directory_iterator(path, error)) {
      if (entry.path().filename() == kRunLockFile) continue;  // the lock we hold stays
      fs::remove_all(entry.path(), error);
      if (error) break;
    }
    if (error) refuse("cannot clear (" + error.message() + ")");
  }
  fs::create_directories(path + "/logs", error);
  if (error) refuse("cannot create (" + error.message() + ")");
}

void writeRunInputs(const std::string& run_dir, const common::Scenario& scenario, const RunIdentity& identity,
                    int participants, const HostPlan& hosts) {
  common::writeTextFile(run_dir + "/scenario.yaml", scenario::resolvedScenarioYaml(scenario));
  dds::CycloneSecurity security;
  if (scenario.run.security == common::RunSecurity::kOn)
    security.credentials_dir =
        writeRunCredentials(run_dir, identity.run_id, identity.domain, scenario.run.message_protection);
  for (std::size_t h = 0; h < std::max<std::size_t>(hosts.hosts().size(), 1); ++h)
    common::writeTextFile(hostConfigFile(run_dir, hosts, h), dds::cycloneConfigTemplate(identity.run_id, participants,
                                                                                       cycloneNetworkOf(hosts, h), security));

  const common::Truth truth(truthConfig(scenario));
  common::CsvFile csv(run_dir + "/truth.csv", kTruthCsvHeader);
  for (std::int32_t t = 1; t <= scenario.run.ticks; ++t)
    for (const auto& target : truth.at(t))
      csv.row(std::to_string(t) + "," + std::to_string(target.id) + "," + common::fixed6(target.x) + "," +
              common::fixed6(target.y) + "," + common::fixed6(target.vx) + "," + common::fixed6(target.vy) + "," +
              common::targetClassName(target.target_class));
  csv.close();

  if (scenario.sensors.kind != common::SensorLayoutConfig::Kind::kGrid) {  // grids need no list
    const common::SensorLayout layout(sensorFieldConfig(scenario));
    common::CsvFile sensors(run_dir + "/sensors.csv", kSensorsCsvHeader);
    for (common::SensorId id = 0; id < layout.size(); ++id) {
      const auto p = layout.truePosition(id);
      sensors.row(std::to_string(id) + "," + common::fixed6(p.x) + "," + common::fixed6(p.y));
    }
    sensors.close();
  }
}

RunIdentity claimRunDirectory(const std::string& run_dir, const common::Scenario& scenario, bool in_process,
                              bool overwrite, const HostPlan& hosts) {
  createRunDirectory(run_dir, overwrite);
  RunIdentity identity;
  identity.run_id = newRunId();
  const int participants = participantCount(scenario, in_process, hosts);
  // Cyclone maps participant index i to ports 7400 + 250 d + 2 i + {10, 11}: beyond 119
  // participants a run's ports would spill into the next domain's range.
  if (participants > kMaxParticipants)
    throw std::runtime_error("a run may have at most " + std::to_string(kMaxParticipants) +
                             " DDS participants on one host (node tiles + supernodes + 3), this one needs " +
                             std::to_string(participants));
  identity.domain = pickFreeDomain(identity.run_id, participants);
  return identity;
}

}  // namespace wsn::launcher

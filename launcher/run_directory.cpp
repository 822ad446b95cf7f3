#include "launcher/run_directory.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <stdexcept>

#include "common/dds/cyclone_config.hpp"
#include "common/output.hpp"
#include "common/rng.hpp"
#include "common/truth.hpp"

namespace wsn::launcher {
namespace {

bool udpPortFree(int port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return false;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const bool free = ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  ::close(fd);
  return free;
}

}  // namespace

std::uint64_t newRunId() {
  static std::atomic<std::uint64_t> counter{0};
  const auto now = static_cast<std::uint64_t>(std::chrono::system_clock::now().time_since_epoch().count());
  std::uint64_t id = common::mix64(now ^ common::mix64(static_cast<std::uint64_t>(::getpid()) + (counter++ << 32)));
  return id == 0 ? 1 : id;
}

int pickFreeDomain(std::uint64_t run_id, int participants) {
  const int span = dds::kMaxDomainId;  // domains 1..230
  const int start = static_cast<int>(run_id % static_cast<std::uint64_t>(span));
  for (int attempt = 0; attempt < span; ++attempt) {
    const int domain = 1 + (start + attempt) % span;
    bool free = true;
    // Every index up to MaxAutoParticipantIndex, both the discovery and the data port.
    for (int index = 0; index <= participants + 1 && free; ++index) {
      const auto [discovery, data] = dds::cyclonePorts(domain, index);
      free = udpPortFree(discovery) && udpPortFree(data);
    }
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
}

}  // namespace wsn::launcher

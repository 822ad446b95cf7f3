// Where the processes of a run spread over several hosts run (`wsntrack run --hosts FILE`): each
// host's name and address, the command that starts a process there, and the roles it runs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/dds/cyclone_config.hpp"
#include "common/scenario_config.hpp"

namespace wsn::launcher {

/// One host of a run.
struct Host {
  std::string name;     ///< [A-Za-z0-9_-]+, names its Cyclone configuration (cyclonedds-NAME.xml)
  std::string address;  ///< IPv4 address its processes use; every host lists every other as a unicast peer
  /// Command a role's command line is appended to, to start it there (ssh HOST, ip netns exec NS);
  /// empty on the launcher's own host, whose roles the launcher starts directly.
  std::vector<std::string> start;
  int line = 0;  ///< where the hosts file lists it, for messages
};

/// The hosts of a run and which role instance runs on which. An empty plan is a run on this host
/// alone, on loopback.
class HostPlan {
 public:
  HostPlan() = default;
  HostPlan(std::vector<Host> hosts, std::map<std::pair<std::string, std::uint32_t>, std::size_t> placed)
      : hosts_(std::move(hosts)), placed_(std::move(placed)) {}

  bool multiHost() const { return !hosts_.empty(); }
  const std::vector<Host>& hosts() const { return hosts_; }
  /// The host (index into hosts()) of role `role` `index`: the one the file names, else the
  /// launcher's own (0).
  std::size_t hostOf(const std::string& role, std::uint32_t index) const;
  /// Whether role `role` `index` starts through a host's start command rather than directly.
  bool startsRemotely(const std::string& role, std::uint32_t index) const {
    return multiHost() && !hosts_[hostOf(role, index)].start.empty();
  }

 private:
  std::vector<Host> hosts_;
  std::map<std::pair<std::string, std::uint32_t>, std::size_t> placed_;
};

/// Where the DDS traffic of processes on host `host` goes: loopback alone for a single-host plan;
/// else the host's address, with every host's address as a unicast peer (its own included, for its
/// other processes).
dds::CycloneNetwork cycloneNetworkOf(const HostPlan& plan, std::size_t host);

/// The Cyclone configuration template of host `host` in run directory `run_dir`: the launcher's
/// host (0) uses the run's cyclonedds.xml, every other host cyclonedds-NAME.xml.
std::string hostConfigFile(const std::string& run_dir, const HostPlan& plan, std::size_t host);

/// Throws common::ScenarioError "FILE:LINE: ..." unless this machine (network namespace) has the
/// first host's address: the launcher runs there, and its observer joins the run from it.
void checkLauncherHost(const HostPlan& plan, const std::string& file);

/// Reads a hosts file for `scenario` (its node tiles and supernodes bound the role indices).
/// Throws common::ScenarioError "FILE:LINE: what was expected" for any problem.
HostPlan loadHostPlan(const std::string& path, const common::Scenario& scenario);

/// The same from the file's text; `name_for_errors` stands for the file in messages.
HostPlan parseHostPlan(const std::string& yaml_text, const std::string& name_for_errors,
                       const common::Scenario& scenario);

}  // namespace wsn::launcher

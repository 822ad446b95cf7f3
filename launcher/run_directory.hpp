// Preparing a run directory: the resolved scenario, the truth, the Cyclone configuration and
// the isolation settings (run id, domain id) that keep concurrent runs apart.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/scenario_config.hpp"
#include "launcher/hosts.hpp"
#include "launcher/run_description.hpp"

namespace wsn::launcher {

/// A fresh run id (time, pid and a counter mixed), never 0.
std::uint64_t newRunId();

/// The domain ids 1 .. dds::kMaxDomainId whose whole Cyclone port block (7400 + 250 d ..
/// + 249) lies outside the kernel's ephemeral port range [ephemeral_first, ephemeral_last]:
/// a port in that range can be taken by any socket the OS numbers itself (another run's, a
/// browser's) between the launcher's check and the roles' bind.
std::vector<int> domainsOutsideEphemeralPorts(int ephemeral_first, int ephemeral_last);

/// The kernel's ephemeral port range (/proc/sys/net/ipv4/ip_local_port_range); Linux's default
/// 32768-60999 when it cannot be read.
std::pair<int, int> ephemeralPortRange();

/// Picks a domain id outside the ephemeral ports whose Cyclone unicast ports for `participants`
/// indices are free on 127.0.0.1, starting from a run-id-dependent position so that
/// concurrent runs spread out, and reserves it for the rest of this process's life (a lock file
/// per domain under the temporary directory): no other launcher on this host picks it meanwhile.
int pickFreeDomain(std::uint64_t run_id, int participants);

/// Default run directory: runs/<scenario name>-seed<seed>-<UTC timestamp>-<pid>.
std::string defaultRunDirectory(const common::Scenario& scenario);

/// The headers of the run's inputs the launcher writes: the targets' states, and the sensors of a
/// layout other than a grid.
inline constexpr const char* kTruthCsvHeader = "tick,target,x,y,vx,vy,class";
inline constexpr const char* kSensorsCsvHeader = "sensor,x,y";

/// The lock file a launcher holds (flock, exclusive) in its run directory for the run's whole life.
inline constexpr const char* kRunLockFile = ".wsntrack.lock";

/// Creates the directory (parents too); it must not exist or be empty unless `overwrite`, and never
/// hold a live run: the directory's lock (kRunLockFile) is taken before anything in it is deleted and
/// held until this process ends, so a second launcher, --overwrite or not, is refused while the
/// first runs ("RUN_DIR: a run is still live there (wsntrack pid N)").
void createRunDirectory(const std::string& path, bool overwrite);

/// Writes scenario.yaml (resolved), truth.csv and cyclonedds.xml for `participants` processes (on a
/// run over several hosts: the launcher's host's, and cyclonedds-NAME.xml for each other host), and
/// sensors.csv (sensor,x,y: true positions) when the layout is random: a grid follows from
/// scenario.yaml alone, and writing it would cost up to 10^7 rows. With run.security on, first the
/// run's credentials (launcher/run_credentials.hpp), which the configurations then name.
void writeRunInputs(const std::string& run_dir, const common::Scenario& scenario, const RunIdentity& identity,
                    int participants, const HostPlan& hosts = {});

/// What a run needs before its run.json can be written: the directory (created, or cleared with
/// `overwrite`, and locked), a fresh run id and a domain with free ports for its participants. The
/// inputs (writeRunInputs) follow once run.json says the run is running, so that a run stopped
/// while they are written is marked. Throws std::runtime_error saying what failed.
RunIdentity claimRunDirectory(const std::string& run_dir, const common::Scenario& scenario, bool in_process,
                              bool overwrite, const HostPlan& hosts = {});

}  // namespace wsn::launcher

// The per-run Cyclone DDS configuration: loopback only (or, for a run over several hosts, the
// host's own address), multicast off, unicast peers (127.0.0.1, or every host of the run), a
// discovery tag unique to the run, and an explicit participant index per process (Cyclone 0.10's
// automatic index probing has an off-by-one; the launcher knows every process).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace wsn::dds {

/// Placeholder in the stored template that each process replaces by its participant index.
inline constexpr const char* kParticipantIndexPlaceholder = "${WSN_PARTICIPANT_INDEX}";

/// Placeholder in a secured run's template for the identity whose credentials a participant
/// presents: each process replaces it by its own (cycloneConfigFor); a viewer that reads the
/// stored file as it is (examples/, through CYCLONEDDS_URI) presents the read-only viewer's.
inline constexpr const char* kIdentityPlaceholder = "${WSN_IDENTITY:-viewer}";

/// Participant indices kept free for live viewers (wsntrack watch, examples/): a run with
/// `participants` processes (the launcher included, indices 0 .. participants - 1) leaves
/// participants .. participants + kViewerSlots - 1 to them, inside MaxAutoParticipantIndex so
/// that unicast discovery reaches them.
inline constexpr int kViewerSlots = 4;

/// Where a process's DDS traffic goes: one interface, and the unicast peers discovery reaches.
struct CycloneNetwork {
  std::string interface_address;                 ///< empty: the loopback interface "lo"
  std::vector<std::string> peers{"127.0.0.1"};   ///< every address a participant of the run may have
};

/// A secured run's credentials (launcher/run_credentials.hpp writes them); an empty directory
/// means security off.
struct CycloneSecurity {
  std::string credentials_dir;  ///< absolute: ca.pem, governance.p7s, permissions.p7s, IDENTITY.{cert,key}.pem
  bool on() const { return !credentials_dir.empty(); }
};

/// Where this build found Cyclone DDS's security plugins (libdds_security_{auth,crypto,ac}.so);
/// empty when it found none, and then no run can be secured.
const std::string& securityPluginDirectory();

/// Participant announcements (SPDP) the run's participants may send in a second, all together.
/// Each participant announces itself to every peer port (participants + viewer slots) once per
/// interval: at one second, 74 participants (64 supernodes) sent 5,700 datagrams a second;
/// Cyclone's discovery thread (dq.builtins) took 6.6 % of all CPU in the tick loop (1.3 % at 8 s).
inline constexpr long long kSpdpAnnouncementsPerSecond = 1000;
/// Cyclone announces at least every lease duration - 2 s (10 s - 2 s) whatever the setting.
inline constexpr int kMaxSpdpIntervalSeconds = 8;

/// The receive buffer each socket asks the kernel for (it gives at most net.core.rmem_max, and
/// a smaller one is no error): 4 MiB holds a tick's burst of fragmented batches.
inline constexpr long long kSocketReceiveBufferBytes = 4LL << 20;

/// How often each participant announces itself, in whole seconds: 1 s while the run is small, so
/// that a lost announcement on a loaded host (sanitizers, parallel runs) is repaired within a
/// second rather than Cyclone's default 30 s; longer as the run grows, keeping all announcements
/// within kSpdpAnnouncementsPerSecond; at most kMaxSpdpIntervalSeconds.
int spdpIntervalSeconds(int participants);

/// The XML template for a run with `participants` processes (the launcher included; on a run
/// over several hosts, the most on any one host).
/// With `security` on, every participant authenticates with the run's credentials and is held
/// to the run's governance and permissions (common/dds/security.hpp); throws std::runtime_error
/// when this build has no security plugins.
std::string cycloneConfigTemplate(std::uint64_t run_id, int participants, const CycloneNetwork& network = {},
                                  const CycloneSecurity& security = {});

/// The template with the participant-index placeholder replaced by `participant_index` and, when
/// `identity` is not empty, the identity placeholder by `identity` (a secured run's credentials).
std::string cycloneConfigFor(const std::string& config_template, int participant_index,
                             const std::string& identity = "");

/// UDP unicast ports Cyclone uses on `domain` for participant `index` (discovery, data).
std::pair<int, int> cyclonePorts(int domain, int index);

/// Whether Cyclone's unicast ports of `index` on `domain` can be bound on 127.0.0.1 right now.
bool cyclonePortsFree(int domain, int index);

/// The interface address a configuration made by cycloneConfigTemplate names; empty for loopback.
std::string cycloneInterfaceAddress(const std::string& config_xml);

/// Whether an interface of this machine (of this network namespace) has IPv4 address `address`.
bool hasLocalAddress(const std::string& address);

/// Largest domain id whose ports still fit below 65536.
inline constexpr int kMaxDomainId = 230;

}  // namespace wsn::dds

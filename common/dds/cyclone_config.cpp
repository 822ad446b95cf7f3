#include "common/dds/cyclone_config.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace wsn::dds {

int spdpIntervalSeconds(int participants) {
  const long long peer_ports = participants + kViewerSlots + 1;
  const long long announcements = static_cast<long long>(participants) * peer_ports;
  const long long seconds = (announcements + kSpdpAnnouncementsPerSecond - 1) / kSpdpAnnouncementsPerSecond;
  return static_cast<int>(std::clamp(seconds, 1LL, static_cast<long long>(kMaxSpdpIntervalSeconds)));
}

const std::string& securityPluginDirectory() {
  static const std::string directory = WSN_DDS_SECURITY_PLUGIN_DIR;
  return directory;
}

namespace {

/// The Security element of a secured run's configuration: Cyclone's three built-in plugins by
/// full path (Debian keeps them out of the loader's path), the run's CA as identity and
/// permissions CA, and the participant's own certificate and key through the identity placeholder.
std::string securitySection(const CycloneSecurity& security) {
  if (securityPluginDirectory().empty())
    throw std::runtime_error("this build of wsntrack found no Cyclone DDS security plugins "
                             "(libdds_security_auth.so, from Debian's libddsc0debian); run with --security off");
  const std::string dir = "file:" + security.credentials_dir + "/";
  const std::string identity = kIdentityPlaceholder;
  const auto library = [](const char* name, const char* init, const char* finalize) {
    return std::string("<Library path=\"") + securityPluginDirectory() + "/libdds_security_" + name +
           ".so\" initFunction=\"" + init + "\" finalizeFunction=\"" + finalize + "\"/>";
  };
  std::ostringstream xml;
  xml << "    <Security>\n"
      << "      <Authentication>" << library("auth", "init_authentication", "finalize_authentication") << "\n"
      << "        <IdentityCA>" << dir << "ca.pem</IdentityCA>\n"
      << "        <IdentityCertificate>" << dir << identity << ".cert.pem</IdentityCertificate>\n"
      << "        <PrivateKey>" << dir << identity << ".key.pem</PrivateKey>\n"
      << "      </Authentication>\n"
      << "      <Cryptographic>" << library("crypto", "init_crypto", "finalize_crypto") << "</Cryptographic>\n"
      << "      <AccessControl>" << library("ac", "init_access_control", "finalize_access_control") << "\n"
      << "        <PermissionsCA>" << dir << "ca.pem</PermissionsCA>\n"
      << "        <Governance>" << dir << "governance.p7s</Governance>\n"
      << "        <Permissions>" << dir << "permissions.p7s</Permissions>\n"
      << "      </AccessControl>\n"
      << "    </Security>\n";
  return xml.str();
}

}  // namespace

std::string cycloneConfigTemplate(std::uint64_t run_id, int participants, const CycloneNetwork& network,
                                  const CycloneSecurity& security) {
  std::ostringstream xml;
  std::string interface = "<NetworkInterface name=\"lo\"/>";
  if (!network.interface_address.empty()) interface = "<NetworkInterface address=\"" + network.interface_address + "\"/>";
  std::string peers;
  for (const auto& peer : network.peers) peers += "<Peer address=\"" + peer + "\"/>";
  // MaxAutoParticipantIndex bounds the ports probed on the unicast peer: one per process and
  // per viewer slot, with headroom for Cyclone's off-by-one.
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<CycloneDDS xmlns=\"https://cdds.io/config\">\n"
      << "  <Domain Id=\"any\">\n"
      << "    <General>\n"
      << "      <Interfaces>" << interface << "</Interfaces>\n"
      << "      <AllowMulticast>false</AllowMulticast>\n"
      << "    </General>\n"
      << "    <Discovery>\n"
      << "      <ParticipantIndex>" << kParticipantIndexPlaceholder << "</ParticipantIndex>\n"
      << "      <MaxAutoParticipantIndex>" << participants + kViewerSlots + 1 << "</MaxAutoParticipantIndex>\n"
      << "      <Peers>" << peers << "</Peers>\n"
      << "      <Tag>wsntrack-" << std::hex << run_id << std::dec << "</Tag>\n"
      << "      <SPDPInterval>" << spdpIntervalSeconds(participants) << " s</SPDPInterval>\n"
      << "    </Discovery>\n"
      // A killed process's readers stay matched until their lease ends (10 s), and a reliable
      // writer keeps what they never acknowledge. Cyclone's adaptive watermark (30 kB at first,
      // lowered whenever a reader asks for retransmits, as a restarted process does when it joins)
      // then blocked every write of the run for those 10 s; a fixed 8 MB per writer rides that out
      // and costs nothing while readers keep up.
      // A burst of fragmented samples (a batch over the 1344-byte fragment size) overflowed the
      // 1 MB receive buffer Cyclone asks for: each lost fragment waits for a heartbeat and a
      // NACK to be repaired, the writer stalls meanwhile, and 4 kB batches went 10x slower than
      // 1 kB ones. Asking for more (max: whatever the kernel's net.core.rmem_max allows, never
      // an error) took them 3x faster (docs/PERFORMANCE.md, "Transport and lockstep").
      << "    <Internal>\n"
      << "      <SocketReceiveBufferSize max=\"" << kSocketReceiveBufferBytes << " B\"/>\n"
      << "      <Watermarks><WhcAdaptive>false</WhcAdaptive><WhcHigh>8 MB</WhcHigh><WhcHighInit>8 MB</WhcHighInit></Watermarks>\n"
      << "    </Internal>\n"
      << (security.on() ? securitySection(security) : std::string())
      << "  </Domain>\n"
      << "</CycloneDDS>\n";
  return xml.str();
}

std::string cycloneConfigFor(const std::string& config_template, int participant_index, const std::string& identity) {
  std::string xml = config_template;
  const std::string placeholder = kParticipantIndexPlaceholder;
  const auto at = xml.find(placeholder);
  if (at == std::string::npos) throw std::invalid_argument("Cyclone configuration has no participant-index placeholder");
  xml.replace(at, placeholder.size(), std::to_string(participant_index));
  if (!identity.empty()) {
    const std::string identity_placeholder = kIdentityPlaceholder;
    for (auto pos = xml.find(identity_placeholder); pos != std::string::npos;
         pos = xml.find(identity_placeholder, pos + identity.size()))
      xml.replace(pos, identity_placeholder.size(), identity);
  }
  return xml;
}

std::pair<int, int> cyclonePorts(int domain, int index) {
  // RTPS port mapping with Cyclone's defaults: PB 7400, DG 250, PG 2, d1 10, d3 11.
  const int base = 7400 + 250 * domain + 2 * index;
  return {base + 10, base + 11};
}

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

std::string cycloneInterfaceAddress(const std::string& config_xml) {
  const std::string key = "<NetworkInterface address=\"";
  const auto at = config_xml.find(key);
  if (at == std::string::npos) return "";
  const auto end = config_xml.find('"', at + key.size());
  return end == std::string::npos ? "" : config_xml.substr(at + key.size(), end - at - key.size());
}

bool hasLocalAddress(const std::string& address) {
  in_addr wanted{};
  if (::inet_pton(AF_INET, address.c_str(), &wanted) != 1) return false;
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return false;
  bool found = false;
  for (const ifaddrs* i = list; i != nullptr && !found; i = i->ifa_next)
    if (i->ifa_addr != nullptr && i->ifa_addr->sa_family == AF_INET)
      found = reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr.s_addr == wanted.s_addr;
  ::freeifaddrs(list);
  return found;
}

bool cyclonePortsFree(int domain, int index) {
  const auto [discovery, data] = cyclonePorts(domain, index);
  return udpPortFree(discovery) && udpPortFree(data);
}

}  // namespace wsn::dds

// The per-run Cyclone configuration: how often participants announce themselves as a run grows.
#include "common/dds/cyclone_config.hpp"

#include <catch2/catch.hpp>
#include <string>

using wsn::dds::cycloneConfigTemplate;
using wsn::dds::kMaxSpdpIntervalSeconds;
using wsn::dds::kSpdpAnnouncementsPerSecond;
using wsn::dds::kViewerSlots;
using wsn::dds::spdpIntervalSeconds;

namespace {
long long announcementsPerSecond(int participants) {
  return static_cast<long long>(participants) * (participants + kViewerSlots + 1) / spdpIntervalSeconds(participants);
}
}  // namespace

TEST_CASE("a small run announces its participants every second", "[dds]") {
  CHECK(spdpIntervalSeconds(1) == 1);
  CHECK(spdpIntervalSeconds(6) == 1);   // the default scenario: 2 tiles, network, supernode, aggregator, launcher
  CHECK(spdpIntervalSeconds(29) == 1);  // 29 x 34 = 986 announcements a second
  CHECK(spdpIntervalSeconds(30) == 2);  // 30 x 35 = 1,050: over the bound at 1 s
}

TEST_CASE("a large run announces less often so that all announcements stay within the bound", "[dds]") {
  // 74 participants (64 supernodes) and 79 ports each: 5,846 a round, so every 6 s.
  CHECK(spdpIntervalSeconds(74) == 6);
  // Up to 85 participants; beyond, Cyclone's lease caps the interval (next case).
  for (int participants = 1; participants <= 85; ++participants) {
    INFO("participants " << participants);
    CHECK(announcementsPerSecond(participants) <= kSpdpAnnouncementsPerSecond);
    CHECK(spdpIntervalSeconds(participants) >= spdpIntervalSeconds(participants == 1 ? 1 : participants - 1));
  }
}

TEST_CASE("the announcement interval never exceeds what Cyclone's lease allows", "[dds]") {
  CHECK(spdpIntervalSeconds(200) == kMaxSpdpIntervalSeconds);
  CHECK(spdpIntervalSeconds(2000) == kMaxSpdpIntervalSeconds);
}

TEST_CASE("the configuration template carries the derived announcement interval", "[dds]") {
  CHECK(cycloneConfigTemplate(1, 5).find("<SPDPInterval>1 s</SPDPInterval>") != std::string::npos);
  CHECK(cycloneConfigTemplate(1, 74).find("<SPDPInterval>6 s</SPDPInterval>") != std::string::npos);
}

TEST_CASE("the configuration asks for a larger receive buffer as a maximum only", "[dds]") {
  const std::string xml = cycloneConfigTemplate(1, 5);
  // A min would make Cyclone fail to start on a kernel whose rmem_max is below it (Debian's
  // default is 208 KiB); a max is a request the kernel may cap.
  CHECK(xml.find("<SocketReceiveBufferSize max=\"4194304 B\"/>") != std::string::npos);
  CHECK(xml.find("SocketReceiveBufferSize min") == std::string::npos);
}

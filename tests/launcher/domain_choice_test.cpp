// The choice of a run's DDS domain: only domains whose whole Cyclone port block lies outside the
// kernel's ephemeral ports, so no socket the OS numbers itself can take a port a role will bind.
#include <algorithm>

#include <catch2/catch.hpp>

#include "launcher/run_directory.hpp"

namespace wsn::launcher {
namespace {

TEST_CASE("domains whose ports touch the ephemeral range are never chosen", "[launcher]") {
  // Linux's default 32768-60999. Domain d uses ports 7400 + 250 d .. 7400 + 250 d + 249:
  // d = 100 ends at 32649 (below), d = 101 ends at 32899 (inside); d = 214 starts at 60900
  // (inside), d = 215 starts at 61150 (above); d = 230 ends at 65149, below 65536.
  const auto domains = domainsOutsideEphemeralPorts(32768, 60999);
  REQUIRE(domains.size() == 100 + 16);
  CHECK(domains.front() == 1);
  CHECK(domains[99] == 100);
  CHECK(domains[100] == 215);
  CHECK(domains.back() == 230);
}

TEST_CASE("a narrower or shifted ephemeral range frees more domains", "[launcher]") {
  // 49152-65535 (the IANA range): ports up to 49151 are safe, 7400 + 250 d + 249 <= 49151 gives d <= 166.
  const auto iana = domainsOutsideEphemeralPorts(49152, 65535);
  REQUIRE(iana.size() == 166);
  CHECK(iana.back() == 166);
  // A range covering every domain's ports leaves none.
  CHECK(domainsOutsideEphemeralPorts(1024, 65535).empty());
}

TEST_CASE("the ephemeral range is read from the kernel and is a proper range", "[launcher]") {
  const auto [first, last] = ephemeralPortRange();
  CHECK(first > 0);
  CHECK(first <= last);
  CHECK(last < 65536);
}

TEST_CASE("a picked domain lies outside the ephemeral ports", "[launcher]") {
  const auto [first, last] = ephemeralPortRange();
  const auto allowed = domainsOutsideEphemeralPorts(first, last);
  for (const std::uint64_t run_id : {1ULL, 77ULL, 123456789ULL}) {
    const int domain = pickFreeDomain(run_id, 8);
    CHECK(std::find(allowed.begin(), allowed.end(), domain) != allowed.end());
  }
}

TEST_CASE("a picked domain is reserved: the same run id picks another one next time", "[launcher]") {
  // Two launchers starting at once with colliding run ids used to probe the same free ports and
  // both take them; the first pick now holds the domain until its process ends.
  const int first = pickFreeDomain(4242, 8);
  const int second = pickFreeDomain(4242, 8);
  CHECK(first != second);
}

}  // namespace
}  // namespace wsn::launcher

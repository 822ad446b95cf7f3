// The hosts file of `wsntrack run --hosts` (launcher/hosts.cpp): which host runs which role, what
// each host's Cyclone configuration lists, and an error with file and line for every mistake.
#include "launcher/hosts.hpp"

#include <catch2/catch.hpp>

#include "common/scenario_error.hpp"

namespace wsn::launcher {
namespace {

/// Two node tiles and four supernodes, as oh_quadrants.
common::Scenario fourGroups() {
  common::Scenario s;
  s.run.node_processes = 2;
  s.supernodes.assign(4, common::Vec2{});
  return s;
}

constexpr const char* kThreeHosts =
    "hosts:\n"
    "  - name: head\n"
    "    address: 10.0.0.1\n"
    "    roles: [network, aggregator]\n"
    "  - name: rack1\n"
    "    address: 10.0.0.2\n"
    "    start: ssh -o BatchMode=yes 10.0.0.2\n"
    "    roles: [node 0, supernode 0-1]\n"
    "  - name: rack2\n"
    "    address: 10.0.0.3\n"
    "    start: [ip, netns, exec, rack2]\n"
    "    roles: [node 1, supernode 2, supernode 3]\n";

/// The message parseHostPlan throws for `text`, or "" when it accepts it.
std::string errorOf(const std::string& text) {
  try {
    parseHostPlan(text, "hosts.yaml", fourGroups());
  } catch (const common::ScenarioError& error) {
    return error.what();
  }
  return "";
}

TEST_CASE("a hosts file places each role on the host that names it", "[launcher][hosts]") {
  const HostPlan plan = parseHostPlan(kThreeHosts, "hosts.yaml", fourGroups());
  REQUIRE(plan.multiHost());
  REQUIRE(plan.hosts().size() == 3);
  CHECK(plan.hostOf("network", 0) == 0);
  CHECK(plan.hostOf("aggregator", 0) == 0);
  CHECK(plan.hostOf("node", 0) == 1);
  CHECK(plan.hostOf("supernode", 1) == 1);
  CHECK(plan.hostOf("node", 1) == 2);
  CHECK(plan.hostOf("supernode", 3) == 2);
  CHECK(plan.hosts()[1].start == std::vector<std::string>{"ssh", "-o", "BatchMode=yes", "10.0.0.2"});
  CHECK(plan.hosts()[2].start == std::vector<std::string>{"ip", "netns", "exec", "rack2"});
  CHECK_FALSE(plan.startsRemotely("network", 0));
  CHECK(plan.startsRemotely("supernode", 2));
}

TEST_CASE("roles no host names run on the launcher's host", "[launcher][hosts]") {
  const HostPlan plan = parseHostPlan(
      "hosts:\n  - {name: a, address: 10.0.0.1}\n  - {name: b, address: 10.0.0.2, start: ssh b, roles: [supernode]}\n",
      "hosts.yaml", fourGroups());
  CHECK(plan.hostOf("node", 1) == 0);
  CHECK(plan.hostOf("network", 0) == 0);
  for (std::uint32_t j = 0; j < 4; ++j) CHECK(plan.hostOf("supernode", j) == 1);
}

TEST_CASE("every host's Cyclone configuration uses its own address and lists every host", "[launcher][hosts]") {
  const HostPlan plan = parseHostPlan(kThreeHosts, "hosts.yaml", fourGroups());
  const auto network = cycloneNetworkOf(plan, 2);
  CHECK(network.interface_address == "10.0.0.3");
  CHECK(network.peers == std::vector<std::string>{"10.0.0.1", "10.0.0.2", "10.0.0.3"});
  const std::string xml = dds::cycloneConfigTemplate(1, 5, network);
  CHECK(xml.find("<NetworkInterface address=\"10.0.0.3\"/>") != std::string::npos);
  CHECK(xml.find("<Peer address=\"10.0.0.1\"/><Peer address=\"10.0.0.2\"/><Peer address=\"10.0.0.3\"/>") !=
        std::string::npos);
  CHECK(xml.find("<AllowMulticast>false</AllowMulticast>") != std::string::npos);
}

TEST_CASE("a single-host plan keeps the loopback configuration", "[launcher][hosts]") {
  const HostPlan none;
  CHECK_FALSE(none.multiHost());
  CHECK(none.hostOf("supernode", 3) == 0);
  CHECK_FALSE(none.startsRemotely("supernode", 3));
  const std::string xml = dds::cycloneConfigTemplate(1, 5, cycloneNetworkOf(none, 0));
  CHECK(xml.find("<NetworkInterface name=\"lo\"/>") != std::string::npos);
  CHECK(xml.find("<Peers><Peer address=\"127.0.0.1\"/></Peers>") != std::string::npos);
}

TEST_CASE("the launcher runs only where the first host's address is", "[launcher][hosts]") {
  const std::string second = "  - {name: b, address: 192.0.2.7, start: ssh b, roles: [node]}\n";
  const HostPlan here = parseHostPlan("hosts:\n  - {name: a, address: 127.0.0.1}\n" + second, "hosts.yaml", fourGroups());
  CHECK_NOTHROW(checkLauncherHost(here, "hosts.yaml"));
  // 192.0.2.0/24 is TEST-NET-1 (RFC 5737): no machine has it.
  const HostPlan elsewhere =
      parseHostPlan("hosts:\n  - {name: a, address: 192.0.2.1}\n" + second, "hosts.yaml", fourGroups());
  try {
    checkLauncherHost(elsewhere, "hosts.yaml");
    FAIL("a launcher on a host without 192.0.2.1 was accepted");
  } catch (const common::ScenarioError& error) {
    CHECK(std::string(error.what()) ==
          "hosts.yaml:2: the first host (a) is the launcher's own, but no interface here has 192.0.2.1: run wsntrack on "
          "that host (in its network namespace, if it is one)");
  }
  CHECK_NOTHROW(checkLauncherHost(HostPlan{}, "none"));
}

TEST_CASE("mistakes in a hosts file are reported with their line", "[launcher][hosts]") {
  const std::string a = "hosts:\n  - {name: a, address: 10.0.0.1}\n";
  CHECK(errorOf("hosts: []\n") ==
        "hosts.yaml:1: a hosts file lists at least two hosts under 'hosts:', the first the launcher's own, each with a "
        "name, an address and (but the first) a start command");
  CHECK(errorOf(a + "  - {name: b, address: 10.0.0.2, start: ssh b, roles: [node 2]}\n") ==
        "hosts.yaml:3: 'node 2': the scenario has 2 nodes (indices 0 to 1)");
  CHECK(errorOf(a + "  - {name: b, address: 10.0.0.2, start: ssh b, roles: [supernode 3-1]}\n") ==
        "hosts.yaml:3: 'supernode 3-1': the range's first index is above its last");
  CHECK(errorOf(a + "  - {name: b, address: 10.0.0.2, start: ssh b, roles: [tracker]}\n")
            .rfind("hosts.yaml:3: a role must read 'network', 'aggregator', 'node',", 0) == 0);
  CHECK(errorOf(a + "  - {name: b, address: 10.0.0.2, start: ssh b, roles: [network 0]}\n") ==
        "hosts.yaml:3: the run has one network process: write 'network' without an index");
  CHECK(errorOf(a + "  - {name: b, address: 10.0.0.2, start: ssh b, roles: [supernode 0-2]}\n"
                    "  - {name: c, address: 10.0.0.3, start: ssh c, roles: [supernode 2]}\n") ==
        "hosts.yaml:4: supernode 2 is placed on two hosts (b and c)");
  CHECK(errorOf(a + "  - {name: b, address: 10.0.0.2, roles: [node]}\n") ==
        "hosts.yaml:3: 'hosts[1]' (b) needs 'start', the command that starts a process there, e.g. "
        "'ssh -o BatchMode=yes 10.0.0.2'");
  CHECK(errorOf("hosts:\n  - {name: a, address: 10.0.0.1, start: ssh a}\n  - {name: b, address: 10.0.0.2, start: ssh b}\n") ==
        "hosts.yaml:2: the first host is the launcher's own, whose roles it starts directly: leave out 'hosts[0].start'");
  CHECK(errorOf(a + "  - {name: b, address: host-b, start: ssh b}\n") ==
        "hosts.yaml:3: 'hosts[1].address' must be an IPv4 address (a.b.c.d), got 'host-b'");
  CHECK(errorOf(a + "  - {name: b, address: 10.0.0.1, start: ssh b}\n") ==
        "hosts.yaml:3: address 10.0.0.1 is given to two hosts (a and b)");
  CHECK(errorOf(a + "  - {name: b, address: 10.0.0.2, start: ssh b}\n") ==
        "hosts.yaml:3: 'hosts[1]' (b) runs no role: list its roles, e.g. [node 0, supernode 0-1], or leave the host out");
  CHECK(errorOf(a + "  - {name: b, address: 10.0.0.2, start: ssh b, roles: []}\n")
            .rfind("hosts.yaml:3: 'hosts[1]' (b) runs no role", 0) == 0);
  CHECK(errorOf("- {name: a, address: 10.0.0.1}\n") ==
        "hosts.yaml:1: a hosts file is a mapping with one key, 'hosts:', got a list");
  CHECK(errorOf(a + "  - {name: a, address: 10.0.0.2, start: ssh b}\n") == "hosts.yaml:3: host 'a' is listed twice");
  CHECK(errorOf(a + "  - {name: b/c, address: 10.0.0.2, start: ssh b}\n") ==
        "hosts.yaml:3: 'hosts[1].name' must be 1 to 32 of A-Z a-z 0-9 _ -, got 'b/c'");
  CHECK(errorOf(a + "  - {name: b, address: 10.0.0.2, start: ''}\n")
            .rfind("hosts.yaml:3: 'hosts[1].start' is empty", 0) == 0);
  CHECK(errorOf(a + "  - {name: b, address: 10.0.0.2, start: ssh b, user: me, roles: [node]}\n").rfind("hosts.yaml:3: ", 0) == 0);
  CHECK(errorOf("hosts: [\n").rfind("hosts.yaml:", 0) == 0);
}

}  // namespace
}  // namespace wsn::launcher

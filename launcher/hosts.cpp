#include "launcher/hosts.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "common/config/yaml_reader.hpp"
#include "common/scenario_error.hpp"

namespace wsn::launcher {
namespace {

using common::ScenarioError;
using common::config::Entry;
using common::config::Reader;
using common::config::Section;

/// "node 0-3" -> every (role, index) it names, checked against the scenario's counts.
std::vector<std::pair<std::string, std::uint32_t>> roleInstances(const Reader& r, int line, const std::string& text,
                                                                 const common::Scenario& scenario) {
  static const std::regex pattern(R"(\s*(node|supernode|network|aggregator)(?:\s+(\d{1,7})(?:\s*-\s*(\d{1,7}))?)?\s*)");
  std::smatch match;
  if (!std::regex_match(text, match, pattern))
    r.fail(line, "a role must read 'network', 'aggregator', 'node', 'node N', 'node N-M', 'supernode', "
                 "'supernode N' or 'supernode N-M', got '" + text + "'");
  const std::string role = match[1];
  const std::int64_t count = role == "node"        ? scenario.run.node_processes
                             : role == "supernode" ? static_cast<std::int64_t>(scenario.supernodes.size())
                                                   : 1;
  if (count == 1 && (role == "network" || role == "aggregator") && match[2].matched)
    r.fail(line, "the run has one " + role + " process: write '" + role + "' without an index");
  std::int64_t first = 0;
  std::int64_t last = count - 1;
  if (match[2].matched) first = last = std::stoll(match[2]);
  if (match[3].matched) last = std::stoll(match[3]);
  if (first > last) r.fail(line, "'" + text + "': the range's first index is above its last");
  if (last >= count)
    r.fail(line, "'" + text + "': the scenario has " + std::to_string(count) + " " + role + (count == 1 ? "" : "s") +
                     " (indices 0 to " + std::to_string(count - 1) + ")");
  std::vector<std::pair<std::string, std::uint32_t>> instances;
  for (std::int64_t i = first; i <= last; ++i) instances.emplace_back(role, static_cast<std::uint32_t>(i));
  return instances;
}

/// A start command: a list of words, or one string split at white space (no shell quoting).
std::vector<std::string> startCommand(const Reader& r, const Entry& entry, const std::string& path) {
  std::vector<std::string> words;
  const int line = Reader::lineOf(entry);
  if (entry.value.IsSequence()) {
    for (const auto& word : entry.value) {
      if (!word.IsScalar() || word.Scalar().empty())
        r.fail(line, "'" + path + "' must list non-empty words, got " + common::config::describe(word));
      words.push_back(word.Scalar());
    }
  } else {
    std::istringstream in(r.textValue(entry, path));
    for (std::string word; in >> word;) words.push_back(word);
  }
  if (words.empty())
    r.fail(line, "'" + path + "' is empty: give the command that starts a process there (e.g. ssh HOST), "
                 "or leave the key out on the launcher's own host");
  return words;
}

}  // namespace

std::size_t HostPlan::hostOf(const std::string& role, std::uint32_t index) const {
  const auto it = placed_.find({role, index});
  return it == placed_.end() ? 0 : it->second;
}

dds::CycloneNetwork cycloneNetworkOf(const HostPlan& plan, std::size_t host) {
  dds::CycloneNetwork network;
  if (!plan.multiHost()) return network;
  network.interface_address = plan.hosts().at(host).address;
  network.peers.clear();
  for (const auto& h : plan.hosts()) network.peers.push_back(h.address);
  return network;
}

HostPlan parseHostPlan(const std::string& yaml_text, const std::string& name_for_errors,
                       const common::Scenario& scenario) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& error) {
    const int line = error.mark.is_null() ? 1 : error.mark.line + 1;
    throw ScenarioError(name_for_errors + ":" + std::to_string(line) + ": invalid YAML: " + error.msg);
  }
  const Reader r(name_for_errors);
  if (root.IsDefined() && !root.IsNull() && !root.IsMap())
    r.fail(Reader::lineOf(root), "a hosts file is a mapping with one key, 'hosts:', got " + common::config::describe(root));
  const Section top = r.section(root, 1, "", {"hosts"});
  const Entry* list = top.find("hosts");
  if (list == nullptr || !list->value.IsSequence() || list->value.size() < 2)
    r.fail(list == nullptr ? 1 : Reader::lineOf(*list),
           "a hosts file lists at least two hosts under 'hosts:', the first the launcher's own, each with a name, an "
           "address and (but the first) a start command");

  std::vector<Host> hosts;
  std::map<std::pair<std::string, std::uint32_t>, std::size_t> placed;
  std::set<std::string> names;
  std::map<std::string, std::string> host_of_address;
  common::config::forEachItem(r, *list, "hosts", "{name, address, start, roles}",
                              [&](const YAML::Node& item, int line, const std::string& path) {
    const Section s = r.section(item, line, path, {"address", "name", "roles", "start"});
    r.require(s, {"name", "address"}, path);
    Host host;
    host.name = r.textValue(*s.find("name"), path + ".name");
    static const std::regex kHostName("[A-Za-z0-9_-]{1,32}");
    if (!std::regex_match(host.name, kHostName))
      r.fail(Reader::lineOf(*s.find("name")), "'" + path + ".name' must be 1 to 32 of A-Z a-z 0-9 _ -, got '" + host.name + "'");
    if (!names.insert(host.name).second) r.fail(Reader::lineOf(*s.find("name")), "host '" + host.name + "' is listed twice");
    host.address = r.textValue(*s.find("address"), path + ".address");
    in_addr parsed{};
    if (::inet_pton(AF_INET, host.address.c_str(), &parsed) != 1)
      r.fail(Reader::lineOf(*s.find("address")), "'" + path + ".address' must be an IPv4 address (a.b.c.d), got '" + host.address + "'");
    if (const auto [at, inserted] = host_of_address.emplace(host.address, host.name); !inserted)
      r.fail(Reader::lineOf(*s.find("address")),
             "address " + host.address + " is given to two hosts (" + at->second + " and " + host.name + ")");
    host.line = line;
    if (const Entry* start = s.find("start")) {
      if (hosts.empty())
        r.fail(Reader::lineOf(*start), "the first host is the launcher's own, whose roles it starts directly: leave out "
                                       "'" + path + ".start'");
      host.start = startCommand(r, *start, path + ".start");
    } else if (!hosts.empty()) {
      r.fail(line, "'" + path + "' (" + host.name + ") needs 'start', the command that starts a process there, e.g. "
                   "'ssh -o BatchMode=yes " + host.address + "'");
    }
    const Entry* roles = s.find("roles");
    if (!hosts.empty() && (roles == nullptr || (roles->value.IsSequence() && roles->value.size() == 0)))
      r.fail(roles == nullptr ? line : Reader::lineOf(*roles),
             "'" + path + "' (" + host.name + ") runs no role: list its roles, e.g. [node 0, supernode 0-1], or leave the "
             "host out");
    if (roles != nullptr) {
      if (!roles->value.IsSequence())
        r.fail(Reader::lineOf(*roles), "'" + path + ".roles' must be a list such as [network, node 0-1, supernode 2], got " +
                                           common::config::describe(roles->value));
      for (const auto& role : roles->value) {
        const int role_line = Reader::lineOf(role) > 0 ? Reader::lineOf(role) : Reader::lineOf(*roles);
        if (!role.IsScalar()) r.fail(role_line, "'" + path + ".roles' must list role names, got " + common::config::describe(role));
        for (const auto& instance : roleInstances(r, role_line, role.Scalar(), scenario)) {
          const auto [at, inserted] = placed.emplace(instance, hosts.size());
          if (!inserted)
            r.fail(role_line, instance.first + " " + std::to_string(instance.second) + " is placed on two hosts (" +
                                  hosts[at->second].name + " and " + host.name + ")");
        }
      }
    }
    hosts.push_back(std::move(host));
  });
  return HostPlan(std::move(hosts), std::move(placed));
}

std::string hostConfigFile(const std::string& run_dir, const HostPlan& plan, std::size_t host) {
  if (host == 0) return run_dir + "/cyclonedds.xml";
  return run_dir + "/cyclonedds-" + plan.hosts().at(host).name + ".xml";
}

void checkLauncherHost(const HostPlan& plan, const std::string& file) {
  if (!plan.multiHost()) return;
  const Host& first = plan.hosts().front();
  if (!dds::hasLocalAddress(first.address))
    throw ScenarioError(file + ":" + std::to_string(std::max(first.line, 1)) + ": the first host (" + first.name +
                        ") is the launcher's own, but no interface here has " + first.address +
                        ": run wsntrack on that host (in its network namespace, if it is one)");
}

HostPlan loadHostPlan(const std::string& path, const common::Scenario& scenario) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ScenarioError(path + ": cannot open hosts file (" + std::strerror(errno) + ")");
  std::stringstream text;
  text << in.rdbuf();
  return parseHostPlan(text.str(), path, scenario);
}

}  // namespace wsn::launcher

// libFuzzer target: a scenario file and its --set overrides, through the loader as `wsntrack run`
// and `wsntrack validate` read them (docs/FUZZING.md). An input is YAML text whose lines starting
// with "--set " are taken out and applied as overrides, in order.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "common/edge_checks.hpp"
#include "scenario/loader.hpp"
#include "scenario/overrides.hpp"
#include "scenario/writer.hpp"

namespace {

using wsn::scenario::ScenarioOverride;

constexpr std::string_view kSetPrefix = "--set ";

/// The YAML text of `input` and its overrides; an override the command line would refuse
/// (no '=', an empty key) is refused here the same way, by OverrideError.
std::string splitOverrides(std::string_view input, std::vector<ScenarioOverride>& overrides) {
  std::string yaml;
  yaml.reserve(input.size());
  while (!input.empty()) {
    const std::size_t end = input.find('\n');
    const std::string_view line = input.substr(0, end == std::string_view::npos ? input.size() : end + 1);
    input.remove_prefix(line.size());
    if (line.starts_with(kSetPrefix)) {
      std::string_view text = line.substr(kSetPrefix.size());
      if (text.ends_with('\n')) text.remove_suffix(1);
      overrides.push_back(wsn::scenario::parseOverride(std::string(text)));
    } else {
      yaml.append(line);  // a dropped line would shift every later line number of the messages
    }
  }
  return yaml;
}

[[noreturn]] void finding(const std::string& what, const std::string& resolved) {
  std::fprintf(stderr, "scenario fuzzer: %s\n--- resolved scenario.yaml ---\n%s\n", what.c_str(), resolved.c_str());
  std::abort();
}

/// The resolved YAML without its "# derived: how" notes: loading it again gives the same values,
/// but every one of them is then written in the file, so none is marked derived any more.
std::string withoutDerivedNotes(const std::string& yaml) {
  std::string out;
  out.reserve(yaml.size());
  std::size_t at = 0;
  while (at < yaml.size()) {
    std::size_t end = yaml.find('\n', at);
    if (end == std::string::npos) end = yaml.size();
    const std::string_view line(yaml.data() + at, end - at);
    out.append(line.substr(0, line.find("  # derived: ")));
    out.push_back('\n');
    at = end + 1;
  }
  return out;
}

/// What a loaded scenario must allow: the bounds every role checks its input against, and the
/// resolved scenario.yaml the launcher writes, which every role loads: it must load, to a
/// scenario that resolves to the same values (writer.hpp: "loads back to an equal scenario").
void checkLoaded(const wsn::common::Scenario& scenario) {
  (void)wsn::common::edgeBounds(scenario);
  const std::string resolved = wsn::scenario::resolvedScenarioYaml(scenario);
  std::string again;
  try {
    again = wsn::scenario::resolvedScenarioYaml(wsn::scenario::parseScenario(resolved, "scenario.yaml"));
  } catch (const wsn::common::ScenarioError& error) {
    finding(std::string("the resolved scenario does not load: ") + error.what(), resolved);
  }
  if (withoutDerivedNotes(again) != withoutDerivedNotes(resolved))
    finding("the resolved scenario loads to another one:\n" + again, resolved);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  try {
    std::vector<ScenarioOverride> overrides;
    const std::string yaml = splitOverrides(input, overrides);
    const wsn::common::Scenario scenario = overrides.empty()
                                               ? wsn::scenario::parseScenario(yaml, "fuzz.yaml")
                                               : wsn::scenario::applyOverrides(yaml, "fuzz.yaml", overrides);
    checkLoaded(scenario);
  } catch (const wsn::common::ScenarioError&) {
    // A clear refusal ("fuzz.yaml:3: ..." or "--set KEY=VALUE: ..."): what bad input must get.
    // Any other exception escapes and libFuzzer reports it: the user would read a bare what()
    // (a yaml-cpp or std::stod message) without file, line or what was expected.
  }
  return 0;
}

// Command-line overrides (--set KEY=VALUE) of scenario/overrides.cpp: applied to the file's YAML,
// validated like a file, and every error naming the --set that caused it.
#include "scenario/overrides.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "node/signal_strength/config.hpp"
#include "scenario/loader.hpp"
#include "scenario/writer.hpp"

namespace wsn::scenario {
namespace {

using namespace common;

/// A small valid scenario; line 5 holds network.pte, line 8 tracker.engine.
constexpr const char* kBase =
    "name: base\n"                                      // 1
    "supernodes:\n"                                     // 2
    "  - {x: 25, y: 50}\n"                              // 3
    "  - {x: 75, y: 50}\n"                              // 4
    "network: {communication_range: 11.6, pte: 0.3}\n"  // 5
    "sensor_model:\n"                                   // 6
    "  sensing_range: 1.5\n"                            // 7
    "tracker: {engine: gnn}\n";                         // 8

std::vector<ScenarioOverride> sets(const std::vector<std::string>& texts) {
  std::vector<ScenarioOverride> out;
  for (const auto& t : texts) out.push_back(parseOverride(t));
  return out;
}

/// The signal-strength model's beta of a scenario.
double betaOf(const Scenario& s) { return settingsOf<node::signal_strength::SignalStrengthSettings>(s.sensor_model).beta; }

Scenario apply(const std::vector<std::string>& texts, const std::string& text = kBase,
               const ScenarioCheck& check = {}) {
  return applyOverrides(text, "s.yaml", sets(texts), check);
}

/// The message of the error applying `texts` throws, prefixed "override: " when it is an
/// OverrideError ("" when nothing is thrown).
std::string errorOf(const std::vector<std::string>& texts, const std::string& text = kBase,
                    const ScenarioCheck& check = {}) {
  try {
    apply(texts, text, check);
  } catch (const OverrideError& error) {
    return std::string("override: ") + error.what();
  } catch (const ScenarioError& error) {
    return error.what();
  }
  return "";
}

/// Stands in for the engine registry: knows the engine "gnn" only and reports at the engine's line.
void onlyGnn(Scenario& s) {
  if (s.tracker.engine != "gnn")
    throw ScenarioError(s.source_path + ":" + std::to_string(s.tracker.engine_line) + ": unknown tracker engine '" +
                        s.tracker.engine + "'; expected one of: gnn");
}

TEST_CASE("an override splits at the first '=' and needs a key", "[scenario][override]") {
  const auto o = parseOverride("tracker.engine=a=b");
  CHECK(o.key == "tracker.engine");
  CHECK(o.value == "a=b");
  CHECK(o.text() == "--set tracker.engine=a=b");
  CHECK(parseOverride("network.pte=").value.empty());
  REQUIRE_THROWS_MATCHES(parseOverride("foo"), OverrideError,
                         Catch::Message("--set foo: expected KEY=VALUE, e.g. --set network.pte=0.4"));
  REQUIRE_THROWS_AS(parseOverride("=3"), OverrideError);
}

TEST_CASE("an override gives the scenario an edit of the file would give", "[scenario][override]") {
  std::string edited = kBase;
  edited.replace(edited.find("pte: 0.3"), 8, "pte: 0.4");
  const Scenario s = apply({"network.pte=0.4"});
  CHECK(s.network.pte == 0.4);
  CHECK(s.network.communication_range == 11.6);  // the rest of the section stays
  CHECK(s.source_path == "s.yaml");
  CHECK(resolvedScenarioYaml(s) == resolvedScenarioYaml(parseScenario(edited, "s.yaml")));
  // No overrides: exactly the file.
  CHECK(resolvedScenarioYaml(apply({})) == resolvedScenarioYaml(parseScenario(kBase, "s.yaml")));
}

TEST_CASE("overrides apply in order and the last one for a key wins", "[scenario][override]") {
  CHECK(apply({"run.ticks=20", "run.ticks=30"}).run.ticks == 30);
  // An empty value is null: the section empties back to its defaults, then gets one key again.
  const Scenario s = apply({"network=", "network.pte=0.4"});
  CHECK(s.network.pte == 0.4);
  CHECK(s.network.communication_range == 11.6);  // the default, not the file's (equal here)
}

TEST_CASE("values derived by the loader follow the overrides", "[scenario][override]") {
  // Oh §VII: beta = 3 (1 + gamma Rs^alpha); with Rs = 2, gamma = 1, alpha = 2: 3 (1 + 4) = 15.
  CHECK(betaOf(apply({})) == 9.75);
  CHECK(betaOf(apply({"sensor_model.sensing_range=2"})) == 15.0);
  // The default supernode sits at the centre of the region: (0 + 50) / 2 = 25.
  const Scenario s = apply({"region.x_max=50", "region.y_max=50"}, "");
  REQUIRE(s.supernodes.size() == 1);
  CHECK(s.supernodes[0].x == 25.0);
  CHECK(s.supernodes[0].y == 25.0);
}

TEST_CASE("sections and engine params left out of the file are created", "[scenario][override]") {
  const Scenario s = apply({"run.ticks=20", "tracker.params.gate_chi2=12", "metrics.ospa_c=10"}, "");
  CHECK(s.run.ticks == 20);
  REQUIRE(s.tracker.params.count("gate_chi2") == 1);
  CHECK(s.tracker.params.at("gate_chi2").value == 12.0);
  CHECK(s.metrics.ospa_c == 10.0);
  // An empty 'tracker:' in the file is filled the same way.
  CHECK(apply({"tracker.params.gate_chi2=12"}, "tracker:\n").tracker.params.at("gate_chi2").value == 12.0);
}

TEST_CASE("values are YAML scalars: numbers, words, quoted strings", "[scenario][override]") {
  CHECK(apply({"tracker.engine=mcmcda"}).tracker.engine == "mcmcda");
  CHECK(apply({"network.pte=4e-1"}).network.pte == 0.4);
  CHECK(apply({"run.seed=0x10"}).run.seed == 16u);
  CHECK(errorOf({"network.pte=abc"}) == "override: --set network.pte=abc: 'network.pte' must be a number, got 'abc'");
  // Quoted, a number is a string, and the loader rejects it as it would in the file.
  CHECK(errorOf({"network.pte=\"0.4\""}) ==
        "override: --set network.pte=\"0.4\": 'network.pte' must be a number, got the quoted string '0.4'");
  CHECK(errorOf({"network.pte="}) == "override: --set network.pte=: 'network.pte' must be a number, got nothing");
  CHECK(errorOf({"network.pte=[1, 2]"}) ==
        "override: --set network.pte=[1, 2]: VALUE must be a single value such as 0.4 or gnn, got a list; lists "
        "and mappings belong in the scenario file");
  CHECK(errorOf({"name=a: b"}).rfind("override: --set name=a: b: VALUE must be a single value", 0) == 0);
  CHECK(errorOf({"name={"}).rfind("override: --set name={: VALUE is not valid YAML (", 0) == 0);
  // yaml-cpp 0.7's LoadAll would loop without end on this one (see yaml_documents.hpp).
  CHECK(errorOf({"name=\"a\", b"}) == "override: --set name=\"a\", b: VALUE is not valid YAML (the YAML parser cannot go "
                                       "past this point); quote it to make it a string");
}

TEST_CASE("an unknown key is the loader's message, naming the --set and no line", "[scenario][override]") {
  CHECK(errorOf({"network.nope=1"}) ==
        "override: --set network.nope=1: unknown key 'nope' in 'network'; expected one of: communication_range, pde, "
        "pte");
  CHECK(errorOf({"nope.x=1"}) ==
        "override: --set nope.x=1: unknown key 'nope' at the top level; expected one of: aggregator, dynamics, faults, "
        "localisation, metrics, name, network, region, run, sensor_model, sensors, supernodes, targets, terrain, tracker");
  CHECK(errorOf({"run.ticks=0"}) == "override: --set run.ticks=0: 'run.ticks' must be in [1, 1000000], got 0");
}

TEST_CASE("list items are addressed by index and never added", "[scenario][override]") {
  const Scenario s = apply({"supernodes[1].x=60"});
  CHECK(s.supernodes[0].x == 25.0);
  CHECK(s.supernodes[1].x == 60.0);
  CHECK(s.supernodes[1].y == 50.0);
  CHECK(errorOf({"supernodes[2].x=60"}) ==
        "override: --set supernodes[2].x=60: 'supernodes' has 2 items (from [0]); a list can only be changed item "
        "by item, not extended");
  CHECK(errorOf({"supernodes.x=60"}) ==
        "override: --set supernodes.x=60: 'supernodes' is a list; address its items as supernodes[0]");
  CHECK(errorOf({"network[0]=1"}) == "override: --set network[0]=1: 'network' is a mapping, not a list");
  CHECK(errorOf({"network.pte.x=1"}) == "override: --set network.pte.x=1: 'network.pte' is '0.3', not a mapping");
  CHECK(errorOf({"supernodes[1].x=150"}) ==
        "override: --set supernodes[1].x=150: 'supernodes[1]' at (150, 50) is outside the region [0, 100] x [0, 100]");
  for (const std::string bad : {"a..b=1", ".a=1", "a.=1", "a[x]=1", "a[]=1", "a[1=1", "a[1]b=1"})
    CHECK(errorOf({bad}) == "override: --set " + bad +
                                ": KEY must be a dotted path of names, list items as name[i] (e.g. network.pte, "
                                "tracker.params.gate_chi2, supernodes[0].x)");
}

TEST_CASE("a problem of the file itself keeps its file:line", "[scenario][override]") {
  const std::string broken = std::string(kBase) + "run: {ticks: many}\n";  // line 9
  CHECK(errorOf({"network.pte=0.4"}, broken) == "s.yaml:9: 'run.ticks' must be an integer, got 'many'");
  // An override that fixes it fixes the scenario.
  CHECK(apply({"run.ticks=5"}, broken).run.ticks == 5);
  // One that breaks a section read earlier than 'run' is the first problem, and is named.
  CHECK(errorOf({"network.pte=2"}, broken) == "override: --set network.pte=2: 'network.pte' must be in [0, 1], got 2");
  CHECK(errorOf({"network.pte=0.4"}, "a: [1\n") == "s.yaml:2: invalid YAML: end of sequence flow not found");
}

TEST_CASE("with several overrides the error names the ones responsible", "[scenario][override]") {
  CHECK(errorOf({"run.ticks=20", "network.pte=2", "tracker.engine=gnn"}) ==
        "override: --set network.pte=2: 'network.pte' must be in [0, 1], got 2");
  // Only the combination is wrong: both are named.
  CHECK(errorOf({"supernodes[0].x=60", "supernodes[1].x=60"}) ==
        "override: --set supernodes[0].x=60 --set supernodes[1].x=60: 'supernodes[1]' at (60, 50) is at the same "
        "place as 'supernodes[0]'");
}

TEST_CASE("further checks run on the result and their errors name the --set", "[scenario][override]") {
  CHECK(apply({"network.pte=0.4"}, kBase, onlyGnn).network.pte == 0.4);
  CHECK(errorOf({"tracker.engine=mcmcda"}, kBase, onlyGnn) ==
        "override: --set tracker.engine=mcmcda: unknown tracker engine 'mcmcda'; expected one of: gnn");
  // The file's own engine problem keeps its line (8).
  std::string other = kBase;
  other.replace(other.find("engine: gnn"), 11, "engine: rb");
  CHECK(errorOf({"network.pte=0.4"}, other, onlyGnn) == "s.yaml:8: unknown tracker engine 'rb'; expected one of: gnn");
  CHECK(apply({"tracker.engine=gnn"}, other, onlyGnn).tracker.engine == "gnn");
}

TEST_CASE("loadScenario with overrides reads the file and names it in its own errors", "[scenario][override]") {
  const Scenario s = loadScenario(WSN_SCENARIO_DIR "/oh_quadrants.yaml", sets({"network.pte=0.4", "run.ticks=20"}));
  CHECK(s.network.pte == 0.4);
  CHECK(s.network.pde == 0.3);
  CHECK(s.run.ticks == 20);
  CHECK(s.source_path == WSN_SCENARIO_DIR "/oh_quadrants.yaml");
  REQUIRE_THROWS_MATCHES(loadScenario(WSN_SCENARIO_DIR "/missing.yaml", sets({"network.pte=0.4"})), ScenarioError,
                         Catch::Message(WSN_SCENARIO_DIR "/missing.yaml: cannot open scenario file (No such file or "
                                                         "directory)"));
}

}  // namespace
}  // namespace wsn::scenario

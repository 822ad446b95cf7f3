// The options of `wsntrack run` (launcher/run_arguments.cpp): --seed, --nodes and --ticks are
// overrides after every --set, checked once by the scenario loader, and an error names the option
// as the user typed it.
#include "launcher/run_arguments.hpp"

#include <boost/program_options/errors.hpp>
#include <catch2/catch.hpp>

namespace wsn::launcher {
namespace {

/// A 10 x 10 region: with sensing range 1.5 its node tiles are made of cells of side 3, with
/// 2.5 of side 5 (4 cells), so 5 tiles fit the first and not the second.
constexpr const char* kBase =
    "name: base\n"
    "region: {x_max: 10, y_max: 10}\n"
    "sensor_model:\n"
    "  sensing_range: 1.5\n";

RunArguments parsed(std::vector<std::string> args) {
  args.insert(args.begin(), "s.yaml");
  return parseRunArguments(args);
}

common::Scenario apply(const std::vector<std::string>& args) { return applyRunOverrides(kBase, "s.yaml", parsed(args)); }

/// The message of what applying `args` throws, "override: " first for an OverrideError.
std::string errorOf(const std::vector<std::string>& args) {
  try {
    apply(args);
  } catch (const scenario::OverrideError& error) {
    return std::string("override: ") + error.what();
  } catch (const common::ScenarioError& error) {
    return error.what();
  }
  return "";
}

TEST_CASE("run options are read as given", "[launcher][run_arguments]") {
  const auto a = parseRunArguments({"scen.yaml", "--seed", "7", "--nodes", "3", "--ticks", "20", "--set", "network.pte=0.4",
                                    "--set", "run.ticks=5", "--in-process", "-q", "--no-plot", "--out", "d", "--overwrite"});
  CHECK(a.scenario_path == "scen.yaml");
  CHECK(a.seed == "7");
  CHECK(a.nodes == "3");
  CHECK(a.ticks == "20");
  CHECK(a.sets == std::vector<std::string>{"network.pte=0.4", "run.ticks=5"});
  CHECK(a.in_process);
  CHECK(a.quiet);
  CHECK_FALSE(a.plot);
  CHECK(a.out_dir == "d");
  CHECK(a.overwrite);
  CHECK_FALSE(a.help);
  // The defaults: 30 minutes, a minute without input, no pacing, png.
  const auto d = parseRunArguments({"scen.yaml"});
  CHECK(d.timeout_s == 1800);
  CHECK(d.stall_timeout_s == 60);
  CHECK(d.tick_interval_s == 0);
  CHECK(d.plot_format == "png");
  CHECK_FALSE(d.seed);
  CHECK(parseRunArguments({"--help"}).help);
  CHECK(parseRunArguments({}).scenario_path.empty());
  REQUIRE_THROWS_AS(parseRunArguments({"s.yaml", "--nope"}), boost::program_options::error);
  REQUIRE_THROWS_AS(parseRunArguments({"s.yaml", "--timeout", "soon"}), boost::program_options::error);
}

TEST_CASE("seed, nodes and ticks are overrides after every --set", "[launcher][run_arguments]") {
  const auto overrides = runOverrides(parsed({"--ticks", "20", "--set", "run.ticks=5", "--seed", "7", "--nodes", "3"}));
  REQUIRE(overrides.size() == 4);
  CHECK(overrides[0].set.text() == "--set run.ticks=5");
  CHECK(overrides[0].as_typed == "--set run.ticks=5");
  // Each names itself as typed in the loader's messages, and sets its key.
  CHECK(overrides[1].set.text() == "--seed 7");
  CHECK(overrides[1].set.key == "run.seed");
  CHECK(overrides[1].as_typed == "--seed 7");
  CHECK(overrides[2].set.text() == "--nodes 3");
  CHECK(overrides[2].set.key == "run.node_processes");
  CHECK(overrides[2].as_typed == "--nodes 3");
  CHECK(overrides[3].set.text() == "--ticks 20");
  CHECK(overrides[3].set.key == "run.ticks");
  CHECK(overrides[3].as_typed == "--ticks 20");
  // Applied last, --ticks wins over the --set of the same key.
  const auto s = apply({"--ticks", "20", "--set", "run.ticks=5", "--seed", "7", "--nodes", "3"});
  CHECK(s.run.ticks == 20);
  CHECK(s.run.seed == 7u);
  CHECK(s.run.node_processes == 3);
  // A seed is a YAML integer like run.seed in a file: hex and the full 64 bits are exact.
  CHECK(apply({"--seed", "0x10"}).run.seed == 16u);
  CHECK(apply({"--seed", "18446744073709551615"}).run.seed == 18446744073709551615u);
  CHECK(apply({}).run.ticks == common::Scenario{}.run.ticks);
}

TEST_CASE("a bad seed, nodes or ticks is the loader's message naming the option", "[launcher][run_arguments]") {
  CHECK(errorOf({"--nodes", "0"}) == "override: --nodes 0: 'run.node_processes' must be in [1, 64], got 0");
  CHECK(errorOf({"--nodes", "65"}) == "override: --nodes 65: 'run.node_processes' must be in [1, 64], got 65");
  CHECK(errorOf({"--ticks", "0"}) == "override: --ticks 0: 'run.ticks' must be in [1, 1000000], got 0");
  CHECK(errorOf({"--ticks", "abc"}) == "override: --ticks abc: 'run.ticks' must be an integer, got 'abc'");
  CHECK(errorOf({"--seed", "-1"}) == "override: --seed -1: 'run.seed' must be in [0, 18446744073709551615], got -1");
  CHECK(errorOf({"--seed", "1x"}) == "override: --seed 1x: 'run.seed' must be an integer, got '1x'");
  // The --set before it is named as written, the option after it by its own name.
  CHECK(errorOf({"--set", "run.ticks=0", "--nodes", "2"}) ==
        "override: --set run.ticks=0: 'run.ticks' must be in [1, 1000000], got 0");
  // 5 tiles need 5 cells: 10 x 10 has (10 / 3)^2 = 9 of side 3, only 4 of side 5; each option
  // alone is fine, so both are named.
  CHECK(errorOf({"--nodes", "5"}).empty());
  const auto both = errorOf({"--set", "sensor_model.sensing_range=2.5", "--nodes", "5"});
  CHECK(both.rfind("override: --set sensor_model.sensing_range=2.5 --nodes 5: 'run.node_processes' 5 exceeds the 4 cells",
                   0) == 0);
  // A --set without '=' is rejected before any loading.
  REQUIRE_THROWS_MATCHES(runOverrides(parsed({"--set", "foo"})), scenario::OverrideError,
                         Catch::Message("--set foo: expected KEY=VALUE, e.g. --set network.pte=0.4"));
}

TEST_CASE("options that are not scenario values are checked on their own", "[launcher][run_arguments]") {
  CHECK_FALSE(checkRunOptions(parsed({})));
  CHECK(checkRunOptions(parsed({"--timeout", "0"})) == "--timeout must be in (0, 604800] seconds, got 0");
  CHECK(checkRunOptions(parsed({"--stall-timeout", "nan"})) == "--stall-timeout must be in (0, 604800] seconds, got nan");
  CHECK(checkRunOptions(parsed({"--plot-format", "jpg"})) == "--plot-format must be png, svg or pdf, got 'jpg'");
  CHECK_FALSE(checkRunOptions(parsed({"--plot-format", "pdf"})).has_value());
  // Pacing must stay below the stall timeout, or every role would give up between two ticks.
  CHECK(checkRunOptions(parsed({"--tick-interval", "60"})) ==
        "--tick-interval must be in [0, 3600] seconds and below --stall-timeout, got 60");
  CHECK_FALSE(checkRunOptions(parsed({"--tick-interval", "0.2"})));
}

TEST_CASE("run help lists every option", "[launcher][run_arguments]") {
  const auto help = runHelp();
  CHECK(help.rfind("Usage: wsntrack run SCENARIO", 0) == 0);
  for (const char* option : {"--seed", "--nodes", "--ticks", "--set", "--out", "--overwrite", "--in-process", "--timeout",
                             "--stall-timeout", "--tick-interval", "--quiet", "--no-plot", "--plot-format"})
    CHECK(help.find(option) != std::string::npos);
}

}  // namespace
}  // namespace wsn::launcher

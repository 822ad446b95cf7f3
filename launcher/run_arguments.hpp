// The options of `wsntrack run` and the scenario they make: --set, --seed, --nodes and --ticks
// are all overrides of the scenario file, checked once by its loader.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scenario/overrides.hpp"

namespace wsn::launcher {

/// The help of --set, shared by run and validate.
inline constexpr const char* kSetHelp =
    "set a scenario value, KEY=VALUE (repeatable): KEY is a dotted path into the scenario YAML, list "
    "items as name[i] (network.pte=0.4, tracker.engine=gnn, tracker.params.max_speed=4, run.ticks=20, "
    "supernodes[0].x=30); VALUE is one YAML scalar; the result is checked like a file";

/// `wsntrack run`'s options as given.
struct RunArguments {
  std::string scenario_path;
  std::string out_dir;  ///< empty: defaultRunDirectory()
  bool overwrite = false;
  std::vector<std::string> sets;     ///< --set KEY=VALUE, in order
  std::optional<std::string> seed;   ///< --seed, as typed
  std::optional<std::string> nodes;  ///< --nodes, as typed
  std::optional<std::string> ticks;  ///< --ticks, as typed
  std::optional<std::string> security;  ///< --security, as typed (on or off)
  bool keep_credentials = false;        ///< --keep-credentials
  bool in_process = false;
  std::string hosts_file;  ///< --hosts: spread the processes over the hosts it lists
  double timeout_s = 1800;
  double stall_timeout_s = 60;
  double tick_interval_s = 0;
  bool quiet = false;
  bool plot = true;
  std::string plot_format = "png";
  bool help = false;  ///< --help: show runHelp()
};

/// Parses the arguments after `wsntrack run`; throws boost::program_options::error for a malformed
/// option (unknown, missing its value, not a number).
RunArguments parseRunArguments(const std::vector<std::string>& args);

/// The text of `wsntrack run --help`.
std::string runHelp();

/// The first problem of the options that are not scenario values (timeouts, pacing, plot format),
/// as "--option must be ..., got ..."; empty when there is none.
std::optional<std::string> checkRunOptions(const RunArguments& args);

/// One scenario override and the option the user wrote for it.
struct RunOverride {
  scenario::ScenarioOverride set;
  std::string as_typed;  ///< "--set KEY=VALUE", or "--nodes 4" for the run.node_processes=4 it stands for
};

/// The overrides of a run in the order they apply: every --set, then --seed, --nodes and --ticks
/// as run.seed, run.node_processes and run.ticks. Throws scenario::OverrideError for a --set without '='.
std::vector<RunOverride> runOverrides(const RunArguments& args);

/// applyOverrides() of the scenario text with the run's overrides; an OverrideError names the
/// options as the user typed them: "--nodes 0: 'run.node_processes' must be in [1, 64], got 0".
common::Scenario applyRunOverrides(const std::string& yaml_text, const std::string& name_for_errors,
                                   const RunArguments& args, const scenario::ScenarioCheck& check = {});

/// The same from args.scenario_path (scenario::loadScenario, with its messages for a missing file).
common::Scenario loadRunScenario(const RunArguments& args, const scenario::ScenarioCheck& check = {});

}  // namespace wsn::launcher

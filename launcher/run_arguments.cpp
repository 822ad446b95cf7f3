#include "launcher/run_arguments.hpp"

#include <boost/program_options.hpp>
#include <cmath>
#include <functional>
#include <sstream>
#include <tuple>

namespace wsn::launcher {
namespace {

namespace po = boost::program_options;

constexpr const char* kRunUsage =
    "Usage: wsntrack run SCENARIO [--seed N] [--out DIR [--overwrite]] [--nodes N] [--ticks T]\n"
    "                    [--set KEY=VALUE]... [--in-process] [--timeout S] [--stall-timeout S]\n"
    "                    [--tick-interval S] [--hosts FILE] [--security on|off]\n"
    "                    [--keep-credentials]\n"
    "                    [--quiet] [--no-plot] [--plot-format png|svg|pdf]\n\n"
    "Starts every process of the cluster on this host — sensor-node tiles, the network\n"
    "model, one supernode per tracking group and the aggregator — over Cyclone DDS on\n"
    "loopback (or, with --hosts, over the hosts a file lists, by unicast between their\n"
    "addresses), shows progress, and prints a summary. Outputs (run directory):\n"
    "  scenario.yaml  truth.csv  observations.csv  tracks_supernode.csv  tracks.csv\n"
    "  tracks_settled.csv  network.json  metrics.json  rejected.json  logs/<role>-<index>.log\n"
    "  sensors.csv (random layout)\n"
    "  plots/{tracks,cardinality,ospa}.png (or .svg; and detections.png with ADMAN sensors):\n"
    "  drawn after the run by plot_run.py with /usr/bin/python3 and matplotlib unless\n"
    "  --no-plot; without them a warning, not a failure\n\n"
    "--set KEY=VALUE changes one value as an edit of the file would: values the loader\n"
    "derives (sensor_model.beta) follow it, and the result passes every check of\n"
    "'wsntrack validate'. The --set options apply in order, e.g. --set network.pte=0.4\n"
    "--set tracker.params.max_speed=4; --seed, --nodes, --ticks and --security follow them as\n"
    "overrides of run.seed, run.node_processes, run.ticks and run.security. The run\n"
    "directory's scenario.yaml records the result.\n\n"
    "Exit status: 0 when every process ran to the last tick; 1 when one failed, timed out or\n"
    "stalled (the summary names it, with its log); 130 (SIGINT, Ctrl-C) or 143 (SIGTERM) when\n"
    "the run was stopped before its end, whose run directory is then incomplete; 2 for bad\n"
    "options or a scenario that does not validate.\n\n";

/// The options, bound to the fields of `a`.
po::options_description runOptions(RunArguments& a) {
  po::options_description options("Options");
  options.add_options()("help,h", "show this help")(
      "seed", po::value<std::string>(),
      "random seed, 0 .. 2^64-1 (overrides run.seed of the scenario)")(
      "out", po::value(&a.out_dir), "run directory (default runs/<scenario>-seed<seed>-<UTC time>-<pid>)")(
      "overwrite", "reuse --out even if it is not empty (its contents are deleted)")(
      "nodes", po::value<std::string>(),
      "number of sensor-node processes (tiles); overrides run.node_processes")(
      "ticks", po::value<std::string>(), "number of ticks T; overrides run.ticks")(
      "security", po::value<std::string>()->value_name("on|off"),
      "DDS Security (overrides run.security; default on): the run's processes authenticate with "
      "credentials made for this run, and nothing else on the host can join, inject or abort it "
      "(docs/SECURITY.md)")(
      "keep-credentials", "keep the run's keys and certificates (RUN_DIR/credentials) after the run, "
      "for debugging; they are removed otherwise")(
      "set", po::value(&a.sets)->value_name("KEY=VALUE"), kSetHelp)(
      "in-process", "run every role as a thread of this process (still over DDS)")(
      "hosts", po::value(&a.hosts_file)->value_name("FILE"),
      "spread the processes over the hosts FILE lists (YAML: each host's name, address, start command "
      "and roles; docs/MULTIHOST.md); the run directory and the wsntrack executables must be at the same "
      "paths on every host")(
      "timeout", po::value(&a.timeout_s)->default_value(1800), "stop everything after this many seconds")(
      "stall-timeout", po::value(&a.stall_timeout_s)->default_value(60),
      "a role gives up after this many seconds without input (a peer died), or without its peers at start")(
      "tick-interval", po::value(&a.tick_interval_s)->default_value(0),
      "real-time pacing: at most one tick per this many seconds, to follow with 'wsntrack watch' "
      "(0: as fast as possible; outputs are the same either way)")(
      "quiet,q", "no progress display")("no-plot", "do not draw the plots (tools/plot_run.py) after the run")(
      "plot-format", po::value(&a.plot_format)->default_value("png"), "format of the plots: png, svg or pdf")(
      "scenario", po::value(&a.scenario_path), "scenario file");
  return options;
}

std::optional<std::string> optionText(const po::variables_map& vm, const char* name) {
  if (!vm.count(name)) return std::nullopt;
  return vm[name].as<std::string>();
}

/// `load` with the run's overrides (an OverrideError names each as the user typed it).
common::Scenario namingOptions(
    const RunArguments& args,
    const std::function<common::Scenario(const std::vector<scenario::ScenarioOverride>&)>& load) {
  const auto overrides = runOverrides(args);
  std::vector<scenario::ScenarioOverride> sets;
  for (const auto& o : overrides) sets.push_back(o.set);
  return load(sets);
}

}  // namespace

RunArguments parseRunArguments(const std::vector<std::string>& args) {
  RunArguments a;
  const auto options = runOptions(a);
  po::positional_options_description positional;
  positional.add("scenario", 1);
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(options).positional(positional).run(), vm);
  po::notify(vm);
  a.seed = optionText(vm, "seed");
  a.nodes = optionText(vm, "nodes");
  a.ticks = optionText(vm, "ticks");
  a.security = optionText(vm, "security");
  a.keep_credentials = vm.count("keep-credentials") != 0;
  a.overwrite = vm.count("overwrite") != 0;
  a.in_process = vm.count("in-process") != 0;
  a.quiet = vm.count("quiet") != 0;
  a.plot = vm.count("no-plot") == 0;
  a.help = vm.count("help") != 0;
  return a;
}

std::string runHelp() {
  RunArguments unused;
  std::ostringstream out;
  out << kRunUsage << runOptions(unused) << "\n";
  return out.str();
}

std::optional<std::string> checkRunOptions(const RunArguments& a) {
  std::ostringstream why;
  for (const auto& [name, value] : {std::pair{"--timeout", a.timeout_s}, std::pair{"--stall-timeout", a.stall_timeout_s}})
    if (!std::isfinite(value) || value <= 0 || value > 604800) {
      why << name << " must be in (0, 604800] seconds, got " << value;
      return why.str();
    }
  if (!a.hosts_file.empty() && a.in_process)
    return "--hosts spreads the run's processes over hosts; --in-process keeps them in one: give one of them";
  if (a.plot_format != "png" && a.plot_format != "svg" && a.plot_format != "pdf")
    return "--plot-format must be png, svg or pdf, got '" + a.plot_format + "'";
  const double interval = a.tick_interval_s;
  if (!std::isfinite(interval) || interval < 0 || interval > 3600 || interval >= a.stall_timeout_s) {
    why << "--tick-interval must be in [0, 3600] seconds and below --stall-timeout, got " << interval;
    return why.str();
  }
  return std::nullopt;
}

std::vector<RunOverride> runOverrides(const RunArguments& a) {
  std::vector<RunOverride> overrides;
  for (const auto& text : a.sets) {
    auto set = scenario::parseOverride(text);
    overrides.push_back({set, set.text()});
  }
  for (const auto& [option, key, value] : {std::tuple{"--seed", "run.seed", a.seed},
                                           std::tuple{"--nodes", "run.node_processes", a.nodes},
                                           std::tuple{"--ticks", "run.ticks", a.ticks},
                                           std::tuple{"--security", "run.security", a.security}})
    if (value) {
      const std::string typed = std::string(option) + " " + *value;
      overrides.push_back({{key, *value, typed}, typed});
    }
  return overrides;
}

common::Scenario applyRunOverrides(const std::string& yaml_text, const std::string& name_for_errors,
                                   const RunArguments& args, const scenario::ScenarioCheck& check) {
  return namingOptions(args, [&](const auto& sets) { return scenario::applyOverrides(yaml_text, name_for_errors, sets, check); });
}

common::Scenario loadRunScenario(const RunArguments& args, const scenario::ScenarioCheck& check) {
  return namingOptions(args, [&](const auto& sets) { return scenario::loadScenario(args.scenario_path, sets, check); });
}

}  // namespace wsn::launcher

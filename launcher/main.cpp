// wsntrack: run a tracking cluster on this host, or validate a scenario.
#include <unistd.h>

#include <boost/program_options.hpp>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>
#include <sstream>

#include "aggregator/association.hpp"
#include "common/provenance.hpp"
#include "common/scenario.hpp"
#include "common/version.hpp"
#include "launcher/cluster.hpp"
#include "launcher/install_layout.hpp"
#include "launcher/plot_job.hpp"
#include "launcher/run_directory.hpp"
#include "launcher/watch.hpp"
#include "supernode/engine.hpp"

namespace po = boost::program_options;
using namespace wsn;

namespace {

constexpr const char* kUsage =
    "Usage: wsntrack <command> [options]\n\n"
    "Multi-target tracking in a wireless sensor network (Oh et al., hierarchical MCMCDA),\n"
    "run as a real multi-process cluster over Cyclone DDS on the loopback interface.\n\n"
    "Commands:\n"
    "  run SCENARIO       start every process of the cluster on this host and write a run directory\n"
    "  watch RUN_DIR      live view of a running cluster's tracks and metrics (from another terminal)\n"
    "  validate FILE...   check scenario files without running them\n"
    "  engines            list the supernode tracking engines, the aggregator's association methods and their parameters\n"
    "  replay RUN_DIR     write an animation of a finished run (GIF, MP4 or HTML) with plot_run.py --animate\n"
    "  version            print the version, git commit and Cyclone DDS version (also --version)\n"
    "  help               show this text\n\n"
    "'wsntrack <command> --help' explains each command's options.\n";

/// The help of --set, shared by run and validate.
constexpr const char* kSetHelp =
    "set a scenario value, KEY=VALUE (repeatable): KEY is a dotted path into the scenario YAML, list "
    "items as name[i] (network.pte=0.4, tracker.engine=gnn, tracker.params.max_speed=4, run.ticks=20, "
    "supernodes[0].x=30); VALUE is one YAML scalar; the result is checked like a file";

/// The --set options, in the order given; throws common::OverrideError for one without '='.
std::vector<common::ScenarioOverride> overridesOf(const po::variables_map& vm) {
  std::vector<common::ScenarioOverride> overrides;
  if (vm.count("set"))
    for (const auto& text : vm["set"].as<std::vector<std::string>>()) overrides.push_back(common::parseOverride(text));
  return overrides;
}

/// Resolves the parameters of the supernode engine and of the aggregator's association.
void resolveComponentParams(common::Scenario& scenario) {
  supernode::resolveEngineParams(scenario);
  aggregator::resolveAssociationParams(scenario);
}

/// Loads a scenario with its overrides and resolves its component parameters: every check a run
/// would make, applied to the scenario as overridden.
common::Scenario loadResolved(const std::string& path, const std::vector<common::ScenarioOverride>& overrides) {
  return common::loadScenario(path, overrides, resolveComponentParams);
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The first number after "key": in one of our own JSON files (fixed, known layout).
std::optional<double> jsonNumber(const std::string& json, const std::string& key) {
  const std::regex pattern("\"" + key + "\"\\s*:\\s*(-?[0-9.eE+-]+)");
  std::smatch match;
  if (!std::regex_search(json, match, pattern)) return std::nullopt;
  return std::stod(match[1].str());
}

std::string show(std::optional<double> value, int decimals) {
  if (!value) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, *value);
  return buffer;
}

void printSummary(const std::string& run_dir, const launcher::ClusterResult& result, bool in_process) {
  const auto metrics = readFile(run_dir + "/metrics.json");
  const auto network = readFile(run_dir + "/network.json");
  const auto row = [](const std::string& name, const std::string& value) {
    std::cout << "  " << name << std::string(name.size() < 26 ? 26 - name.size() : 1, ' ') << value << "\n";
  };
  std::cout << "\nRun directory: " << run_dir << "\n";
  row("mode", in_process ? "in-process (threads over DDS)" : "multi-process over DDS");
  row("targets (truth)", show(jsonNumber(metrics, "truth_targets"), 0));
  row("tracks (global ids)", show(jsonNumber(metrics, "track_ids"), 0));
  row("eps_K  (Oh eq. 9)", show(jsonNumber(metrics, "eps_k"), 4));
  row("eps_X  (Oh eq. 10)", show(jsonNumber(metrics, "eps_x"), 4));
  row("OSPA (mean)", show(jsonNumber(metrics, "ospa_mean"), 4));
  row("reports sent", show(jsonNumber(network, "sent"), 0));
  row("reports lost", show(jsonNumber(network, "lost"), 0));
  row("reports delayed", show(jsonNumber(network, "delayed"), 0));
  row("dropped (older than ws)", show(jsonNumber(metrics, "observations_dropped_stale"), 0));
  row("wall time (tick loop)", show(jsonNumber(metrics, "wall_s"), 3) + " s");
  row("ticks/s (tick loop)", show(jsonNumber(metrics, "ticks_per_s"), 1));
  row("wall time (all)", show(result.wall_s, 3) + " s");
  if (in_process) {
    row("peak RSS (whole process)", show(static_cast<double>(result.in_process_peak_rss_kb) / 1024.0, 1) + " MiB");
    return;
  }
  std::cout << "  peak RSS per process (MiB):";
  for (const auto& outcome : result.outcomes)
    std::cout << " " << outcome.name << " " << show(static_cast<double>(outcome.peak_rss_kb) / 1024.0, 1) << ";";
  std::cout << "\n";
}

int commandValidate(const std::vector<std::string>& args) {
  po::options_description options("Options");
  options.add_options()("help,h", "show this help")(
      "set", po::value<std::vector<std::string>>()->value_name("KEY=VALUE"), kSetHelp)(
      "files", po::value<std::vector<std::string>>(), "scenario files");
  po::positional_options_description positional;
  positional.add("files", -1);
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(options).positional(positional).run(), vm);
  if (vm.count("help") || !vm.count("files")) {
    std::cout << "Usage: wsntrack validate FILE... [--set KEY=VALUE]...\n\nChecks each scenario strictly (unknown"
                 " keys, types, ranges, engine parameters)\nand prints file:line and what was expected for the first"
                 " problem of each file.\nWith --set, each file is checked with the overrides applied; a problem they"
                 " cause\nis reported as 'FILE: --set KEY=VALUE: what was expected'.\nExit code 0 when every file is"
                 " valid, 1 otherwise (2 for a malformed --set).\n\n"
              << options << "\n";
    return vm.count("help") ? 0 : 2;
  }
  std::vector<common::ScenarioOverride> overrides;
  try {
    overrides = overridesOf(vm);
  } catch (const common::OverrideError& error) {
    std::cerr << "wsntrack validate: " << error.what() << "\n";
    return 2;
  }
  int failures = 0;
  for (const auto& file : vm["files"].as<std::vector<std::string>>()) {
    try {
      const auto scenario = loadResolved(file, overrides);
      std::cout << file << (overrides.empty() ? "" : " with " + std::to_string(overrides.size()) + " --set")
                << ": ok (" << scenario.name << ": " << scenario.run.ticks << " ticks, " << scenario.supernodes.size()
                << " supernodes, engine " << scenario.tracker.engine << ")\n";
    } catch (const common::OverrideError& error) {
      std::cerr << file << ": " << error.what() << "\n";
      ++failures;
    } catch (const std::exception& error) {
      std::cerr << error.what() << "\n";
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}

void printParams(const std::vector<common::ParamSpec>& params) {
  for (const auto& p : params)
    std::cout << "  " << p.name << " (default " << p.default_value << ", range [" << p.min << ", " << p.max
              << "]): " << p.description << "\n";
}

int commandEngines() {
  std::cout << "Supernode tracking engines (tracker.engine, tracker.params):\n";
  for (const auto& engine : supernode::engineRegistry()) {
    std::cout << engine.name << ": " << engine.description << "\n";
    printParams(engine.params);
  }
  std::cout << "\nAggregator track association (aggregator.association, aggregator.params):\n";
  for (const auto& method : aggregator::associationRegistry()) {
    std::cout << method.name << ": " << method.description << "\n";
    printParams(method.params);
  }
  return 0;
}

std::string executableDirectory() {
  return std::filesystem::canonical("/proc/self/exe").parent_path().string();
}

/// `wsntrack replay RUN_DIR [options]`: the animation is drawn by plot_run.py --animate (matplotlib),
/// so this only finds the script and hands over; its options and exit status are the script's.
int commandReplay(const std::vector<std::string>& args) {
  const std::string python = launcher::kPlotPython;
  const std::string script = launcher::locateInstall(executableDirectory()).plot_script;
  if (args.empty()) {
    std::cerr << "Usage: wsntrack replay RUN_DIR [options]   ('wsntrack replay --help' lists them)\n";
    return 2;
  }
  if (::access(python.c_str(), X_OK) != 0 || ::access(script.c_str(), R_OK) != 0) {
    std::cerr << "wsntrack replay: needs " << python << " (Debian's python3-matplotlib) and " << script << "\n";
    return 2;
  }
  std::vector<std::string> exec_args{python, script, "--animate"};
  if (args.front() == "--help" || args.front() == "-h") {
    std::cout << "Usage: wsntrack replay RUN_DIR [plot_run.py --animate options]\n\n"
                 "Writes an animation of a finished run: the sensor field, the observations delivered at\n"
                 "each tick, the true targets and the tracks with their ids and covariance ellipses.\n"
                 "The work is done by plot_run.py --animate, whose options follow:\n\n"
              << std::flush;
    exec_args.push_back("--help");
  } else {
    exec_args.insert(exec_args.end(), args.begin(), args.end());
  }
  std::vector<char*> argv;
  for (auto& arg : exec_args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  ::execv(python.c_str(), argv.data());
  std::cerr << "wsntrack replay: cannot start " << python << ": " << std::strerror(errno) << "\n";
  return 1;
}

int commandRun(const std::vector<std::string>& command_line) {
  const std::vector<std::string> args(command_line.begin() + 2, command_line.end());
  std::string scenario_path;
  std::string out_dir;
  std::string seed_text;
  int nodes = 0;
  int ticks = 0;
  double timeout_s = 1800;
  double stall_s = 60;
  double tick_interval_s = 0;
  std::string plot_format = "png";
  po::options_description options("Options");
  options.add_options()("help,h", "show this help")(
      "seed", po::value(&seed_text), "random seed, 0 .. 2^64-1 (overrides run.seed of the scenario)")(
      "out", po::value(&out_dir), "run directory (default runs/<scenario>-seed<seed>-<UTC time>-<pid>)")(
      "overwrite", "reuse --out even if it is not empty (its contents are deleted)")(
      "nodes", po::value(&nodes), "number of sensor-node processes (tiles); overrides run.node_processes")(
      "ticks", po::value(&ticks), "number of ticks T; overrides run.ticks")(
      "set", po::value<std::vector<std::string>>()->value_name("KEY=VALUE"), kSetHelp)(
      "in-process", "run every role as a thread of this process (still over DDS)")(
      "timeout", po::value(&timeout_s)->default_value(1800), "stop everything after this many seconds")(
      "stall-timeout", po::value(&stall_s)->default_value(60),
      "a role gives up after this many seconds without input (a peer died)")(
      "tick-interval", po::value(&tick_interval_s)->default_value(0),
      "real-time pacing: at most one tick per this many seconds, to follow with 'wsntrack watch' "
      "(0: as fast as possible; outputs are the same either way)")(
      "quiet,q", "no progress display")("no-plot", "do not draw the plots (tools/plot_run.py) after the run")(
      "plot-format", po::value(&plot_format)->default_value("png"), "format of the plots: png or svg")(
      "scenario", po::value(&scenario_path), "scenario file");
  po::positional_options_description positional;
  positional.add("scenario", 1);
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(options).positional(positional).run(), vm);
  po::notify(vm);
  if (vm.count("help") || scenario_path.empty()) {
    std::cout << "Usage: wsntrack run SCENARIO [--seed N] [--out DIR [--overwrite]] [--nodes N] [--ticks T]\n"
                 "                    [--set KEY=VALUE]... [--in-process] [--timeout S] [--stall-timeout S]\n"
                 "                    [--tick-interval S]\n"
                 "                    [--quiet] [--no-plot] [--plot-format png|svg]\n\n"
                 "Starts every process of the cluster on this host — sensor-node tiles, the network\n"
                 "model, one supernode per tracking group and the aggregator — over Cyclone DDS on\n"
                 "loopback, shows progress, and prints a summary. Outputs (run directory):\n"
                 "  scenario.yaml  truth.csv  observations.csv  tracks_supernode.csv  tracks.csv\n"
                 "  network.json  metrics.json  logs/<role>-<index>.log  sensors.csv (random layout)\n"
                 "  plots/{tracks,cardinality,ospa}.png (or .svg): drawn after the run by plot_run.py with\n"
                 "  /usr/bin/python3 and matplotlib unless --no-plot; without them a warning, not a failure\n\n"
                 "--set KEY=VALUE changes one value as an edit of the file would: values the loader\n"
                 "derives (sensor_model.beta) follow it, and the result passes every check of\n"
                 "'wsntrack validate'. The --set options apply in order, before --seed, --nodes and\n"
                 "--ticks; e.g. --set network.pte=0.4 --set tracker.params.max_speed=4. The run\n"
                 "directory's scenario.yaml records the result.\n\n"
              << options << "\n";
    return vm.count("help") ? 0 : 2;
  }

  common::Scenario scenario;
  try {
    scenario = loadResolved(scenario_path, overridesOf(vm));
  } catch (const common::OverrideError& error) {
    std::cerr << "wsntrack run: " << error.what() << "\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << error.what() << "\n";
    return 2;
  }
  if (vm.count("seed")) {
    std::uint64_t seed = 0;
    const char* end = seed_text.data() + seed_text.size();
    const auto [stop, error] = std::from_chars(seed_text.data(), end, seed);
    if (seed_text.empty() || error != std::errc() || stop != end) {
      std::cerr << "wsntrack run: --seed must be a whole number in [0, 2^64-1], got '" << seed_text << "'\n";
      return 2;
    }
    scenario.run.seed = seed;
  }
  for (const auto& [name, value] : {std::pair{"--timeout", timeout_s}, std::pair{"--stall-timeout", stall_s}}) {
    if (!std::isfinite(value) || value <= 0 || value > 604800) {
      std::cerr << "wsntrack run: " << name << " must be in (0, 604800] seconds, got " << value << "\n";
      return 2;
    }
  }
  if (vm.count("nodes")) {
    if (nodes < 1 || nodes > 64) {
      std::cerr << "wsntrack run: --nodes must be in [1, 64], got " << nodes << "\n";
      return 2;
    }
    scenario.run.node_processes = nodes;
  }
  if (vm.count("ticks")) {
    if (ticks < 1 || ticks > 1000000) {
      std::cerr << "wsntrack run: --ticks must be in [1, 1000000], got " << ticks << "\n";
      return 2;
    }
    scenario.run.ticks = ticks;
  }

  if (plot_format != "png" && plot_format != "svg") {
    std::cerr << "wsntrack run: --plot-format must be png or svg, got '" << plot_format << "'\n";
    return 2;
  }

  // The overrides pass the same cross-field checks as the file (e.g. tiles vs. cells).
  if (vm.count("seed") || vm.count("nodes") || vm.count("ticks")) {
    try {
      scenario = common::parseScenario(common::resolvedScenarioYaml(scenario), scenario_path + " with --seed/--nodes/--ticks");
      resolveComponentParams(scenario);
    } catch (const std::exception& error) {
      std::cerr << "wsntrack run: " << error.what() << "\n";
      return 2;
    }
  }

  launcher::ClusterOptions cluster;
  cluster.scenario = scenario;
  cluster.in_process = vm.count("in-process") != 0;
  cluster.show_progress = vm.count("quiet") == 0;
  cluster.timeout = std::chrono::seconds(static_cast<long>(timeout_s));
  cluster.stall_timeout_s = stall_s;
  if (!std::isfinite(tick_interval_s) || tick_interval_s < 0 || tick_interval_s > 3600 || tick_interval_s >= stall_s) {
    std::cerr << "wsntrack run: --tick-interval must be in [0, 3600] seconds and below --stall-timeout, got "
              << tick_interval_s << "\n";
    return 2;
  }
  cluster.tick_interval_s = tick_interval_s;
  try {
    cluster.provenance_json = common::provenanceJson(common::captureProvenance(command_line, scenario_path));
  } catch (const std::exception& error) {
    std::cerr << "wsntrack run: " << error.what() << "\n";
    return 2;
  }
  // Located once: the role executables for the cluster, the plot script for the plots.
  const launcher::InstallLayout install = launcher::locateInstall(executableDirectory());
  cluster.bin_dir = install.requireRoleDir();
  cluster.run_dir = out_dir.empty() ? launcher::defaultRunDirectory(scenario) : out_dir;
  try {
    launcher::createRunDirectory(cluster.run_dir, vm.count("overwrite") != 0);
    cluster.identity.run_id = launcher::newRunId();
    const int participants = launcher::participantCount(scenario, cluster.in_process);
    // Cyclone maps participant index i to ports 7400 + 250 d + 2 i + {10, 11}: beyond 119
    // participants a run's ports would spill into the next domain's range.
    if (participants > launcher::kMaxParticipants)
      throw std::runtime_error("a run may have at most " + std::to_string(launcher::kMaxParticipants) +
                               " DDS participants (node tiles + supernodes + 3), this one needs " +
                               std::to_string(participants));
    cluster.identity.domain = launcher::pickFreeDomain(cluster.identity.run_id, participants);
    launcher::writeRunInputs(cluster.run_dir, scenario, cluster.identity, participants);
  } catch (const std::exception& error) {
    std::cerr << "wsntrack run: " << error.what() << "\n";
    return 1;
  }

  std::cerr << "wsntrack: " << scenario.name << " (seed " << scenario.run.seed << ", " << scenario.run.ticks
            << " ticks) on " << scenario.run.node_processes << " node tiles, " << scenario.supernodes.size()
            << " supernodes, engine " << scenario.tracker.engine << ", domain " << cluster.identity.domain
            << (cluster.in_process ? ", in-process" : "") << "\n";
  // Started before the cluster so that python and matplotlib load while it runs.
  std::optional<launcher::PlotJob> plot_job;
  if (!vm.count("no-plot")) plot_job.emplace(install.plot_script, cluster.run_dir, plot_format);
  const auto result = launcher::runCluster(cluster);
  if (!result.ok) {
    std::cerr << "wsntrack run: FAILED: " << result.failure << "\n";
    for (const auto& outcome : result.outcomes)
      if (outcome.exit_code != 0)
        std::cerr << "  " << outcome.name << ": exit " << outcome.exit_code
                  << (outcome.message.empty() ? "" : " (" + outcome.message + ")") << "\n";
    return 1;
  }
  // A run that succeeded stays a success whatever becomes of its plots: they are a view of it.
  std::optional<launcher::PlotOutcome> plots;
  if (plot_job) {
    plots = plot_job->finish(true);
    if (plots->status != launcher::PlotOutcome::Status::kDrawn)
      std::cerr << "wsntrack run: warning: no plots: " << plots->message << "\n";
  }
  printSummary(cluster.run_dir, result, cluster.in_process);
  if (plots) {
    const bool drawn = plots->status == launcher::PlotOutcome::Status::kDrawn;
    std::cout << "  plots" << std::string(21, ' ')
              << (drawn ? plots->message + " (" + show(plots->seconds, 1) + " s)" : "none: " + plots->message) << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << kUsage;
    return 2;
  }
  const std::string command = argv[1];
  const std::vector<std::string> command_line(argv, argv + argc);
  const std::vector<std::string> args(argv + 2, argv + argc);
  try {
    if (command == "run") return commandRun(command_line);
    if (command == "replay") return commandReplay(args);
    if (command == "version" || command == "--version" || command == "-V") {
      std::cout << version::describe() << "\n";
      return 0;
    }
    if (command == "validate") return commandValidate(args);
    if (command == "engines") return commandEngines();
    if (command == "watch") return launcher::commandWatch(args);
    if (command == "help" || command == "--help" || command == "-h") {
      std::cout << kUsage;
      return 0;
    }
    std::cerr << "wsntrack: unknown command '" << command << "'\n\n" << kUsage;
    return 2;
  } catch (const po::error& error) {
    std::cerr << "wsntrack " << command << ": " << error.what() << " (try 'wsntrack " << command << " --help')\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "wsntrack " << command << ": " << error.what() << "\n";
    return 1;
  }
}

// wsntrack: run a tracking cluster on this host, or validate a scenario.
#include <unistd.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>

#include "aggregator/association.hpp"
#include "common/provenance.hpp"
#include "common/version.hpp"
#include "launcher/cluster.hpp"
#include "launcher/components.hpp"
#include "launcher/install_layout.hpp"
#include "launcher/plot_job.hpp"
#include "launcher/resource_estimate.hpp"
#include "launcher/run_arguments.hpp"
#include "launcher/rejections.hpp"
#include "launcher/run_credentials.hpp"
#include "launcher/run_directory.hpp"
#include "launcher/run_summary.hpp"
#include "launcher/setup_guard.hpp"
#include "launcher/watch.hpp"
#include "observation_model/observation_statistics.hpp"
#include "scenario/overrides.hpp"
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
    "  components         list every sensor model, tracking engine and track association with its parameters\n"
    "                     (--json: the machine-readable catalogue the Python package reads: every key,\n"
    "                     component and metric with units and labels, the output files' columns, the\n"
    "                     track-id layout; --markdown: the key tables of scenarios/README.md; --names KIND:\n"
    "                     the names of one kind, one per line: sensor-models, engines, associations or metrics)\n"
    "  engines            list the tracking engines and association methods only\n"
    "  sweep SPEC.yaml    a robustness sweep: one run per grid point, engine and seed, with results.csv,\n"
    "                     summary.csv (mean, sd, 95 % CI), table.md and plots; resumes; -j N or a Dask\n"
    "                     cluster (--scheduler). Also the flag form: sweep --scenario FILE --set-grid ...\n"
    "  replay RUN_DIR     write an animation of a finished run (GIF, MP4 or HTML) with plot_run.py --animate\n"
    "  version            print the version, git commit and Cyclone DDS version (also --version)\n"
    "  help               show this text\n\n"
    "'wsntrack <command> --help' explains each command's options.\n";

/// The --set options, in the order given; throws scenario::OverrideError for one without '='.
std::vector<scenario::ScenarioOverride> overridesOf(const po::variables_map& vm) {
  std::vector<scenario::ScenarioOverride> overrides;
  if (vm.count("set"))
    for (const auto& text : vm["set"].as<std::vector<std::string>>()) overrides.push_back(scenario::parseOverride(text));
  return overrides;
}

/// Resolves the parameters of the supernode engine and of the aggregator's association.
void resolveComponentParams(common::Scenario& scenario) {
  const common::StatisticsSource statistics = observation_model::lazyStatistics(scenario);  // measured once, if at all
  supernode::resolveEngineParams(scenario, statistics);
  aggregator::resolveAssociationParams(scenario, statistics);
  launcher::checkComponentsFit(scenario);
}

/// Loads a scenario with its overrides and resolves its component parameters: every check a run
/// would make, applied to the scenario as overridden.
common::Scenario loadResolved(const std::string& path, const std::vector<scenario::ScenarioOverride>& overrides) {
  return scenario::loadScenario(path, overrides, resolveComponentParams);
}

/// Prints a "warning:" line for a scenario far beyond this machine, before resolving it: resolving
/// (measuring the observation statistics) is itself what takes long on a huge one. A scenario that
/// does not load is left to loadResolved to report.
void warnAboutResources(const std::string& file, const std::vector<scenario::ScenarioOverride>& overrides) {
  common::Scenario scenario;
  try {
    scenario = scenario::loadScenario(file, overrides, [](common::Scenario&) {});
  } catch (const std::exception&) {
    return;
  }
  for (const auto& warning : launcher::resourceWarnings(launcher::estimateResources(scenario), launcher::totalRamBytes()))
    std::cerr << file << ": " << warning << std::endl;
}

int commandValidate(const std::vector<std::string>& args) {
  po::options_description options("Options");
  options.add_options()("help,h", "show this help")(
      "set", po::value<std::vector<std::string>>()->value_name("KEY=VALUE"), launcher::kSetHelp)(
      "seed", po::value<std::string>()->value_name("N"), "the seed: sets run.seed after every --set, as wsntrack run does")(
      "nodes", po::value<std::string>()->value_name("N"), "node processes: sets run.node_processes, as wsntrack run does")(
      "ticks", po::value<std::string>()->value_name("T"), "ticks T: sets run.ticks, as wsntrack run does")(
      "files", po::value<std::vector<std::string>>(), "scenario files");
  po::positional_options_description positional;
  positional.add("files", -1);
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(options).positional(positional).run(), vm);
  if (vm.count("help") || !vm.count("files")) {
    std::cout << "Usage: wsntrack validate FILE... [--set KEY=VALUE]... [--seed N] [--nodes N] [--ticks T]\n\nChecks each scenario strictly (unknown"
                 " keys, types, ranges, engine parameters)\nand prints file:line and what was expected for the first"
                 " problem of each file.\nWith --set, each file is checked with the overrides applied; a problem they"
                 " cause\nis reported as 'FILE: --set KEY=VALUE: what was expected'.\nExit code 0 when every file is"
                 " valid, 1 otherwise (2 for a malformed --set).\n\n"
              << options << "\n";
    return vm.count("help") ? 0 : 2;
  }
  std::vector<scenario::ScenarioOverride> overrides;
  try {
    overrides = overridesOf(vm);
    // The same overrides, reported as typed, that wsntrack run makes of these options.
    for (const auto& [option, key] : {std::pair{"seed", "run.seed"}, std::pair{"nodes", "run.node_processes"},
                                      std::pair{"ticks", "run.ticks"}})
      if (vm.count(option)) {
        const auto value = vm[option].as<std::string>();
        overrides.push_back({key, value, "--" + std::string(option) + " " + value});
      }
  } catch (const scenario::OverrideError& error) {
    std::cerr << "wsntrack validate: " << error.what() << "\n";
    return 2;
  }
  int failures = 0;
  for (const auto& file : vm["files"].as<std::vector<std::string>>()) {
    try {
      warnAboutResources(file, overrides);
      const auto scenario = loadResolved(file, overrides);
      std::cout << file
                << (overrides.empty() ? ""
                                      : " with " + std::to_string(overrides.size()) +
                                            (overrides.size() == 1 ? " override" : " overrides"))
                << ": ok (" << scenario.name << ": " << scenario.run.ticks << " ticks, " << scenario.supernodes.size()
                << " supernodes, engine " << scenario.tracker.engine << ")\n";
    } catch (const scenario::OverrideError& error) {
      std::cerr << file << ": " << error.what() << "\n";
      ++failures;
    } catch (const std::exception& error) {
      std::cerr << error.what() << "\n";
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}

std::string executableDirectory() {
  return std::filesystem::canonical("/proc/self/exe").parent_path().string();
}

/// Replaces this process with `exec_args` (a python and its script); returns only on failure.
int execTool(const std::string& command, std::vector<std::string>& exec_args) {
  std::vector<char*> argv;
  for (auto& arg : exec_args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  ::execv(exec_args.front().c_str(), argv.data());
  std::cerr << "wsntrack " << command << ": cannot start " << exec_args.front() << ": " << std::strerror(errno) << "\n";
  return 1;
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
  return execTool("replay", exec_args);
}

/// `wsntrack sweep SPEC.yaml | --scenario FILE ...`: robustness sweeps are the Python package's
/// (wsntrack.sweep: scheduling, Student's t intervals, matplotlib plots, Dask); this finds
/// sweep.py and hands over, with this wsntrack as the one the sweep runs unless --wsntrack names another.
int commandSweep(const std::vector<std::string>& args) {
  const std::string python = launcher::kPlotPython;
  const std::string script = launcher::locateInstall(executableDirectory()).tools_dir + "/sweep.py";
  if (::access(python.c_str(), X_OK) != 0 || ::access(script.c_str(), R_OK) != 0) {
    std::cerr << "wsntrack sweep: needs " << python << " (Debian's python3) and " << script << "\n";
    return 2;
  }
  std::vector<std::string> exec_args{python, script};
  exec_args.insert(exec_args.end(), args.begin(), args.end());
  const bool named = std::any_of(args.begin(), args.end(), [](const std::string& a) {
    return a == "--wsntrack" || a.rfind("--wsntrack=", 0) == 0;
  });
  if (!named) {
    exec_args.push_back("--wsntrack");
    exec_args.push_back(std::filesystem::canonical("/proc/self/exe").string());
  }
  ::setenv("WSNTRACK_PROG", "wsntrack sweep", 1);  // the usage line names the command the user typed
  return execTool("sweep", exec_args);
}

/// The files a run that succeeded has written: a run is complete only with every one of them.
constexpr const char* kRunOutputs[] = {"scenario.yaml",        "truth.csv",          "observations.csv",
                                       "network.json",         "tracks_supernode.csv", "tracks.csv",
                                       "tracks_settled.csv",   "metrics_per_tick.csv", "metrics.json",
                                       "rejected.json"};

/// Marks run.json; a run.json that cannot be rewritten (deleted under the run) is a warning, not a
/// second failure.
void markRunOrWarn(const std::string& run_dir, const std::string& status, const std::string& reason) {
  try {
    launcher::markRun(run_dir, status, reason);
  } catch (const std::exception& error) {
    std::cerr << "wsntrack run: warning: " << error.what() << "\n";
  }
}

/// Ends a run that failed: run.json marked failed with the failure, then the report. The exit status.
int failRun(const std::string& run_dir, const launcher::ClusterResult& result) {
  markRunOrWarn(run_dir, launcher::kRunFailed, result.failure);
  std::cerr << launcher::runFailure(result);
  return launcher::runExitStatus(result);
}

/// Draws the plots of a run that succeeded; a failure to draw them is a warning, not a failure of
/// the run: they are a view of it.
std::optional<launcher::PlotOutcome> finishPlots(std::optional<launcher::PlotJob>& job) {
  if (!job) return std::nullopt;
  auto plots = job->finish(true);
  if (plots.status != launcher::PlotOutcome::Status::kDrawn)
    std::cerr << "wsntrack run: warning: no plots: " << plots.message << "\n";
  return plots;
}

int commandRun(const std::vector<std::string>& command_line) {
  const auto started = std::chrono::steady_clock::now();
  const auto args = launcher::parseRunArguments({command_line.begin() + 2, command_line.end()});
  if (args.help || args.scenario_path.empty()) {
    std::cout << launcher::runHelp();
    return args.help ? 0 : 2;
  }
  if (const auto problem = launcher::checkRunOptions(args)) {
    std::cerr << "wsntrack run: " << *problem << "\n";
    return 2;
  }
  launcher::ClusterOptions cluster;
  cluster.started = started;
  cluster.timeout = std::chrono::seconds(static_cast<long>(args.timeout_s));
  // From here until the cluster runs, --timeout and SIGINT/SIGTERM end set-up wherever it is.
  launcher::SetupGuard guard(started, cluster.timeout);
  guard.phase("resolving the scenario");
  common::Scenario scenario;
  try {
    scenario = launcher::loadRunScenario(args, resolveComponentParams);
  } catch (const scenario::OverrideError& error) {
    std::cerr << "wsntrack run: " << error.what() << "\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << error.what() << "\n";
    return 2;
  }

  if (!args.hosts_file.empty()) {
    try {
      cluster.hosts = launcher::loadHostPlan(args.hosts_file, scenario);
      launcher::checkLauncherHost(cluster.hosts, args.hosts_file);
    } catch (const std::exception& error) {
      std::cerr << "wsntrack run: " << error.what() << "\n";
      return 2;
    }
  }
  cluster.scenario = scenario;
  cluster.in_process = args.in_process;
  cluster.show_progress = !args.quiet;
  cluster.stall_timeout_s = args.stall_timeout_s;
  cluster.tick_interval_s = args.tick_interval_s;
  try {
    cluster.provenance_json = common::provenanceJson(common::captureProvenance(command_line, args.scenario_path));
  } catch (const std::exception& error) {
    std::cerr << "wsntrack run: " << error.what() << "\n";
    return 2;
  }
  // Located once: the role executables for the cluster, the plot script for the plots.
  const launcher::InstallLayout install = launcher::locateInstall(executableDirectory());
  cluster.bin_dir = install.requireRoleDir();
  cluster.run_dir = args.out_dir.empty() ? launcher::defaultRunDirectory(scenario) : args.out_dir;
  // Another host's processes start wherever its start command leaves them (ssh: the home directory).
  if (cluster.hosts.multiHost()) cluster.run_dir = std::filesystem::absolute(cluster.run_dir).lexically_normal().string();
  guard.phase("preparing the run directory");
  // The credentials go however the command ends once the directory is this run's (the set-up
  // guard removes them if a signal ends set-up).
  launcher::CredentialsRemoval credentials(args.keep_credentials);
  guard.keepCredentials(args.keep_credentials);
  try {
    cluster.identity =
        launcher::claimRunDirectory(cluster.run_dir, scenario, cluster.in_process, args.overwrite, cluster.hosts);
    credentials.arm(cluster.run_dir);
    {
      const std::lock_guard lock(guard.runJsonMutex());
      launcher::writeRunDescription(cluster.run_dir, launcher::describeRun(cluster));
    }
    guard.runDirectory(cluster.run_dir);
    guard.phase("writing the run's inputs");
    launcher::writeRunInputs(cluster.run_dir, scenario, cluster.identity,
                             launcher::participantCount(scenario, cluster.in_process, cluster.hosts), cluster.hosts);
    // The placement is part of the record of the run (its outputs do not depend on it).
    if (cluster.hosts.multiHost())
      std::filesystem::copy_file(args.hosts_file, cluster.run_dir + "/hosts.yaml",
                                 std::filesystem::copy_options::overwrite_existing);
  } catch (const std::exception& error) {
    if (guard.hasRunDirectory()) markRunOrWarn(cluster.run_dir, launcher::kRunFailed, error.what());
    std::cerr << "wsntrack run: " << error.what() << "\n";
    return 1;
  }

  std::cerr << launcher::runStartLine(scenario, cluster.identity.domain, cluster.in_process, cluster.hosts);
  // Started before the cluster so that python and matplotlib load while it runs.
  std::optional<launcher::PlotJob> plot_job;
  if (args.plot) plot_job.emplace(install.plot_script, cluster.run_dir, args.plot_format);
  // Role threads stuck in their own set-up cannot be joined: the run ends with the process.
  cluster.abandon = [&](const launcher::ClusterResult& stuck) {
    auto result = stuck;
    result.failure += " (role threads did not stop within 3 s, still in set-up or stuck: the process ends without them)";
    credentials.remove();
    std::_Exit(failRun(cluster.run_dir, result));
  };
  guard.handOver();
  auto result = launcher::runCluster(cluster);
  try {
    launcher::gatherRejections(cluster.run_dir);
  } catch (const std::exception& error) {
    if (result.ok) result.failure = std::string("cannot write rejected.json: ") + error.what();
    result.ok = false;
  }
  if (result.ok) {
    for (const char* name : kRunOutputs)
      if (!std::filesystem::exists(cluster.run_dir + "/" + name)) {
        result.ok = false;
        result.failure = "every role exited 0, but " + cluster.run_dir + "/" + name + " is missing";
        break;
      }
  }
  if (!result.ok) return failRun(cluster.run_dir, result);
  // Complete before the plots: they are a view of the run, drawn from it, and plot_run.py only
  // draws a complete run.
  markRunOrWarn(cluster.run_dir, launcher::kRunComplete, "");
  const auto plots = finishPlots(plot_job);
  std::cout << launcher::runSummary(cluster.run_dir, launcher::readRunFigures(cluster.run_dir), result,
                                    cluster.in_process, plots);
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
    if (command == "sweep") return commandSweep(args);
    if (command == "version" || command == "--version" || command == "-V") {
      std::cout << version::describe() << "\n";
      return 0;
    }
    if (command == "validate") return commandValidate(args);
    if (command == "components" && args.size() == 1 && (args[0] == "--markdown" || args[0] == "--json")) {
      std::cout << (args[0] == "--json" ? launcher::componentsJson() : launcher::componentsMarkdown());
      return 0;
    }
    if (command == "components" && args.size() == 2 && args[0] == "--names") {
      try {
        std::cout << launcher::componentNames(args[1]);
      } catch (const std::invalid_argument& error) {
        std::cerr << "wsntrack components: " << error.what() << "\n";
        return 2;
      }
      return 0;
    }
    if ((command == "components" || command == "engines") && !args.empty()) {
      std::cerr << "Usage: wsntrack " << command << (command == "components" ? " [--json | --markdown | --names KIND]" : "")
                << "\n";
      return 2;
    }
    if (command == "components" || command == "engines") {
      std::cout << (command == "components" ? launcher::componentsText() : launcher::enginesText());
      return 0;
    }
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

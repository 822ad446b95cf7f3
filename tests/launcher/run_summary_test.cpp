// What `wsntrack run` prints (launcher/run_summary.cpp), from hand-made run files and results.
#include "launcher/run_summary.hpp"

#include <csignal>

#include <catch2/catch.hpp>

namespace wsn::launcher {
namespace {

/// The keys the summary reads, where the aggregator and the network model put them.
constexpr const char* kMetrics = R"({
  "scenario": "s", "truth_targets": 5, "eps_k": 0.123456, "eps_x": 1.5, "eps_x_gated": 0.75, "ospa": 2.25,
  "observations_dropped_stale": 3,
  "metrics": {"eps_k": 9, "ospa_mean": 2.25, "track_ids": 7},
  "streams": {"settled": {"eps_k": 0.0625, "metrics": {"ospa_mean": 1.125}}},
  "timing": {"wall_s": 1.23456, "ticks_per_s": 80.04}
})";
constexpr const char* kNetwork = R"({
  "communication_range": 11.6, "sent": 1174, "lost": 319, "delayed": 449, "unreachable": 12,
  "supernodes": [{"supernode": 0, "sent": 1, "lost": 2, "delayed": 3}]
})";

ClusterResult processes() {
  ClusterResult result;
  result.ok = true;
  result.wall_s = 4.5;
  result.first_tick_s = 1.25;
  result.outcomes = {{"node 0", 0, "", "", 10240, 0, ""}, {"aggregator 0", 0, "", "", 20480 + 512, 0, ""}};
  return result;
}

TEST_CASE("the figures come from their own keys in metrics.json and network.json", "[launcher][run_summary]") {
  const auto f = parseRunFigures(kMetrics, kNetwork);
  CHECK(f.truth_targets == 5);
  CHECK(f.eps_k == 0.123456);  // the headline value, not the one under "metrics"
  // The summary's eps_X is the gated one; the ungated 1.5 is left in metrics.json.
  CHECK(f.eps_x_gated == 0.75);
  CHECK(f.ospa_mean == 2.25);
  CHECK(f.track_ids == 7);
  CHECK(f.dropped_stale == 3);
  CHECK(f.wall_s == 1.23456);
  CHECK(f.ticks_per_s == 80.04);
  CHECK(f.reports_sent == 1174);  // the total, not the supernode's
  CHECK(f.reports_lost == 319);
  CHECK(f.reports_delayed == 449);
}

TEST_CASE("missing files, keys and undefined metrics give no figure", "[launcher][run_summary]") {
  const auto none = parseRunFigures("", "not json");
  CHECK_FALSE(none.truth_targets);
  CHECK_FALSE(none.reports_sent);
  // eps_x_gated is written as null when no match was closer than the gate.
  const auto f = parseRunFigures(R"({"eps_k": 0.5, "eps_x": 2, "eps_x_gated": null, "metrics": 3})", "[]");
  CHECK(f.eps_k == 0.5);
  CHECK_FALSE(f.eps_x_gated);
  CHECK_FALSE(f.track_ids);  // "metrics" is not an object here
  CHECK_FALSE(f.reports_sent);
}

TEST_CASE("the summary of a multi-process run lists figures and each process's memory", "[launcher][run_summary]") {
  PlotOutcome plots;
  plots.status = PlotOutcome::Status::kDrawn;
  plots.message = "d/plots/{tracks,cardinality,ospa}.png";
  plots.seconds = 1.26;
  // Values at 26 columns; eps with 4 decimals, times with 3, ticks/s with 1; RSS in MiB:
  // 10240 kB = 10.0, 20992 kB = 20.5.
  CHECK(runSummary("d", parseRunFigures(kMetrics, kNetwork), processes(), false, plots) ==
        "\nRun directory: d\n"
        "  mode                      multi-process over DDS\n"
        "  targets (truth)           5\n"
        "  tracks (global ids)       7\n"
        "  eps_K  (Oh eq. 9)         0.1235\n"
        "  eps_X gated (Oh eq. 10)   0.7500\n"
        "  OSPA (mean)               2.2500\n"
        "  eps_K  settled            0.0625\n"
        "  OSPA settled (mean)       1.1250\n"
        "  reports sent              1174\n"
        "  reports lost              319\n"
        "  reports delayed           449\n"
        "  reports unreachable       12\n"
        "  dropped (older than ws)   3\n"
        "  start-up (to tick 1)      1.250 s\n"
        "  wall time (tick loop)     1.235 s\n"
        "  ticks/s (tick loop)       80.0\n"
        "  wall time (all)           4.500 s\n"
        "  peak RSS per process (MiB): node 0 10.0; aggregator 0 20.5;\n"
        "  plots                     d/plots/{tracks,cardinality,ospa}.png (1.3 s)\n");
}

TEST_CASE("the summary of an in-process run without figures says n/a", "[launcher][run_summary]") {
  auto result = processes();
  result.in_process_peak_rss_kb = 3 * 1024;
  result.first_tick_s = 0.0;  // the aggregator never finished tick 1
  PlotOutcome skipped;
  skipped.message = "matplotlib is not available";
  const auto text = runSummary("d", RunFigures{}, result, true, skipped);
  CHECK(text.find("  mode                      in-process (threads over DDS)\n") != std::string::npos);
  CHECK(text.find("  eps_K  (Oh eq. 9)         n/a\n") != std::string::npos);
  CHECK(text.find("  wall time (tick loop)     n/a s\n") != std::string::npos);
  CHECK(text.find("start-up") == std::string::npos);
  CHECK(text.find("  peak RSS (whole process)  3.0 MiB\n") != std::string::npos);
  CHECK(text.find("per process") == std::string::npos);
  CHECK(text.find("  plots                     none: matplotlib is not available\n") != std::string::npos);
  // --no-plot: no plots line at all.
  CHECK(runSummary("d", RunFigures{}, result, true, std::nullopt).find("plots") == std::string::npos);
}

TEST_CASE("a failed run names the failure and every process that exited non-zero", "[launcher][run_summary]") {
  auto result = processes();
  result.ok = false;
  result.failure = "supernode 1 exited with 3";
  result.outcomes.push_back({"supernode 1", 3, "bad engine", "", 0, 0, ""});
  result.outcomes.push_back({"network 0", 143, "", "", 0, 0, ""});
  result.outcomes.push_back({"node 1", 1, kStoppedByLauncher, "", 0, 0, ""});
  CHECK(runFailure(result) ==
        "wsntrack run: FAILED: supernode 1 exited with 3\n"
        "  supernode 1: exit 3 (bad engine)\n"
        "  network 0: exit 143\n"
        "  node 1: stopped by the launcher (exit 1)\n");
}

TEST_CASE("a process killed by a signal is named with the signal, its exit code kept", "[launcher][run_summary]") {
  CHECK(signalName(SIGKILL) == "SIGKILL");
  CHECK(signalName(SIGSEGV) == "SIGSEGV");
  CHECK(signalName(SIGTERM) == "SIGTERM");
  CHECK(signalName(64) == "signal 64");
  RoleOutcome killed{"supernode 2", 128 + SIGKILL, "", "", 0, SIGKILL, ""};
  CHECK(exitDescription(killed) == "killed by SIGKILL");
  // A process that exits with 137 itself is not a signal death.
  CHECK(exitDescription({"node 0", 137, "", "", 0, 0, ""}) == "exited with code 137");
  auto result = processes();
  result.ok = false;
  result.failure = "supernode 2 killed by SIGKILL; log d/logs/supernode-2.log";
  result.outcomes.push_back(killed);
  CHECK(runFailure(result) ==
        "wsntrack run: FAILED: supernode 2 killed by SIGKILL; log d/logs/supernode-2.log\n"
        "  supernode 2: killed by SIGKILL, exit 137\n");
}

TEST_CASE("an interrupted run is named as one, with its exit status, and lists no process as failed",
          "[launcher][run_summary]") {
  auto result = processes();
  result.ok = false;
  result.interrupted_by = SIGINT;
  result.failure = "interrupted by SIGINT before the last tick; the run directory is incomplete";
  // Every role stops with a non-zero code when it is told to: none of them is a fault.
  for (auto& outcome : result.outcomes) outcome.exit_code = 1;
  CHECK(runFailure(result) ==
        "wsntrack run: interrupted by SIGINT before the last tick; the run directory is incomplete (exit status 130)\n");
  CHECK(runExitStatus(result) == 130);
  result.interrupted_by = SIGTERM;
  CHECK(runExitStatus(result) == 143);
  result.interrupted_by = 0;
  CHECK(runExitStatus(result) == 1);
  result.ok = true;
  CHECK(runExitStatus(result) == 0);
}

TEST_CASE("the start line says what runs where", "[launcher][run_summary]") {
  common::Scenario s;
  s.name = "oh";
  s.run.seed = 3;
  s.run.ticks = 20;
  s.run.node_processes = 4;
  s.supernodes.resize(2);
  s.tracker.engine = "gnn";
  CHECK(runStartLine(s, 17, false) ==
        "wsntrack: oh (seed 3, 20 ticks) on 4 node tiles, 2 supernodes, engine gnn, domain 17, DDS Security (encrypted)\n");
  s.run.message_protection = common::MessageProtection::kSign;
  CHECK(runStartLine(s, 17, true) == "wsntrack: oh (seed 3, 20 ticks) on 4 node tiles, 2 supernodes, engine gnn, "
                                     "domain 17, in-process, DDS Security (signed)\n");
  s.run.security = common::RunSecurity::kOff;
  CHECK(runStartLine(s, 17, false) ==
        "wsntrack: oh (seed 3, 20 ticks) on 4 node tiles, 2 supernodes, engine gnn, domain 17, DDS Security off\n");
}


TEST_CASE("a run with faults lists each fault and the reports lost to dead supernodes", "[launcher][run_summary]") {
  const std::string metrics = R"({"eps_k": 0.2, "faults": [
    {"tick": 20, "action": "partition", "what": "partition between supernodes 0 and 1 at tick 20 for 15 ticks",
     "handoffs_lost": 2},
    {"tick": 40, "action": "kill", "what": "kill of supernode 2 at tick 40", "tracks_left": 3,
     "tracks_carried_on": 2, "tracks_lost": 1, "rehome_ticks": 1},
    {"tick": 60, "action": "pause", "what": "pause of supernode 1 at tick 60 for 10 ticks", "tracks_left": 0,
     "tracks_carried_on": 0, "tracks_lost": 0, "rehome_ticks": null}]})";
  const auto figures = parseRunFigures(metrics, R"({"sent": 10, "lost_dead_supernode": 7})");
  REQUIRE(figures.faults.size() == 3);
  CHECK(figures.faults[0] == "partition between supernodes 0 and 1 at tick 20 for 15 ticks: 2 handoffs lost");
  CHECK(figures.faults[1] == "kill of supernode 2 at tick 40: 2 of 3 tracks carried on, the first after 1 ticks");
  CHECK(figures.faults[2] == "pause of supernode 1 at tick 60 for 10 ticks: 0 of 0 tracks carried on");
  const auto text = runSummary("d", figures, processes(), false, std::nullopt);
  CHECK(text.find("  lost to dead supernodes   7\n") != std::string::npos);
  CHECK(text.find("  fault                     kill of supernode 2 at tick 40: 2 of 3") != std::string::npos);
  // A run without faults has neither line.
  const auto plain = runSummary("d", parseRunFigures(kMetrics, kNetwork), processes(), false, std::nullopt);
  CHECK(plain.find("fault") == std::string::npos);
  CHECK(plain.find("dead supernodes") == std::string::npos);
}

}  // namespace
}  // namespace wsn::launcher

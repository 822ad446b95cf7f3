#include "launcher/run_summary.hpp"

#include <csignal>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

namespace wsn::launcher {
namespace {

/// The number at `pointer` (e.g. "/metrics/track_ids"); empty when it is absent or not a number.
std::optional<double> numberAt(const nlohmann::json& json, const char* pointer) {
  const nlohmann::json::json_pointer where(pointer);
  if (!json.contains(where) || !json.at(where).is_number()) return std::nullopt;
  return json.at(where).get<double>();
}

nlohmann::json parseOrNull(const std::string& text) {
  auto json = nlohmann::json::parse(text, nullptr, false);
  return json.is_object() ? json : nlohmann::json();
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string show(std::optional<double> value, int decimals) {
  if (!value) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, *value);
  return buffer;
}

double mib(long kb) { return static_cast<double>(kb) / 1024.0; }

/// One "  name      value" line, the values in one column.
void row(std::ostringstream& out, const std::string& name, const std::string& value) {
  out << "  " << name << std::string(name.size() < 26 ? 26 - name.size() : 1, ' ') << value << "\n";
}

/// "kill of supernode 2 at tick 40: 2 of 2 tracks carried on, the first after 0 ticks";
/// "restart of supernode 2 at tick 70: 1 tracks taken back, the first after 2 ticks".
std::string faultLine(const nlohmann::json& fault) {
  std::string line = fault.value("what", std::string("fault"));
  if (fault.contains("tracks_left") && fault["tracks_left"].is_number()) {
    const auto left = fault["tracks_left"].get<long>();
    const auto carried = fault.value("tracks_carried_on", 0L);
    line += ": " + std::to_string(carried) + " of " + std::to_string(left) + " tracks carried on";
    if (fault.contains("rehome_ticks") && fault["rehome_ticks"].is_number())
      line += ", the first after " + std::to_string(fault["rehome_ticks"].get<long>()) + " ticks";
  }
  if (fault.contains("tracks_taken_back") && fault["tracks_taken_back"].is_number()) {
    line += ": " + std::to_string(fault["tracks_taken_back"].get<long>()) + " tracks taken back";
    if (fault.contains("takeback_ticks") && fault["takeback_ticks"].is_number())
      line += ", the first after " + std::to_string(fault["takeback_ticks"].get<long>()) + " ticks";
  }
  if (fault.contains("handoffs_lost") && fault["handoffs_lost"].is_number())
    line += ": " + std::to_string(fault["handoffs_lost"].get<long>()) + " handoffs lost";
  return line;
}

}  // namespace

RunFigures parseRunFigures(const std::string& metrics_json, const std::string& network_json) {
  const auto metrics = parseOrNull(metrics_json);
  const auto network = parseOrNull(network_json);
  RunFigures f;
  f.truth_targets = numberAt(metrics, "/truth_targets");
  f.track_ids = numberAt(metrics, "/metrics/track_ids");
  f.eps_k = numberAt(metrics, "/eps_k");
  f.eps_x_gated = numberAt(metrics, "/eps_x_gated");
  f.ospa_mean = numberAt(metrics, "/metrics/ospa_mean");
  f.settled_eps_k = numberAt(metrics, "/streams/settled/eps_k");
  f.settled_ospa_mean = numberAt(metrics, "/streams/settled/metrics/ospa_mean");
  f.dropped_stale = numberAt(metrics, "/observations_dropped_stale");
  f.wall_s = numberAt(metrics, "/timing/wall_s");
  f.ticks_per_s = numberAt(metrics, "/timing/ticks_per_s");
  f.reports_sent = numberAt(network, "/sent");
  f.reports_lost = numberAt(network, "/lost");
  f.reports_delayed = numberAt(network, "/delayed");
  f.reports_unreachable = numberAt(network, "/unreachable");
  f.reports_lost_dead_supernode = numberAt(network, "/lost_dead_supernode");
  if (metrics.contains("faults") && metrics["faults"].is_array())
    for (const auto& fault : metrics["faults"]) f.faults.push_back(faultLine(fault));
  return f;
}

RunFigures readRunFigures(const std::string& run_dir) {
  auto figures = parseRunFigures(readFile(run_dir + "/metrics.json"), readFile(run_dir + "/network.json"));
  const auto rejected = nlohmann::json::parse(readFile(run_dir + "/rejected.json"), nullptr, false);
  if (!rejected.is_discarded() && rejected.contains("total") && rejected["total"].is_number())
    figures.samples_rejected = rejected["total"].get<double>();
  return figures;
}

std::string runStartLine(const common::Scenario& scenario, int domain, bool in_process, const HostPlan& hosts) {
  std::ostringstream out;
  out << "wsntrack: " << scenario.name << " (seed " << scenario.run.seed << ", " << scenario.run.ticks << " ticks) on "
      << scenario.run.node_processes << " node tiles, " << scenario.supernodes.size() << " supernodes, engine "
      << scenario.tracker.engine << ", domain " << domain << (in_process ? ", in-process" : "")
      << (scenario.run.security == common::RunSecurity::kOn
              ? (scenario.run.message_protection == common::MessageProtection::kSign ? ", DDS Security (signed)"
                                                                                    : ", DDS Security (encrypted)")
              : ", DDS Security off");
  if (hosts.multiHost()) {
    out << ", over " << hosts.hosts().size() << " hosts (";
    for (std::size_t h = 0; h < hosts.hosts().size(); ++h)
      out << (h == 0 ? "" : ", ") << hosts.hosts()[h].name << " " << hosts.hosts()[h].address;
    out << ")";
  }
  out << "\n";
  return out.str();
}

std::string runSummary(const std::string& run_dir, const RunFigures& f, const ClusterResult& result, bool in_process,
                       const std::optional<PlotOutcome>& plots) {
  std::ostringstream out;
  out << "\nRun directory: " << run_dir << "\n";
  std::set<std::string> hosts;
  for (const auto& outcome : result.outcomes)
    if (!outcome.host.empty()) hosts.insert(outcome.host);
  row(out, "mode", in_process        ? "in-process (threads over DDS)"
                   : hosts.size() > 1 ? "multi-process over DDS, over " + std::to_string(hosts.size()) + " hosts"
                                      : "multi-process over DDS");
  row(out, "targets (truth)", show(f.truth_targets, 0));
  row(out, "tracks (global ids)", show(f.track_ids, 0));
  row(out, "eps_K  (Oh eq. 9)", show(f.eps_k, 4));
  row(out, "eps_X gated (Oh eq. 10)", show(f.eps_x_gated, 4));
  row(out, "OSPA (mean)", show(f.ospa_mean, 4));
  row(out, "eps_K  settled", show(f.settled_eps_k, 4));
  row(out, "OSPA settled (mean)", show(f.settled_ospa_mean, 4));
  row(out, "reports sent", show(f.reports_sent, 0));
  row(out, "reports lost", show(f.reports_lost, 0));
  row(out, "reports delayed", show(f.reports_delayed, 0));
  row(out, "reports unreachable", show(f.reports_unreachable, 0));
  if (f.reports_lost_dead_supernode) row(out, "lost to dead supernodes", show(f.reports_lost_dead_supernode, 0));
  for (const auto& fault : f.faults) row(out, "fault", fault);
  row(out, "dropped (older than ws)", show(f.dropped_stale, 0));
  if (f.samples_rejected && *f.samples_rejected > 0)
    row(out, "samples rejected", show(f.samples_rejected, 0) + " (by topic and reason: rejected.json)");
  if (result.first_tick_s > 0.0) row(out, "start-up (to tick 1)", show(result.first_tick_s, 3) + " s");
  row(out, "wall time (tick loop)", show(f.wall_s, 3) + " s");
  row(out, "ticks/s (tick loop)", show(f.ticks_per_s, 1));
  row(out, "wall time (all)", show(result.wall_s, 3) + " s");
  if (in_process) {
    row(out, "peak RSS (whole process)", show(mib(result.in_process_peak_rss_kb), 1) + " MiB");
  } else {
    out << "  peak RSS per process (MiB):";
    for (const auto& outcome : result.outcomes)
      out << " " << outcome.name << (outcome.host.empty() ? "" : "@" + outcome.host) << " "
          << show(mib(outcome.peak_rss_kb), 1) << ";";
    out << "\n";
  }
  if (plots) {
    const bool drawn = plots->status == PlotOutcome::Status::kDrawn;
    row(out, "plots", drawn ? plots->message + " (" + show(plots->seconds, 1) + " s)" : "none: " + plots->message);
  }
  return out.str();
}

std::string signalName(int signal_number) {
  // A table rather than strsignal (a sentence, localised) or sigabbrev_np (glibc 2.32+ only).
  static const std::map<int, const char*> names = {
      {SIGHUP, "SIGHUP"},   {SIGINT, "SIGINT"},   {SIGQUIT, "SIGQUIT"}, {SIGILL, "SIGILL"},   {SIGTRAP, "SIGTRAP"},
      {SIGABRT, "SIGABRT"}, {SIGBUS, "SIGBUS"},   {SIGFPE, "SIGFPE"},   {SIGKILL, "SIGKILL"}, {SIGUSR1, "SIGUSR1"},
      {SIGSEGV, "SIGSEGV"}, {SIGUSR2, "SIGUSR2"}, {SIGPIPE, "SIGPIPE"}, {SIGALRM, "SIGALRM"}, {SIGTERM, "SIGTERM"},
      {SIGXCPU, "SIGXCPU"}, {SIGXFSZ, "SIGXFSZ"}, {SIGSYS, "SIGSYS"}};
  const auto found = names.find(signal_number);
  return found != names.end() ? found->second : "signal " + std::to_string(signal_number);
}

std::string exitDescription(const RoleOutcome& outcome) {
  if (outcome.signal != 0) return "killed by " + signalName(outcome.signal);
  return "exited with code " + std::to_string(outcome.exit_code);
}

std::string runFailure(const ClusterResult& result) {
  std::ostringstream out;
  if (result.interrupted_by != 0) {
    // Every process was told to stop; listing their exit codes would read like a row of crashes.
    out << "wsntrack run: " << result.failure << " (exit status " << runExitStatus(result) << ")\n";
    return out.str();
  }
  out << "wsntrack run: FAILED: " << result.failure << "\n";
  for (const auto& outcome : result.outcomes) {
    if (outcome.exit_code == 0) continue;
    if (outcome.message == kStoppedByLauncher) {
      out << "  " << outcome.name << ": " << kStoppedByLauncher << " (exit " << outcome.exit_code << ")\n";
      continue;
    }
    out << "  " << outcome.name << ": " << (outcome.signal != 0 ? exitDescription(outcome) + ", " : "") << "exit "
        << outcome.exit_code << (outcome.message.empty() ? "" : " (" + outcome.message + ")") << "\n";
  }
  return out.str();
}

}  // namespace wsn::launcher

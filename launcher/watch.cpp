#include "launcher/watch.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "common/dds/codec.hpp"
#include "common/dds/cyclone_config.hpp"
#include "common/dds/entity.hpp"
#include "common/dds/process_main.hpp"
#include "common/dds/role_runtime.hpp"
#include "common/dds/security.hpp"
#include "common/printable.hpp"
#include "launcher/run_credentials.hpp"
#include "launcher/run_description.hpp"
#include "launcher/run_directory.hpp"
#include "launcher/map_server.hpp"
#include "launcher/watch_live_map.hpp"
#include "launcher/watch_state.hpp"
#include "wsntrack.h"

namespace wsn::launcher {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using Seconds = std::chrono::duration<double>;

std::atomic<bool> g_interrupted{false};
extern "C" void onWatchInterrupt(int) { g_interrupted.store(true); }

struct WatchOptions {
  std::string run_dir;
  double timeout_s = 60;
  bool plain = false;
  double max_fps = 20;
  /// --http: where the browser map is served ([ADDR:]PORT parsed); none without it.
  std::optional<std::pair<std::string, int>> http;
};

bool interrupted() { return g_interrupted.load(); }

std::string hex(std::uint64_t value) {
  std::ostringstream out;
  out << std::hex << value;
  return out.str();
}

/// A status sample's state, as the watch's state machine knows it.
ProcessState processState(wsn_msg_ProcessState state) {
  switch (state) {
    case wsn_msg_STARTING: return ProcessState::kStarting;
    case wsn_msg_READY: return ProcessState::kReady;
    case wsn_msg_RUNNING: return ProcessState::kRunning;
    case wsn_msg_DONE: return ProcessState::kDone;
    case wsn_msg_FAILED: return ProcessState::kFailed;
    case wsn_msg_FAULTED: return ProcessState::kFaulted;
  }
  return ProcessState::kStarting;
}

/// Whether the launcher that wrote run.json still runs: its pid is alive and still a wsntrack
/// (a pid reused by another program does not count).
bool launcherAlive(long long pid) {
  if (pid <= 0) return false;
  std::ifstream comm("/proc/" + std::to_string(pid) + "/comm");
  std::string name;
  return comm && std::getline(comm, name) && name == "wsntrack";
}

int terminalRows() {
  winsize size{};
  if (::ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_row > 0) return size.ws_row;
  return 24;
}

/// Hides the cursor while a terminal view is up; shows it again however the view ends.
class CursorGuard {
 public:
  explicit CursorGuard(bool tty) : tty_(tty) {
    if (tty_) std::fputs("\x1b[?25l", stdout);
  }
  ~CursorGuard() {
    if (tty_) std::fputs("\x1b[?25h", stdout);
    std::fflush(stdout);
  }
  CursorGuard(const CursorGuard&) = delete;
  CursorGuard& operator=(const CursorGuard&) = delete;

 private:
  bool tty_;
};

/// Why a run directory cannot be joined (yet).
enum class RunPresence { kLive, kNotRunning, kNotARun };

class Watcher {
 public:
  Watcher(WatchOptions options, bool tty) : options_(std::move(options)), tty_(tty) {}

  int run() {
    const auto started = Clock::now();
    const auto deadline = started + std::chrono::duration_cast<Clock::duration>(Seconds(options_.timeout_s));
    if (options_.http && finishedRunThere()) {  // the map scrubs a finished run from its files
      try {
        serveFinishedRun(options_.run_dir, options_.http->first, options_.http->second, interrupted);
      } catch (const std::runtime_error& error) {
        std::cerr << "wsntrack watch: " << error.what() << "\n";
        return kWatchUsage;
      }
      return kWatchFinished;
    }
    if (const auto code = waitForLiveRun(deadline)) return *code;
    return watch(deadline);
  }

 private:
  // ---- finding the run -------------------------------------------------------------------

  /// Whether RUN_DIR holds a run that finished: its metrics.json written and its launcher gone.
  bool finishedRunThere() {
    std::error_code error;
    if (!fs::exists(options_.run_dir + "/metrics.json", error) || !fs::exists(options_.run_dir + "/run.json", error))
      return false;
    try {
      return !launcherAlive(readRunDescription(options_.run_dir).launcher_pid);
    } catch (const std::exception&) {
      return false;
    }
  }

  RunPresence presence(std::string& why) {
    const std::string dir = options_.run_dir;
    std::error_code error;
    // A missing or empty directory is where a run is about to start ('wsntrack run --out DIR' in
    // another terminal may not have made it yet): wait for it rather than race the launcher.
    if (!fs::exists(dir, error)) {
      why = dir + ": no such directory (yet)";
      return RunPresence::kNotRunning;
    }
    if (!fs::is_directory(dir, error)) {
      why = dir + ": not a directory";
      return RunPresence::kNotARun;
    }
    if (fs::is_empty(dir, error) && !error) {
      why = dir + " is empty: no run has started there yet";
      return RunPresence::kNotRunning;
    }
    if (!fs::exists(dir + "/run.json", error)) {
      // A launcher takes the directory's lock, then writes run.json and the run's inputs.
      if (fs::exists(dir + "/cyclonedds.xml", error) || fs::exists(dir + "/scenario.yaml", error) ||
          fs::exists(dir + "/" + kRunLockFile, error)) {
        why = "its run.json is not there yet (or it was written by an older wsntrack)";
        return RunPresence::kNotRunning;
      }
      why = dir + ": not a wsntrack run directory (no run.json; 'wsntrack run --out DIR' writes one)";
      return RunPresence::kNotARun;
    }
    try {
      run_ = readRunDescription(dir);
    } catch (const std::exception& e) {
      why = e.what();
      return RunPresence::kNotARun;
    }
    if (!launcherAlive(run_.launcher_pid)) {
      why = "its last run (" + hex(run_.identity.run_id) + ") is not running: " +
            (fs::exists(dir + "/metrics.json", error) ? "it finished (results in metrics.json)"
                                                      : "its launcher (pid " + std::to_string(run_.launcher_pid) +
                                                            ") exited before the run finished");
      return RunPresence::kNotRunning;
    }
    if (fs::exists(dir + "/metrics.json", error)) {
      why = "its run (" + hex(run_.identity.run_id) + ") has already finished (results in metrics.json)";
      return RunPresence::kNotRunning;
    }
    return RunPresence::kLive;
  }

  /// Waits until RUN_DIR holds a live run (one may be about to start there, --overwrite); the
  /// exit code when there is none to join.
  std::optional<int> waitForLiveRun(Clock::time_point deadline) {
    bool told = false;
    std::string why;
    while (true) {
      const auto found = presence(why);
      if (found == RunPresence::kLive) return std::nullopt;
      if (found == RunPresence::kNotARun) {
        std::cerr << "wsntrack watch: " << why << "\n";
        return kWatchUsage;
      }
      if (Clock::now() >= deadline) {
        std::cerr << "wsntrack watch: no run started in " << options_.run_dir << " within " << options_.timeout_s
                  << " s: " << why << "\n";
        return kWatchFailed;
      }
      if (!told) {
        std::cerr << "wsntrack watch: waiting up to " << options_.timeout_s << " s for a run to start in "
                  << options_.run_dir << " (" << why << ")\n";
        told = true;
      }
      if (g_interrupted.load()) return kWatchInterrupted;
      ::usleep(200000);
    }
  }

  // ---- joining it --------------------------------------------------------------------------

  /// A Cyclone domain on the first free viewer slot of the run. Ports are probed first so that
  /// Cyclone does not log a failure; a slot taken in between (two viewers starting at once) is
  /// caught by the domain creation failing, and the next slot is tried.
  std::optional<dds::Domain> joinDomain(const std::string& config) {
    for (int slot = 0; slot < run_.viewer_slots; ++slot) {
      const int index = run_.first_viewer_index + slot;
      if (!dds::cyclonePortsFree(run_.identity.domain, index)) continue;
      try {
        dds::Domain domain(static_cast<dds_domainid_t>(run_.identity.domain), dds::cycloneConfigFor(config, index, dds::kViewerIdentity));
        participant_index_ = index;
        return domain;
      } catch (const dds::DdsError&) {
      }
    }
    return std::nullopt;
  }

  int watch(Clock::time_point start_deadline) {
    const std::string config = dds::readConfigTemplate(options_.run_dir);
    if (const auto address = dds::cycloneInterfaceAddress(config); !address.empty() && !dds::hasLocalAddress(address)) {
      std::cerr << "wsntrack watch: this run's launcher host uses address " << address
                << ", which no interface here has: watch from that host (in its network namespace, if it is one)\n";
      return kWatchFailed;
    }
    // A secured run's credentials go when it ends: say so rather than that every slot is taken.
    if (config.find("<Security>") != std::string::npos &&
        !std::filesystem::exists(std::filesystem::path(options_.run_dir) / kCredentialsDirectory)) {
      std::cerr << "wsntrack watch: " << options_.run_dir << "/" << kCredentialsDirectory
                << " is gone: the run has ended (a secured run's credentials are removed at its end)\n";
      return kWatchFailed;
    }
    auto domain = joinDomain(config);
    if (!domain) {
      std::cerr << "wsntrack watch: every viewer slot of this run (participant indices " << run_.first_viewer_index
                << ".." << run_.first_viewer_index + run_.viewer_slots - 1
                << ") is taken: close another viewer of the run first\n";
      return kWatchFailed;
    }
    dds::Participant participant(domain->id());
    // The viewer's topics only: under DDS Security its identity may create no others.
    dds::Topic<wsn_msg_ProcessStatus> status_topic(participant, dds::topic_names::kProcessStatus);
    dds::Topic<wsn_msg_GlobalTrackBatch> track_topic(participant, dds::topic_names::kGlobalTrackBatch);
    dds::Topic<wsn_msg_TickMetrics> metrics_topic(participant, dds::topic_names::kTickMetrics);
    // Reliable readers, so that no tick is skipped for a lost packet; they never hold the run
    // back, since Cyclone acknowledges on arrival, and they are not counted by its start barrier.
    dds::Reader<wsn_msg_ProcessStatus> status_reader(participant, status_topic,
                              dds::Qos::lastValueTransientLocal(dds::Endpoint::kViewer));
    dds::Reader<wsn_msg_GlobalTrackBatch> track_reader(participant, track_topic, dds::Qos::reliableKeepAll(dds::Endpoint::kViewer));
    dds::Reader<wsn_msg_TickMetrics> metrics_reader(participant, metrics_topic, dds::Qos::reliableKeepAll(dds::Endpoint::kViewer));
    dds::ReadCondition status_ready(status_reader), tracks_ready(track_reader), metrics_ready(metrics_reader);
    dds::WaitSet waitset(participant);
    waitset.attach(status_ready.handle(), 0);
    waitset.attach(tracks_ready.handle(), 1);
    waitset.attach(metrics_ready.handle(), 2);
    std::unique_ptr<LiveMap> map;
    try {
      if (options_.http)
        map = std::make_unique<LiveMap>(options_.run_dir, options_.http->first, options_.http->second, participant,
                                        waitset, 3);
    } catch (const std::runtime_error& error) {  // the address is in use or not this host's: an option's fault
      std::cerr << "wsntrack watch: " << error.what() << "\n";
      return kWatchUsage;
    }

    const CursorGuard cursor(tty_);
    if (!tty_)
      std::cout << "watching " << run_.scenario << " run " << hex(run_.identity.run_id) << " (" << run_.ticks
                << " ticks, domain " << run_.identity.domain << ", viewer participant " << participant_index_
                << ") in " << options_.run_dir << "\n"
                << std::flush;

    WatchTiming timing;
    timing.min_frame_gap = std::chrono::duration_cast<Clock::duration>(Seconds(1.0 / options_.max_fps));
    timing.timeout = std::chrono::duration_cast<Clock::duration>(Seconds(options_.timeout_s));
    WatchState state(run_, options_.run_dir, timing, Clock::now(), start_deadline);
    told_waiting_ = false;

    while (true) {
      if (g_interrupted.load()) {
        finishLine("interrupted; the run goes on");
        return kWatchInterrupted;
      }
      waitset.wait(state.nextWait(Clock::now()));
      const auto now = Clock::now();

      status_reader.take([&](const wsn_msg_ProcessStatus& s) {
        if (s.run_id != run_.identity.run_id) return;
        state.onStatus({common::printable(s.role), s.index, processState(s.state), s.tick, common::printable(s.message)}, now);
      });
      track_reader.take([&](const wsn_msg_GlobalTrackBatch& batch) {
        if (batch.run_id != run_.identity.run_id) return;
        auto tracks = dds::decode(batch.tracks);
        if (map) map->onTracks(batch.tick, tracks);
        state.onTracks(batch.tick, std::move(tracks), now);
      });
      metrics_reader.take([&](const wsn_msg_TickMetrics& m) {
        if (m.run_id != run_.identity.run_id) return;
        TickScores scores;
        for (std::uint32_t i = 0; i < m.values._length; ++i) scores[m.values._buffer[i].name] = m.values._buffer[i].value;
        state.onMetrics(m.tick, scores);
        if (map) map->onMetrics(m.tick, scores);
      });
      if (map) map->poll(run_.identity.run_id);

      const auto step = state.step(now, metrics_reader.matchedWriters() > 0, static_cast<bool>(std::cout),
                                   [&] { return launcherAlive(run_.launcher_pid); });
      if (step.frame) drawTick(state, *step.frame);
      if (step.draw_waiting) drawWaiting(state);
      if (step.end) return map ? keepServing(*map, *step.end) : finish(*step.end);
    }
  }

  /// The run ended with a map up: the page says how, and scrubs the run until Ctrl-C or SIGTERM.
  int keepServing(LiveMap& map, const WatchEnd& end) {
    map.ended(end.exit_code == kWatchFinished ? "finished" : "failed", end.text.empty() ? "the run ended" : end.text);
    const int code = finish(end);
    std::cerr << "wsntrack watch: the map still shows the run at " << map.url() << "; Ctrl-C stops it\n" << std::flush;
    while (!g_interrupted.load()) ::usleep(200000);
    return code;
  }

  // ---- drawing -----------------------------------------------------------------------------

  void drawWaiting(const WatchState& state) {
    if (tty_) {
      std::cout << "\x1b[H\x1b[2J" << watchTitle(run_) << "\n\n  " << state.waitingLine() << "\x1b[K\n\n  Ctrl-C quits.\x1b[J"
                << std::flush;
    } else if (!told_waiting_) {
      std::cerr << "wsntrack watch: " << state.waitingLine() << "\n";
      told_waiting_ = true;
    }
  }

  void drawTick(const WatchState& state, const WatchFrame& frame) {
    const std::string head_line = frameHeadLine(frame, run_.ticks);
    const std::vector<std::string> rows = frameRows(frame);
    if (!tty_) {
      std::cout << head_line << "\n";
      for (const auto& row : rows) std::cout << row << "\n";
      std::cout << "\n" << std::flush;
      return;
    }
    // Home and overwrite line by line (clearing each line's rest) rather than clearing the
    // screen first: no flicker between frames.
    std::ostringstream screen;
    screen << "\x1b[H" << watchTitle(run_) << "\x1b[K\n" << state.processSummary() << "\x1b[K\n\x1b[K\n";
    const int bar_width = 40;
    const int filled = static_cast<int>(std::lround(bar_width * static_cast<double>(frame.tick) / run_.ticks));
    screen << "  [" << std::string(static_cast<std::size_t>(filled), '#')
           << std::string(static_cast<std::size_t>(bar_width - filled), '.') << "]\x1b[K\n";
    screen << "  " << head_line << "\x1b[K\n\x1b[K\n";
    const int fixed_lines = 8;  // everything above, the "more" line and the footer
    const auto room = static_cast<std::size_t>(std::max(2, terminalRows() - fixed_lines));
    const std::size_t shown = std::min(rows.size(), room);
    for (std::size_t i = 0; i < shown; ++i) screen << rows[i] << "\x1b[K\n";
    if (shown < rows.size()) screen << "  ... " << rows.size() - shown << " more tracks\x1b[K\n";
    screen << "\x1b[K\n  Ctrl-C quits; the run goes on.\x1b[J";
    std::cout << screen.str() << std::flush;
  }

  /// The watch's last words: an error on stderr, or a line below the last frame.
  int finish(const WatchEnd& end) {
    if (end.error && !end.text.empty()) std::cerr << "wsntrack watch: " << end.text << "\n";
    if (!end.error) finishLine(end.text);
    return end.exit_code;
  }

  /// The last word, below the last frame.
  void finishLine(const std::string& text) {
    if (tty_) std::cout << "\n\n";
    std::cout << text << "\n" << std::flush;
  }

  WatchOptions options_;
  bool tty_;
  RunDescription run_;
  int participant_index_ = -1;
  bool told_waiting_ = false;
};

constexpr const char* kWatchHelp =
    "Usage: wsntrack watch RUN_DIR [--timeout S] [--plain] [--max-fps N] [--http [ADDR:]PORT]\n\n"
    "Live view of a cluster started by 'wsntrack run --out RUN_DIR' (from another terminal):\n"
    "it joins the run's DDS domain as a viewer and, every tick, shows the run's progress (tick\n"
    "t/T), the aggregator's per-tick metrics (K* truth targets, K tracks, OSPA, GOSPA, running\n"
    "epsK and mean OSPA; 'n/a' when the aggregator does not publish TickMetrics) and its global\n"
    "tracks (id as supernode:serial or S:tTsK, x, y, vx, vy, speed). To follow a run at a human pace,\n"
    "start it with --tick-interval, e.g. 'wsntrack run SCENARIO --out runs/demo --tick-interval\n"
    "0.2' and then 'wsntrack watch runs/demo'.\n\n"
    "On a terminal the view is redrawn in place (ANSI); otherwise, or with --plain, every frame is\n"
    "printed as lines: 'tick t/T  K*=.. K=.. OSPA=.. GOSPA=.. epsK=.. meanOSPA=..', a header and\n"
    "one row per track, then an empty line. Frames are drawn at most --max-fps times a second;\n"
    "ticks in between are skipped, the last tick is always drawn.\n\n"
    "RUN_DIR's run.json says how to join (run id, domain, the participant indices kept for\n"
    "viewers: up to 4 viewers at a time). The watch waits up to --timeout seconds for a run to\n"
    "start there (RUN_DIR may not exist yet) and then for each sign of progress; it never slows\n"
    "the run down or changes it.\n\n"
    "With --http [ADDR:]PORT the watch also serves a map of the run to a browser, at\n"
    "http://127.0.0.1:PORT/ (ADDR: another address of this host to listen on; PORT 0: any free port,\n"
    "printed): the sensor field, the supernodes and their tracking groups, each tick's truth,\n"
    "delivered reports and tracks with their ids and 2-sigma ellipses, and the per-tick metrics,\n"
    "updated as the run goes (Server-Sent Events). It is read-only. The page answers once the run has\n"
    "started (the field is the run's scenario). After the run ends the page can scrub it (slider,\n"
    "arrow keys) until Ctrl-C or SIGTERM, and the exit status is then the run's (0 finished, 1\n"
    "failed), not 130. On a RUN_DIR whose run has already finished, the map of that run is served\n"
    "from its files (a failed run is waited past, as without --http). An address that cannot be\n"
    "listened on is exit status 2.\n\n"
    "Exit status: 0 when the run finished (the aggregator reported DONE or the last tick was shown);\n"
    "1 when the run failed, its launcher exited early, no run started or nothing happened within\n"
    "--timeout; 2 for bad options or when RUN_DIR is not a run directory; 130 on Ctrl-C.\n\n";

}  // namespace

int commandWatch(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  WatchOptions options;
  po::options_description described("Options");
  described.add_options()("help,h", "show this help")(
      "timeout", po::value(&options.timeout_s)->default_value(60),
      "seconds to wait for the run to start, and then at most between two signs of progress")(
      "plain", "line-oriented frames even on a terminal (the default when stdout is not one)")(
      "max-fps", po::value(&options.max_fps)->default_value(20), "most frames drawn per second")(
      "http", po::value<std::string>()->value_name("[ADDR:]PORT"),
      "also serve a live map of the run to a browser (127.0.0.1 unless ADDR; PORT 0: any free port)")(
      "run-dir", po::value(&options.run_dir), "run directory of the run to watch");
  po::positional_options_description positional;
  positional.add("run-dir", 1);
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(described).positional(positional).run(), vm);
  po::notify(vm);
  if (vm.count("help") || options.run_dir.empty()) {
    (vm.count("help") ? std::cout : std::cerr) << kWatchHelp << described << "\n";
    return vm.count("help") ? kWatchFinished : kWatchUsage;
  }
  if (!std::isfinite(options.timeout_s) || options.timeout_s <= 0 || options.timeout_s > 604800) {
    std::cerr << "wsntrack watch: --timeout must be in (0, 604800] seconds, got " << options.timeout_s << "\n";
    return kWatchUsage;
  }
  if (!std::isfinite(options.max_fps) || options.max_fps < 0.1 || options.max_fps > 1000) {
    std::cerr << "wsntrack watch: --max-fps must be in [0.1, 1000], got " << options.max_fps << "\n";
    return kWatchUsage;
  }
  if (vm.count("http")) {
    try {
      options.http = parseHttpAddress(vm["http"].as<std::string>());
    } catch (const std::invalid_argument& error) {
      std::cerr << "wsntrack watch: " << error.what() << "\n";
      return kWatchUsage;
    }
  }
  options.plain = options.plain || vm.count("plain") != 0;
  const bool tty = !options.plain && ::isatty(STDOUT_FILENO) != 0;
  std::signal(SIGINT, onWatchInterrupt);
  std::signal(SIGTERM, onWatchInterrupt);
  // A reader of a pipe that went away must not kill the watch in the middle of a DDS call.
  std::signal(SIGPIPE, SIG_IGN);
  try {
    return Watcher(options, tty).run();
  } catch (const std::exception& error) {
    std::cerr << "wsntrack watch: " << error.what() << "\n";
    return kWatchFailed;
  }
}

}  // namespace wsn::launcher

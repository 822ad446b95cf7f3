// The state machine of `wsntrack watch` without DDS or a terminal (processes, ticks to draw, when the
// run is finished, failed or dead); watch.cpp feeds it the samples it takes and draws what it says.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/messages.hpp"
#include "launcher/run_description.hpp"

namespace wsn::launcher {

/// A role instance's state on the status topic (the IDL's ProcessState, without DDS).
/// kFaulted: killed or paused by the scenario's faults, as the run meant.
enum class ProcessState { kStarting, kReady, kRunning, kDone, kFailed, kFaulted };

/// One status sample of the run.
struct ProcessReport {
  std::string role;  ///< "node", "network", "supernode", "aggregator"
  std::uint32_t index = 0;
  ProcessState state = ProcessState::kStarting;
  std::int32_t tick = 0;
  std::string message;
};

/// What the aggregator's TickMetrics say about one tick: every metric's live values, by name
/// (aggregator/metric/metric.hpp); a name the aggregator did not publish shows as n/a.
using TickScores = std::map<std::string, double>;

/// One tick to draw: its global tracks in id order and its scores, when they came.
struct WatchFrame {
  std::int32_t tick = 0;
  std::vector<common::TrackEstimate> tracks;
  std::optional<TickScores> scores;
};

/// How a watch ends: its exit code and its last words.
struct WatchEnd {
  int exit_code = 0;
  /// An error goes to stderr after "wsntrack watch: "; otherwise the text is the closing line
  /// under the last frame, on stdout. Empty: nothing to say (nobody reads stdout any more).
  bool error = false;
  std::string text;
};

/// What to do after one wake-up, in this order: draw the frame, redraw the waiting screen, end.
struct WatchStep {
  std::optional<WatchFrame> frame;
  bool draw_waiting = false;  ///< no tick drawn yet: show who is up
  std::optional<WatchEnd> end;
};

/// The watch's clocks; the first two come from its options.
struct WatchTiming {
  using Duration = std::chrono::steady_clock::duration;
  Duration min_frame_gap = std::chrono::milliseconds(50);  ///< 1 / --max-fps
  Duration timeout = std::chrono::seconds(60);             ///< --timeout: most time without progress
  /// After the aggregator's DONE, its last batch may still be on its way (another topic).
  Duration end_grace = std::chrono::seconds(2);
  /// TickMetrics of tick t follow its batch at once; a frame waits this long for them at most.
  Duration metrics_wait = std::chrono::milliseconds(300);
  /// The launcher stops every process after the first failure, and they report FAILED too
  /// ("stopped on request"): a moment's wait collects the cause along with them.
  Duration failure_grace = std::chrono::milliseconds(500);
  Duration waiting_redraw = std::chrono::milliseconds(500);
  Duration launcher_check = std::chrono::milliseconds(500);
};

/// The watch of one run, from joining it to its end.
class WatchState {
 public:
  using Clock = std::chrono::steady_clock;

  /// `start_deadline`: by when a first process must show up.
  WatchState(RunDescription run, std::string run_dir, WatchTiming timing, Clock::time_point now,
             Clock::time_point start_deadline);

  void onStatus(const ProcessReport& report, Clock::time_point now);
  /// Global tracks of `tick`; a tick already drawn is ignored.
  void onTracks(std::int32_t tick, std::vector<common::TrackEstimate> tracks, Clock::time_point now);
  /// Scores of `tick`; a tick already drawn is ignored.
  void onMetrics(std::int32_t tick, const TickScores& scores);

  /// The decisions after the samples of one wake-up. `metrics_published`: some TickMetrics writer
  /// is matched (else no tick waits for its scores); `stdout_ok`: someone still reads the frames;
  /// `launcher_alive` is asked at most every timing.launcher_check while the run is neither done
  /// nor failed.
  WatchStep step(Clock::time_point now, bool metrics_published, bool stdout_ok,
                 const std::function<bool()>& launcher_alive);

  /// How long the next wait for samples may last: a frame held back by the rate limit is drawn as
  /// soon as it is allowed, not a wake-up later.
  std::chrono::milliseconds nextWait(Clock::time_point now) const;

  const RunDescription& run() const { return run_; }
  std::int32_t drawnTick() const { return drawn_tick_; }
  bool started() const { return started_; }
  /// "N/P processes up (r ready, u running, d done)".
  std::string processSummary() const;
  /// The waiting screen's line: who is up, before the first tick or before anyone.
  std::string waitingLine() const;

 private:
  struct Pending {
    std::vector<common::TrackEstimate> tracks;
    Clock::time_point arrived;
  };

  std::optional<std::int32_t> readyTick(Clock::time_point now, bool metrics_published) const;
  WatchFrame takeFrame(std::int32_t tick);
  std::optional<WatchEnd> endOf(Clock::time_point now, const std::function<bool()>& launcher_alive);
  std::string seen() const;  ///< "N/T", the last tick shown of T

  RunDescription run_;
  std::string run_dir_;
  WatchTiming timing_;
  Clock::time_point start_deadline_;
  std::map<std::pair<std::string, std::uint32_t>, ProcessState> processes_;
  std::map<std::int32_t, Pending> pending_;
  std::map<std::int32_t, TickScores> scores_;
  std::vector<std::string> failures_;
  std::int32_t drawn_tick_ = 0;
  std::int32_t done_tick_ = 0;
  bool started_ = false;
  bool held_back_ = false;
  Clock::time_point last_progress_;
  Clock::time_point last_draw_{};
  Clock::time_point last_waiting_draw_{};
  Clock::time_point last_launcher_check_;
  std::optional<Clock::time_point> done_at_;
  std::optional<Clock::time_point> failed_at_;
};

/// The title of the terminal view: scenario, run id, domain and the pacing.
std::string watchTitle(const RunDescription& run);

/// A frame's first line: "tick t/T  K*=.. K=.. OSPA=.. GOSPA=.. epsK=.. meanOSPA=.." ('n/a' without scores).
std::string frameHeadLine(const WatchFrame& frame, std::int32_t ticks);

/// A frame's table: a header, then one row per track (id, x, y, vx, vy, speed).
std::vector<std::string> frameRows(const WatchFrame& frame);

}  // namespace wsn::launcher

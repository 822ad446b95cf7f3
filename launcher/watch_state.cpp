#include "launcher/watch_state.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/class_evidence.hpp"
#include "launcher/watch.hpp"

namespace wsn::launcher {
namespace {

std::string hex(std::uint64_t value) {
  std::ostringstream out;
  out << std::hex << value;
  return out.str();
}

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

/// Seconds as the user wrote them in --timeout (60, 0.5).
std::string seconds(WatchTiming::Duration duration) {
  std::ostringstream out;
  out << std::chrono::duration<double>(duration).count();
  return out.str();
}

}  // namespace

WatchState::WatchState(RunDescription run, std::string run_dir, WatchTiming timing, Clock::time_point now,
                       Clock::time_point start_deadline)
    : run_(std::move(run)),
      run_dir_(std::move(run_dir)),
      timing_(timing),
      start_deadline_(start_deadline),
      last_progress_(now),
      last_launcher_check_(now) {}

void WatchState::onStatus(const ProcessReport& report, Clock::time_point now) {
  started_ = true;
  last_progress_ = now;
  processes_[{report.role, report.index}] = report.state;
  if (report.state == ProcessState::kFailed) {
    failures_.push_back(report.role + " " + std::to_string(report.index) + ": " + report.message);
    if (!failed_at_) failed_at_ = now;
  }
  if (report.role == "aggregator" && report.state == ProcessState::kDone && !done_at_) {
    done_at_ = now;
    done_tick_ = report.tick;
  }
}

void WatchState::onTracks(std::int32_t tick, std::vector<common::TrackEstimate> tracks, Clock::time_point now) {
  if (tick <= drawn_tick_) return;
  started_ = true;
  last_progress_ = now;
  auto& pending = pending_[tick];
  pending.arrived = now;
  pending.tracks = std::move(tracks);
}

void WatchState::onMetrics(std::int32_t tick, const TickScores& scores) {
  if (tick <= drawn_tick_) return;
  scores_[tick] = scores;
}

WatchStep WatchState::step(Clock::time_point now, bool metrics_published, bool stdout_ok,
                           const std::function<bool()>& launcher_alive) {
  WatchStep step;
  if (failed_at_ && now - *failed_at_ >= timing_.failure_grace) {
    if (!pending_.empty()) step.frame = takeFrame(pending_.rbegin()->first);
    std::string text = "the run FAILED at tick " + seen() + ":\n";
    for (const auto& failure : failures_) text += "  " + failure + "\n";
    text += "  (the launcher's output and " + run_dir_ + "/logs/ say why)";
    step.end = WatchEnd{kWatchFailed, true, text};
    return step;
  }
  if (!stdout_ok) {
    step.end = WatchEnd{kWatchFailed, true, ""};
    return step;
  }

  const auto ready = readyTick(now, metrics_published);
  held_back_ = false;
  if (ready && (*ready == run_.ticks || now - last_draw_ >= timing_.min_frame_gap)) {
    step.frame = takeFrame(*ready);
    last_draw_ = now;
  } else if (ready) {
    held_back_ = true;
  }
  if (drawn_tick_ >= run_.ticks) {
    step.end = WatchEnd{kWatchFinished, false, "the run finished: tick " + seen() + " shown"};
    return step;
  }
  if (done_at_ && pending_.empty() && now - *done_at_ >= timing_.end_grace) {
    step.end = WatchEnd{kWatchFinished, false,
                        "the run finished (aggregator DONE at tick " + std::to_string(done_tick_) + "); last tick shown: " +
                            (drawn_tick_ > 0 ? std::to_string(drawn_tick_) : std::string("none"))};
    return step;
  }
  if (drawn_tick_ == 0 && now - last_waiting_draw_ >= timing_.waiting_redraw) {
    step.draw_waiting = true;
    last_waiting_draw_ = now;
  }
  step.end = endOf(now, launcher_alive);
  return step;
}

std::optional<WatchEnd> WatchState::endOf(Clock::time_point now, const std::function<bool()>& launcher_alive) {
  if (!started_ && now >= start_deadline_)
    return WatchEnd{kWatchFailed, true,
                    "no process of run " + hex(run_.identity.run_id) + " showed up within " + seconds(timing_.timeout) + " s"};
  if (started_ && now - last_progress_ >= timing_.timeout)
    return WatchEnd{kWatchFailed, true, "no progress for " + seconds(timing_.timeout) + " s (last tick seen " + seen() + ")"};
  if (now - last_launcher_check_ >= timing_.launcher_check) {
    last_launcher_check_ = now;
    if (!done_at_ && !failed_at_ && !launcher_alive())
      return WatchEnd{kWatchFailed, true,
                      "the run's launcher (pid " + std::to_string(run_.launcher_pid) +
                          ") exited before the run finished (last tick seen " + seen() + "); see " + run_dir_ + "/logs/"};
  }
  return std::nullopt;
}

std::optional<std::int32_t> WatchState::readyTick(Clock::time_point now, bool metrics_published) const {
  // The newest tick whose metrics are in, or will not come.
  for (auto it = pending_.rbegin(); it != pending_.rend(); ++it) {
    const bool newer_exists = it != pending_.rbegin();
    if (scores_.count(it->first) || !metrics_published || newer_exists || done_at_ ||
        now - it->second.arrived >= timing_.metrics_wait)
      return it->first;
  }
  return std::nullopt;
}

WatchFrame WatchState::takeFrame(std::int32_t tick) {
  WatchFrame frame;
  frame.tick = tick;
  frame.tracks = std::move(pending_[tick].tracks);
  std::sort(frame.tracks.begin(), frame.tracks.end(),
            [](const common::TrackEstimate& a, const common::TrackEstimate& b) { return a.track < b.track; });
  if (const auto found = scores_.find(tick); found != scores_.end()) frame.scores = found->second;
  // Older ticks not drawn yet are skipped for good: the view shows the newest.
  pending_.erase(pending_.begin(), pending_.upper_bound(tick));
  scores_.erase(scores_.begin(), scores_.upper_bound(tick));
  drawn_tick_ = tick;
  return frame;
}

std::chrono::milliseconds WatchState::nextWait(Clock::time_point now) const {
  const auto wait = std::chrono::milliseconds(50);
  if (!held_back_) return wait;
  return std::clamp(std::chrono::ceil<std::chrono::milliseconds>(last_draw_ + timing_.min_frame_gap - now),
                    std::chrono::milliseconds(0), wait);
}

std::string WatchState::seen() const { return std::to_string(drawn_tick_) + "/" + std::to_string(run_.ticks); }

std::string WatchState::processSummary() const {
  int ready = 0, running = 0, done = 0, faulted = 0;
  for (const auto& [key, state] : processes_) {
    if (state == ProcessState::kReady) ++ready;
    if (state == ProcessState::kRunning) ++running;
    if (state == ProcessState::kDone) ++done;
    if (state == ProcessState::kFaulted) ++faulted;
  }
  std::ostringstream out;
  out << processes_.size() << "/" << run_.processes << " processes up";
  if (ready + running + done > 0) out << " (" << ready << " ready, " << running << " running, " << done << " done";
  if (ready + running + done > 0 && faulted > 0) out << ", " << faulted << " faulted";
  if (ready + running + done > 0) out << ")";
  return out.str();
}

std::string WatchState::waitingLine() const {
  return std::string(started_ ? "waiting for the first tick: " : "waiting for the run to start: ") + processSummary();
}

std::string watchTitle(const RunDescription& run) {
  std::ostringstream out;
  out << "wsntrack watch  " << run.scenario << "  run " << hex(run.identity.run_id) << "  domain " << run.identity.domain;
  if (run.tick_interval_s > 0) out << "  paced " << fixed(run.tick_interval_s, 3) << " s/tick";
  return out.str();
}

std::string frameHeadLine(const WatchFrame& frame, std::int32_t ticks) {
  const auto metric = [](const std::string& name, const std::string& value) { return name + "=" + value; };
  const auto value = [&](const char* name, int decimals) -> std::string {
    if (!frame.scores) return "n/a";
    const auto it = frame.scores->find(name);
    if (it == frame.scores->end()) return "n/a";
    return decimals == 0 ? std::to_string(std::llround(it->second)) : fixed(it->second, decimals);
  };
  return "tick " + std::to_string(frame.tick) + "/" + std::to_string(ticks) + "  " +
         metric("K*", value("truth_targets", 0)) + " " + metric("K", std::to_string(frame.tracks.size())) + " " +
         metric("OSPA", value("ospa", 3)) + " " + metric("GOSPA", value("gospa", 3)) + " " +
         metric("epsK", value("eps_k_running", 4)) + " " + metric("meanOSPA", value("ospa_mean_running", 3));
}

std::vector<std::string> frameRows(const WatchFrame& frame) {
  // A class column only when the engine classifies, so that other runs' rows stay as they were.
  const bool classified = std::any_of(frame.tracks.begin(), frame.tracks.end(),
                                      [](const common::TrackEstimate& t) { return !t.class_probabilities.empty(); });
  std::vector<std::string> rows;
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, "  %-14s %9s %9s %8s %8s %7s", "track", "x", "y", "vx", "vy", "speed");
  rows.emplace_back(std::string(buffer) + (classified ? "  class" : ""));
  for (const auto& t : frame.tracks) {
    std::snprintf(buffer, sizeof buffer, "  %-14s %9.2f %9.2f %8.3f %8.3f %7.3f", common::track_id::label(t.track).c_str(), t.x,
                  t.y, t.vx, t.vy, std::hypot(t.vx, t.vy));
    std::string row = buffer;
    if (classified) {
      // name:probability, one field for readers that split on blanks; "-" without evidence.
      const common::DeclaredClass declared = common::declaredTrackClass(t.class_probabilities);
      row += declared.target_class == common::TargetClass::kUnknown
                 ? "  -"
                 : "  " + common::targetClassName(declared.target_class) + ":" + fixed(declared.probability, 2);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace wsn::launcher

// The state machine of `wsntrack watch` (launcher/watch_state.cpp) on hand-made samples and a
// hand-driven clock: who is up, which tick is drawn when, and how a run ends, fails or dies.
#include "launcher/watch_state.hpp"

#include <catch2/catch.hpp>

#include "launcher/watch.hpp"

namespace wsn::launcher {
namespace {

using Clock = WatchState::Clock;
using std::chrono::milliseconds;

/// Time `ms` after the watch joined (an hour after the clock's epoch: the "never drawn" marks,
/// at the epoch, are long past).
Clock::time_point at(long ms) { return Clock::time_point{} + std::chrono::hours(1) + milliseconds(ms); }

RunDescription tenTicks() {
  RunDescription run;
  run.identity.run_id = 0xabc;
  run.identity.domain = 7;
  run.scenario = "s";
  run.ticks = 10;
  run.processes = 4;
  run.launcher_pid = 4242;
  return run;
}

/// A watch at 10 frames a second with a 60 s timeout, joined at at(0), a first process due by 30 s.
WatchState watching(RunDescription run = tenTicks()) {
  WatchTiming timing;
  timing.min_frame_gap = milliseconds(100);
  timing.timeout = std::chrono::seconds(60);
  return WatchState(std::move(run), "RUN", timing, at(0), at(30000));
}

ProcessReport report(const std::string& role, std::uint32_t index, ProcessState state, std::int32_t tick = 0,
                     const std::string& message = "") {
  return {role, index, state, tick, message};
}

common::TrackEstimate track(common::TrackId id, double x) {
  common::TrackEstimate t;
  t.track = id;
  t.x = x;
  return t;
}

TickScores scores(std::int32_t truth_targets) {
  return {{"truth_targets", truth_targets}, {"ospa", 1.5}, {"gospa", 2.0}, {"eps_k_running", 0.25},
          {"ospa_mean_running", 1.25}};
}

/// One step with a live launcher and stdout, TickMetrics published.
WatchStep step(WatchState& state, long ms, bool metrics_published = true) {
  return state.step(at(ms), metrics_published, true, [] { return true; });
}

TEST_CASE("the watch counts processes as they report ready, running and done", "[launcher][watch]") {
  auto state = watching();
  CHECK(state.waitingLine() == "waiting for the run to start: 0/4 processes up");
  CHECK_FALSE(state.started());
  state.onStatus(report("node", 0, ProcessState::kStarting), at(10));
  state.onStatus(report("node", 1, ProcessState::kReady), at(10));
  state.onStatus(report("network", 0, ProcessState::kRunning), at(20));
  state.onStatus(report("supernode", 0, ProcessState::kDone), at(20));
  CHECK(state.started());
  CHECK(state.waitingLine() == "waiting for the first tick: 4/4 processes up (1 ready, 1 running, 1 done)");
  // A process's later report replaces its earlier one: node 1 goes from ready to running.
  state.onStatus(report("node", 1, ProcessState::kRunning), at(30));
  CHECK(state.processSummary() == "4/4 processes up (0 ready, 2 running, 1 done)");
}

TEST_CASE("the waiting screen is redrawn every half second until a tick is drawn", "[launcher][watch]") {
  auto state = watching();
  CHECK(step(state, 0).draw_waiting);
  CHECK_FALSE(step(state, 499).draw_waiting);
  CHECK(step(state, 500).draw_waiting);
  state.onTracks(1, {}, at(600));
  state.onMetrics(1, scores(0));
  const auto drawn = step(state, 1000);
  REQUIRE(drawn.frame);
  CHECK_FALSE(drawn.draw_waiting);  // a tick is on the screen now
  CHECK_FALSE(step(state, 2000).draw_waiting);
}

TEST_CASE("a tick is drawn when its metrics are in or cannot come", "[launcher][watch]") {
  auto state = watching();
  state.onTracks(1, {track(9, 1.0), track(2, 2.0)}, at(0));
  // Metrics are published but not in yet: the tick waits for them, at most 300 ms.
  CHECK_FALSE(step(state, 100).frame);
  state.onMetrics(1, scores(2));
  const auto first = step(state, 150);
  REQUIRE(first.frame);
  CHECK(first.frame->tick == 1);
  REQUIRE(first.frame->tracks.size() == 2);
  CHECK(first.frame->tracks[0].track == 2);  // in id order
  CHECK(first.frame->scores->at("truth_targets") == 2);
  CHECK(state.drawnTick() == 1);
  // Tick 2's metrics never come: drawn 300 ms after its tracks arrived, without scores.
  state.onTracks(2, {}, at(200));
  CHECK_FALSE(step(state, 499).frame);
  const auto second = step(state, 500);
  REQUIRE(second.frame);
  CHECK_FALSE(second.frame->scores);
  // Without a TickMetrics writer at all a tick is drawn at once.
  state.onTracks(3, {}, at(1000));
  CHECK(step(state, 1000, false).frame);
}

TEST_CASE("frames are rate limited, skip to the newest tick, and the last tick ends the watch", "[launcher][watch]") {
  auto state = watching();
  state.onTracks(1, {}, at(0));
  state.onMetrics(1, scores(1));
  REQUIRE(step(state, 0).frame);
  // Ticks 2 and 3 within the 100 ms frame gap: held back, and the next wait ends with the gap.
  for (std::int32_t t : {2, 3}) {
    state.onTracks(t, {}, at(10));
    state.onMetrics(t, scores(1));
  }
  CHECK_FALSE(step(state, 40).frame);
  // The wait for samples is 50 ms at most, and ends when the gap does: 100 - 70 = 30 ms.
  CHECK(state.nextWait(at(40)) == milliseconds(50));
  CHECK(state.nextWait(at(70)) == milliseconds(30));
  const auto skipped = step(state, 100);
  REQUIRE(skipped.frame);
  CHECK(skipped.frame->tick == 3);  // tick 2 is never drawn
  // A sample of a tick already drawn is too late to matter.
  state.onTracks(2, {track(1, 0)}, at(110));
  CHECK_FALSE(step(state, 300).frame);
  // The last tick is drawn at once, gap or not, and the watch ends.
  state.onTracks(10, {}, at(310));
  state.onMetrics(10, scores(1));
  const auto last = step(state, 320);
  REQUIRE(last.frame);
  CHECK(last.frame->tick == 10);
  REQUIRE(last.end);
  CHECK(last.end->exit_code == kWatchFinished);
  CHECK_FALSE(last.end->error);
  CHECK(last.end->text == "the run finished: tick 10/10 shown");
}

TEST_CASE("the aggregator's DONE ends the watch after a grace for its last batch", "[launcher][watch]") {
  auto state = watching();
  state.onStatus(report("aggregator", 0, ProcessState::kDone, 7), at(0));
  CHECK_FALSE(step(state, 1999).end);
  const auto done = step(state, 2000);
  REQUIRE(done.end);
  CHECK(done.end->exit_code == kWatchFinished);
  CHECK(done.end->text == "the run finished (aggregator DONE at tick 7); last tick shown: none");
  // Another role's DONE is not the run's end.
  auto other = watching();
  other.onStatus(report("supernode", 0, ProcessState::kDone, 10), at(0));
  CHECK_FALSE(step(other, 5000).end);
}

TEST_CASE("a failing process fails the watch after a moment that collects the others", "[launcher][watch]") {
  auto state = watching();
  state.onTracks(4, {}, at(0));
  state.onStatus(report("supernode", 1, ProcessState::kFailed, 4, "engine diverged"), at(100));
  CHECK_FALSE(step(state, 200).end);
  state.onStatus(report("node", 0, ProcessState::kFailed, 4, "stopped on request"), at(300));
  const auto failed = step(state, 600);  // 500 ms after the first failure
  // The newest tick is drawn first, so the message says how far the run got.
  REQUIRE(failed.frame);
  CHECK(failed.frame->tick == 4);
  REQUIRE(failed.end);
  CHECK(failed.end->exit_code == kWatchFailed);
  CHECK(failed.end->error);
  CHECK(failed.end->text ==
        "the run FAILED at tick 4/10:\n"
        "  supernode 1: engine diverged\n"
        "  node 0: stopped on request\n"
        "  (the launcher's output and RUN/logs/ say why)");
}

TEST_CASE("a dead launcher ends the watch, asked at most every half second", "[launcher][watch]") {
  auto state = watching();
  state.onStatus(report("node", 0, ProcessState::kRunning), at(0));
  int asked = 0;
  const auto dead = [&] {
    ++asked;
    return false;
  };
  CHECK_FALSE(state.step(at(499), true, true, dead).end);
  CHECK(asked == 0);
  const auto gone = state.step(at(500), true, true, dead);
  CHECK(asked == 1);
  REQUIRE(gone.end);
  CHECK(gone.end->exit_code == kWatchFailed);
  CHECK(gone.end->text == "the run's launcher (pid 4242) exited before the run finished (last tick seen 0/10); see RUN/logs/");
  // Once the aggregator is done the launcher may exit: that is no failure.
  auto finishing = watching();
  finishing.onStatus(report("aggregator", 0, ProcessState::kDone, 10), at(0));
  CHECK_FALSE(finishing.step(at(600), true, true, dead).end);
}

TEST_CASE("a run that never starts or stops progressing times the watch out", "[launcher][watch]") {
  auto idle = watching();
  CHECK_FALSE(step(idle, 29999).end);
  const auto never = step(idle, 30000);
  REQUIRE(never.end);
  CHECK(never.end->text == "no process of run abc showed up within 60 s");
  auto stalled = watching();
  stalled.onTracks(3, {}, at(1000));
  stalled.onMetrics(3, scores(1));
  CHECK(step(stalled, 1000).frame);
  CHECK_FALSE(step(stalled, 60999).end);
  const auto stuck = step(stalled, 61000);  // 60 s after the last sample
  REQUIRE(stuck.end);
  CHECK(stuck.end->exit_code == kWatchFailed);
  CHECK(stuck.end->text == "no progress for 60 s (last tick seen 3/10)");
}

TEST_CASE("the watch ends quietly when nobody reads its output", "[launcher][watch]") {
  auto state = watching();
  const auto gone = state.step(at(0), true, false, [] { return true; });
  REQUIRE(gone.end);
  CHECK(gone.end->exit_code == kWatchFailed);
  CHECK(gone.end->text.empty());
}

TEST_CASE("a frame shows the tick, its scores and one row per track", "[launcher][watch]") {
  WatchFrame frame;
  frame.tick = 3;
  auto t = track(5, 12.345);
  t.y = -1.0;
  t.vx = 3.0;
  t.vy = 4.0;  // speed hypot(3, 4) = 5
  frame.tracks = {t};
  CHECK(frameHeadLine(frame, 10) == "tick 3/10  K*=n/a K=1 OSPA=n/a GOSPA=n/a epsK=n/a meanOSPA=n/a");
  frame.scores = scores(2);
  CHECK(frameHeadLine(frame, 10) == "tick 3/10  K*=2 K=1 OSPA=1.500 GOSPA=2.000 epsK=0.2500 meanOSPA=1.250");
  const auto rows = frameRows(frame);
  REQUIRE(rows.size() == 2);
  CHECK(rows[0] == "  track                  x         y       vx       vy   speed");
  CHECK(rows[1] == "  " + (common::track_id::label(5) + std::string(14 - common::track_id::label(5).size(), ' ')) +
                       "     12.35     -1.00    3.000    4.000   5.000");
  // A classifying engine's tracks add a class column: the declared class and its probability.
  auto classified = track(6, 20.0);
  classified.class_probabilities = {0.1, 0.7, 0.05, 0.05, 0.05, 0.05};
  auto undecided = track(7, 30.0);
  undecided.class_probabilities = std::vector<double>(6, 1.0 / 6.0);
  frame.tracks = {classified, undecided};
  const auto class_rows = frameRows(frame);
  REQUIRE(class_rows.size() == 3);
  CHECK(class_rows[0] == rows[0] + "  class");
  CHECK(class_rows[1].ends_with("  wheeled_heavy:0.70"));
  CHECK(class_rows[2].ends_with("  -"));
  auto paced = tenTicks();
  CHECK(watchTitle(paced) == "wsntrack watch  s  run abc  domain 7");
  paced.tick_interval_s = 0.2;
  CHECK(watchTitle(paced) == "wsntrack watch  s  run abc  domain 7  paced 0.200 s/tick");
}

}  // namespace
}  // namespace wsn::launcher

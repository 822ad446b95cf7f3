#include "supernode/gnn/gnn_engine.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "common/rng.hpp"
#include "supernode/observation_window.hpp"
#include "tests/supernode/test_support.hpp"

namespace wsn::supernode::gnn {
namespace {

using test::gnnScenario;
using test::observation;
using test::sensorAt;

/// A window and a GNN engine of supernode 0, stepped the way SupernodeTracker steps them.
struct Harness {
  explicit Harness(common::Scenario s)
      : scenario(std::move(s)), window(scenario.tracker.window_size), engine(engineContext(scenario, 0)) {}
  void step(std::int32_t tick, const std::vector<common::Observation>& delivered = {}) {
    window.advanceTo(tick);
    for (const auto& o : delivered) window.insert(o);
    engine.step(window);
  }
  common::Scenario scenario;
  ObservationWindow window;
  GnnEngine engine;
};

double positionError(const common::TrackEstimate& e, common::Vec2 truth) { return std::hypot(e.x - truth.x, e.y - truth.y); }

const common::TrackEstimate* findTrack(const std::vector<common::TrackEstimate>& tracks, common::TrackId id) {
  for (const auto& t : tracks)
    if (t.track == id) return &t;
  return nullptr;
}

TEST_CASE("a track id encodes supernode, birth tick and sensor", "[gnn]") {
  // (0 + 1) << 48 | 3 << 24 | 5
  CHECK(common::track_id::birth(0, 3, 5) == ((std::uint64_t{1} << 48) | (std::uint64_t{3} << 24) | 5));
  CHECK(common::track_id::birth(2, 0, 0) == (std::uint64_t{3} << 48));
  CHECK(common::track_id::supernodeOf(common::track_id::birth(2, 77, 9)) == 2);
  CHECK(common::track_id::birthTick(common::track_id::birth(2, 77, 9)) == 77);
  // Read as "started by supernode 2 at tick 77 from sensor 9"; counters (MCMCDA) stay S:N.
  CHECK(common::track_id::label(common::track_id::birth(2, 77, 9)) == "2:t77s9");
  CHECK(common::track_id::label((std::uint64_t{1} << 48) | 1) == "0:1");
  CHECK(common::track_id::label(5) == "g5");
  CHECK_THROWS_AS(common::track_id::birth(0, 1, 1u << 24), std::out_of_range);
  CHECK_THROWS_AS(common::track_id::birth(0, 1 << 20, 0), std::out_of_range);  // run.ticks <= 10^6 < 2^20
  // A further tree of one sensor and tick (sbmht): index 3 << 44, read as ".3"; 16 fit.
  const common::TrackId third = common::track_id::birth(2, 77, 9, 3);
  CHECK(third == (common::track_id::birth(2, 77, 9) | (std::uint64_t{3} << 44)));
  CHECK(common::track_id::birthTick(third) == 77);
  CHECK(common::track_id::birthSensor(third) == 9);
  CHECK(common::track_id::birthIndex(third) == 3);
  CHECK(common::track_id::label(third) == "2:t77s9.3");
  CHECK(common::track_id::label(common::track_id::birth(0, (1 << 20) - 1, (1u << 24) - 1, 15)) ==
        "0:t1048575s16777215.15");
  CHECK_THROWS_AS(common::track_id::birth(0, 1, 0, 16), std::out_of_range);
}

TEST_CASE("a straight-line target is confirmed after M hits and tracked with vanishing error", "[gnn]") {
  Harness h(gnnScenario());
  auto truth = [](std::int32_t t) { return common::Vec2{10.0 + t, 20.0 + 0.5 * t}; };
  const common::TrackId id = common::track_id::birth(0, 1, sensorAt(11.0, 20.5));
  double error_at_5 = 0.0;
  for (std::int32_t t = 1; t <= 30; ++t) {
    const auto p = truth(t);
    h.step(t, {observation(t, t, p.x, p.y)});
    const auto tracks = h.engine.confirmedTracks();
    if (t < 3) {
      // M = 3: one and two hits leave the track tentative.
      CHECK(tracks.empty());
      REQUIRE(h.engine.liveTracks().size() == 1);
      CHECK(h.engine.liveTracks()[0].id == id);
      continue;
    }
    REQUIRE(tracks.size() == 1);
    CHECK(tracks[0].track == id);
    if (t == 5) error_at_5 = positionError(tracks[0], p);
  }
  const auto final_track = h.engine.confirmedTracks().at(0);
  const double error_at_30 = positionError(final_track, truth(30));
  // Noise-free observations of a constant-velocity target: the filter's error decays geometrically
  // from the initial velocity error (v0 = 0 against |v| = 1.1).
  CHECK(error_at_5 > 0.01);
  CHECK(error_at_30 < 0.01);
  CHECK(final_track.vx == Approx(1.0).margin(0.01));
  CHECK(final_track.vy == Approx(0.5).margin(0.01));
}

TEST_CASE("a confirmed track that coasts out of the region is deleted at once", "[gnn]") {
  Harness h(gnnScenario());
  // A target moving +2 per tick along y = 50 is seen up to x = 98.5 (tick 10) and then leaves
  // the region [0, 100]^2. Coasting predicts x = 100.5 at tick 11: outside, so the track goes,
  // although max_misses = 3 would have kept it until tick 13.
  for (std::int32_t t = 1; t <= 10; ++t) h.step(t, {observation(t, t, 78.5 + 2.0 * t, 50.0)});
  REQUIRE(h.engine.confirmedTracks().size() == 1);
  h.step(11);
  CHECK(h.engine.confirmedTracks().empty());
  CHECK(h.engine.liveTracks().empty());
}

TEST_CASE("a confirmed track that misses inside the region coasts for max_misses ticks", "[gnn]") {
  Harness h(gnnScenario());
  // Same target, observed up to x = 60.5 (tick 1..10, starting at 42.5): misses at 11 and 12
  // leave it confirmed; the third consecutive miss (tick 13) deletes it (max_misses = 3).
  for (std::int32_t t = 1; t <= 10; ++t) h.step(t, {observation(t, t, 40.5 + 2.0 * t, 50.0)});
  h.step(11);
  h.step(12);
  CHECK(h.engine.confirmedTracks().size() == 1);
  h.step(13);
  CHECK(h.engine.confirmedTracks().empty());
}

TEST_CASE("two crossing targets keep their identities through the crossing", "[gnn]") {
  Harness h(gnnScenario());
  // A climbs, B descends; at t = 10 they are 0.3 apart at (15, 20) and (15.3, 20).
  auto a = [](std::int32_t t) { return common::Vec2{5.0 + t, 10.0 + t}; };
  auto b = [](std::int32_t t) { return common::Vec2{5.3 + t, 30.0 - t}; };
  const common::TrackId id_a = common::track_id::birth(0, 1, sensorAt(6.0, 11.0));
  const common::TrackId id_b = common::track_id::birth(0, 1, sensorAt(6.3, 29.0));
  REQUIRE(id_a != id_b);
  for (std::int32_t t = 1; t <= 20; ++t) {
    h.step(t, {observation(t, t, a(t).x, a(t).y, 0), observation(t, t, b(t).x, b(t).y, 1)});
    if (t < 3) continue;
    const auto tracks = h.engine.confirmedTracks();
    INFO("tick " << t);
    REQUIRE(tracks.size() == 2);
    const auto* ta = findTrack(tracks, id_a);
    const auto* tb = findTrack(tracks, id_b);
    REQUIRE(ta != nullptr);
    REQUIRE(tb != nullptr);
    CHECK(positionError(*ta, a(t)) < 0.15);  // nearer its own target than the 0.3 separation / 2
    CHECK(positionError(*tb, b(t)) < 0.15);
  }
}

/// Poisson(mean) false alarms per tick, uniform over the 100 x 100 region, from a fixed stream.
std::vector<common::Observation> falseAlarms(std::int32_t tick, double mean) {
  common::Stream clutter(7, common::Purpose::kNoiseExceedance, 0, tick);
  std::vector<common::Observation> out;
  const auto n = clutter.poisson(mean);
  for (std::uint64_t k = 0; k < n; ++k) {
    const double x = clutter.uniform(0.0, 100.0);
    const double y = clutter.uniform(0.0, 100.0);
    out.push_back(observation(tick, tick, x, y, common::kFalseAlarm));
  }
  return out;
}

TEST_CASE("sparse uniform false alarms do not produce confirmed tracks", "[gnn]") {
  Harness h(gnnScenario());
  std::size_t max_tentative = 0;
  for (std::int32_t t = 1; t <= 100; ++t) {
    h.step(t, falseAlarms(t, 1.0));
    INFO("tick " << t);
    CHECK(h.engine.confirmedTracks().empty());
    max_tentative = std::max(max_tentative, h.engine.predictions().size());
  }
  // Tentative tracks were started (so the check above could fail).
  CHECK(max_tentative >= 2);
}

TEST_CASE("at the paper's false-alarm density 4-of-5 confirmation yields no false tracks", "[gnn]") {
  // Oh §VII-E: 603 false alarms in 100 ticks, about 6 per tick over the 100 x 100 region.
  auto s = gnnScenario();
  s.tracker.params["confirm_hits"].value = 4.0;
  Harness h(s);
  std::size_t max_tentative = 0;
  for (std::int32_t t = 1; t <= 100; ++t) {
    h.step(t, falseAlarms(t, 6.0));
    INFO("tick " << t);
    CHECK(h.engine.confirmedTracks().empty());
    max_tentative = std::max(max_tentative, h.engine.predictions().size());
  }
  CHECK(max_tentative >= 10);
}

TEST_CASE("a confirmed track is deleted after max_misses consecutive misses", "[gnn]") {
  Harness h(gnnScenario());
  for (std::int32_t t = 1; t <= 6; ++t) h.step(t, {observation(t, t, 10.0 + t, 10.0)});
  REQUIRE(h.engine.confirmedTracks().size() == 1);
  // max_misses = 3: misses at ticks 7 and 8 coast the track along its velocity ...
  h.step(7);
  h.step(8);
  const auto coasting = h.engine.confirmedTracks();
  REQUIRE(coasting.size() == 1);
  CHECK(coasting[0].x == Approx(18.0).margin(0.05));  // 16 + 2 ticks at speed 1
  // ... and the third consecutive miss deletes it.
  h.step(9);
  CHECK(h.engine.confirmedTracks().empty());
  CHECK(h.engine.predictions().empty());
}

TEST_CASE("a confirmed track ends soon where a sensor would have seen it and coasts where none looks", "[gnn]") {
  // max_misses 20: twenty silent ticks are 1 % likely on the field's average, rho = 0.01^(1/20) =
  // 0.794 a tick. The field's one sensor, a disc of radius 5 at (20, 20) with PD 0.9, covers 0.7 %
  // of the region: a miss there weighs 1 - (1 - rho) x 0.9 / 0.00707 < 0, so the target at rest in
  // it ends at its first miss; the one at (70, 70), where no sensor looks, coasts all 20 ticks, as
  // both do when the coverage is not known.
  common::Scenario s = gnnScenario();
  s.tracker.params["max_misses"] = {20, 0};
  resolveEngineParams(s, wsn::common::kNoStatistics);
  EngineContext context = engineContext(s, 0);
  GnnEngine without_coverage(context);
  context.coverage = {{0, {20.0, 20.0}, 0.0, 2 * std::numbers::pi, 5.0, 0.9, common::SightBlockers::none}};
  context.coverage_region_mean = common::meanSensedProbability(context.coverage, context.region, nullptr);
  GnnEngine with_coverage(context);
  ObservationWindow window(s.tracker.window_size);
  const auto near = [](const std::vector<common::TrackEstimate>& tracks, common::Vec2 at) {
    return std::ranges::count_if(tracks, [&](const common::TrackEstimate& e) { return positionError(e, at) < 1.0; });
  };
  for (std::int32_t t = 1; t <= 30; ++t) {
    window.advanceTo(t);
    if (t <= 6) {
      window.insert(observation(t, t, 20.0, 20.0, 0));
      window.insert(observation(t, t, 70.0, 70.0, 1));
    }
    without_coverage.step(window);
    with_coverage.step(window);
    if (t < 6) continue;  // confirmed by then
    INFO("tick " << t);
    const std::int32_t coasting = t < 6 + 20 ? 1 : 0;
    CHECK(near(without_coverage.confirmedTracks(), {20.0, 20.0}) == coasting);
    CHECK(near(without_coverage.confirmedTracks(), {70.0, 70.0}) == coasting);
    CHECK(near(with_coverage.confirmedTracks(), {20.0, 20.0}) == (t == 6 ? 1 : 0));
    CHECK(near(with_coverage.confirmedTracks(), {70.0, 70.0}) == coasting);
  }
}

TEST_CASE("a tentative track that can no longer reach M hits in N ticks is deleted", "[gnn]") {
  Harness h(gnnScenario());
  h.step(1, {observation(1, 1, 50.0, 50.0)});
  // M = 3 of N = 5: after one hit it can afford N - M = 2 misses (ticks 2, 3).
  h.step(2);
  h.step(3);
  CHECK(h.engine.predictions().size() == 1);
  h.step(4);
  CHECK(h.engine.predictions().empty());
}

/// Observations of a target at (10 + t, 30 - 0.5 t) with a fixed-seed noise of sigma 0.3.
common::Observation noisyObservation(std::int32_t generated, std::int32_t delivered) {
  common::Stream noise(3, common::Purpose::kSensorNoise, 0, generated);
  const double x = 10.0 + generated + 0.3 * noise.normal();
  const double y = 30.0 - 0.5 * generated + 0.3 * noise.normal();
  return observation(generated, delivered, x, y);
}

TEST_CASE("a delayed observation filed into its old slot is used as if it had been on time", "[gnn]") {
  Harness missing(gnnScenario());  // the observation of tick 8 never arrives
  Harness late(gnnScenario());     // it arrives at tick 10
  Harness on_time(gnnScenario());  // it arrives at tick 8
  for (std::int32_t t = 1; t <= 10; ++t) {
    std::vector<common::Observation> m;
    std::vector<common::Observation> l;
    std::vector<common::Observation> o = {noisyObservation(t, t)};
    if (t != 8) {
      m.push_back(noisyObservation(t, t));
      l.push_back(noisyObservation(t, t));
    }
    if (t == 10) l.push_back(noisyObservation(8, 10));
    missing.step(t, m);
    late.step(t, l);
    on_time.step(t, o);
  }
  // The window replays tick 8 with its late observation, so the late run ends exactly where the
  // on-time run does (same ids, same numbers).
  CHECK(late.engine.confirmedTracks() == on_time.engine.confirmedTracks());

  REQUIRE(missing.engine.liveTracks().size() == 1);
  REQUIRE(late.engine.liveTracks().size() == 1);
  const auto& with = late.engine.liveTracks()[0];
  const auto& without = missing.engine.liveTracks()[0];
  CHECK(with.id == without.id);
  CHECK(with.hits == without.hits + 1);
  // An extra update shrinks the covariance at tick 8 and the Riccati recursion is monotone, so the
  // newest covariance is smaller too (whatever the observed values).
  CHECK(with.state.P.trace() < without.state.P.trace());
  CHECK(with.state.x != without.state.x);
}

TEST_CASE("late observations revive a track that their absence had deleted, under its old id", "[gnn]") {
  Harness missing(gnnScenario());  // ticks 7-9 never arrive
  Harness late(gnnScenario());     // ticks 7-9 arrive at tick 10
  Harness on_time(gnnScenario());
  for (std::int32_t t = 1; t <= 10; ++t) {
    const bool gap = t >= 7 && t <= 9;
    on_time.step(t, {noisyObservation(t, t)});
    missing.step(t, gap ? std::vector<common::Observation>{} : std::vector{noisyObservation(t, t)});
    std::vector<common::Observation> l;
    if (!gap) l.push_back(noisyObservation(t, t));
    if (t == 10)
      for (std::int32_t g = 7; g <= 9; ++g) l.push_back(noisyObservation(g, 10));
    late.step(t, l);
    if (t == 9) {
      // Three consecutive misses (max_misses = 3) delete the track in both incomplete runs.
      CHECK(missing.engine.confirmedTracks().empty());
      CHECK(late.engine.confirmedTracks().empty());
    }
  }
  const common::TrackId id = common::track_id::birth(0, 1, noisyObservation(1, 1).sensor);
  const auto revived = late.engine.confirmedTracks();
  REQUIRE(revived.size() == 1);
  CHECK(revived[0].track == id);
  CHECK(revived == on_time.engine.confirmedTracks());
  // Without them tick 10's observation can only start a new, tentative track.
  CHECK(missing.engine.confirmedTracks().empty());
  REQUIRE(missing.engine.liveTracks().size() == 1);
  CHECK(missing.engine.liveTracks()[0].id == common::track_id::birth(0, 10, noisyObservation(10, 10).sensor));
}

TEST_CASE("observations one tick late end where on-time ones do once the window has them", "[gnn]") {
  // ws = 3 with 25 ticks: most ticks are folded into the anchor, with their final contents.
  Harness late(gnnScenario(3));
  Harness on_time(gnnScenario(3));
  auto at = [](std::int32_t t, int k) {
    common::Stream clutter(11, common::Purpose::kNoiseExceedance, 0, t);
    std::vector<common::Observation> out = {noisyObservation(t, t),
                                            observation(t, t, 60.0 + 0.8 * t, 70.0 - 0.9 * t, 1)};
    for (int i = 0; i < k; ++i) out.push_back(observation(t, t, clutter.uniform(0, 100), clutter.uniform(0, 100), -1));
    return out;
  };
  std::vector<common::TrackId> ids_late;
  for (std::int32_t t = 1; t <= 25; ++t) {
    on_time.step(t, at(t, 2));
    std::vector<common::Observation> delayed;
    if (t > 1)
      for (auto o : at(t - 1, 2)) {
        o.tick_delivered = t;
        delayed.push_back(o);
      }
    late.step(t, delayed);
  }
  // Tick 26 brings nothing new to the on-time run and the last late batch to the other.
  on_time.step(26);
  std::vector<common::Observation> last;
  for (auto o : at(25, 2)) {
    o.tick_delivered = 26;
    last.push_back(o);
  }
  late.step(26, last);
  const auto tracks = on_time.engine.confirmedTracks();
  CHECK(tracks.size() == 2);
  CHECK(late.engine.confirmedTracks() == tracks);
  CHECK(late.engine.predictions().size() == on_time.engine.predictions().size());
}

TEST_CASE("a handoff older than the window enters the anchor predicted up to it", "[gnn]") {
  Harness h(gnnScenario(3));
  for (std::int32_t t = 1; t <= 10; ++t) h.step(t);  // anchor after tick 7
  common::TrackHandoff handoff;
  handoff.track = common::track_id::birth(1, 2, 42);
  handoff.to_supernode = 0;
  handoff.last_tick = 5;
  handoff.state = {10.0, 10.0, 1.0, 0.0};
  for (int i = 0; i < 4; ++i) handoff.covariance[static_cast<std::size_t>(i * 5)] = 0.1;
  handoff.hits = 5;
  handoff.confirmed = true;
  h.engine.adopt(handoff);
  // At tick 5 it was at x = 10, so at ticks 9, 10, 11 the target is at 14, 15, 16.
  h.step(11, {observation(9, 11, 14.0, 10.0), observation(10, 11, 15.0, 10.0), observation(11, 11, 16.0, 10.0)});
  const auto tracks = h.engine.confirmedTracks();
  REQUIRE(tracks.size() == 1);
  CHECK(tracks[0].track == handoff.track);
  CHECK(tracks[0].x == Approx(16.0).margin(0.05));
  CHECK(h.engine.liveTracks()[0].hits == 8);  // 5 + the three of ticks 9-11 (tick 8 was a miss)
}

TEST_CASE("a released track leaves every later replay and unknown ones cannot be released", "[gnn]") {
  Harness h(gnnScenario());
  for (std::int32_t t = 1; t <= 5; ++t) h.step(t, {observation(t, t, 10.0 + t, 10.0)});
  const common::TrackId id = common::track_id::birth(0, 1, sensorAt(11.0, 10.0));
  const auto handoff = h.engine.release(id, 3);
  CHECK(handoff.track == id);
  CHECK(handoff.to_supernode == 3);
  CHECK(handoff.last_tick == 5);
  CHECK(handoff.state[0] == Approx(15.0).margin(0.05));
  CHECK(handoff.state[2] == Approx(1.0).margin(0.05));
  CHECK(handoff.covariance[1] == handoff.covariance[4]);  // row-major and symmetric
  CHECK(handoff.hits == 5);
  CHECK(handoff.misses == 0);
  CHECK(handoff.confirmed);
  CHECK(h.engine.predictions().empty());
  CHECK_THROWS_AS(h.engine.release(id, 3), std::invalid_argument);

  // Tick 6 replays ticks 1-6 from the anchor: the track is rebuilt up to tick 5 and removed
  // there, so tick 6's observation starts a new tentative track instead.
  h.step(6, {observation(6, 6, 16.0, 10.0)});
  CHECK(h.engine.confirmedTracks().empty());
  REQUIRE(h.engine.liveTracks().size() == 1);
  CHECK(h.engine.liveTracks()[0].id == common::track_id::birth(0, 6, sensorAt(16.0, 10.0)));
}

}  // namespace
}  // namespace wsn::supernode::gnn

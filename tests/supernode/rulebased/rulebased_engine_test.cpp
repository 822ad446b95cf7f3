#include "supernode/rulebased/rulebased_engine.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "supernode/observation_window.hpp"

namespace wsn::supernode::rulebased {
namespace {

constexpr double kDs = 25.0;

/// The paper's field: 1250 m square, a 50 x 50 grid at Ds = 25 m, engine "rulebased".
common::Scenario fieldScenario(std::initializer_list<std::pair<const char*, double>> params = {}) {
  common::Scenario s;
  s.source_path = "test.yaml";
  s.region = {0.0, 0.0, 1250.0, 1250.0};
  s.sensors.spacing = kDs;
  s.supernodes = {{625.0, 625.0}};
  s.dynamics.process_noise_sigma = 0.0;
  s.tracker.engine = "rulebased";
  for (const auto& [name, value] : params) s.tracker.params[name] = {value, 0};
  resolveEngineParams(s);
  return s;
}

/// A target moving in a straight line, with the sensing range that sets its power Pt = SR^2.
struct Mover {
  double x, y, vx, vy, sensing_range;
  common::Vec2 at(std::int32_t tick) const { return {x + vx * tick, y + vy * tick}; }
};

/// Synthetic detections: every grid sensor where sum_i SR_i^2 / d_i^2 >= 1 reports floor of that sum.
std::vector<common::Observation> detections(std::int32_t tick, const std::vector<Mover>& movers) {
  std::vector<common::Observation> out;
  for (int j = 0; j < 50; ++j)
    for (int i = 0; i < 50; ++i) {
      const common::Vec2 s{12.5 + kDs * i, 12.5 + kDs * j};
      double power = 0.0;
      double loudest = 0.0;
      common::TargetId target = common::kFalseAlarm;
      for (std::size_t k = 0; k < movers.size(); ++k) {
        const double d = std::max(common::distance(s, movers[k].at(tick)), 1.0);
        const double p = movers[k].sensing_range * movers[k].sensing_range / (d * d);
        power += p;
        if (p > loudest) {
          loudest = p;
          target = static_cast<common::TargetId>(k);
        }
      }
      if (power >= 1.0)
        out.push_back({tick, tick, static_cast<common::SensorId>(j * 50 + i), s.x, s.y, target,
                       static_cast<std::int32_t>(std::floor(power))});
    }
  return out;
}

/// A window and an engine of supernode 0, stepped the way SupernodeTracker steps them.
struct Harness {
  explicit Harness(common::Scenario s)
      : scenario(std::move(s)), window(scenario.tracker.window_size), engine(EngineContext{scenario, 0}) {}
  void step(std::int32_t tick, const std::vector<common::Observation>& delivered) {
    window.advanceTo(tick);
    for (const auto& o : delivered) window.insert(o);
    engine.step(window);
  }
  /// Steps ticks from..to with the movers' detections plus `extra(tick)`.
  template <typename Extra>
  void run(std::int32_t from, std::int32_t to, const std::vector<Mover>& movers, Extra extra) {
    for (std::int32_t t = from; t <= to; ++t) {
      auto observed = detections(t, movers);
      const auto more = extra(t);
      observed.insert(observed.end(), more.begin(), more.end());
      step(t, observed);
    }
  }
  void run(std::int32_t from, std::int32_t to, const std::vector<Mover>& movers) {
    run(from, to, movers, [](std::int32_t) { return std::vector<common::Observation>{}; });
  }
  common::Scenario scenario;
  ObservationWindow window;
  RulebasedEngine engine;
};

/// The id of the track nearest to `p` (0 when there is none) and its distance.
std::pair<common::TrackId, double> nearestTrack(const std::vector<common::TrackEstimate>& tracks, common::Vec2 p) {
  std::pair<common::TrackId, double> best{0, std::numeric_limits<double>::infinity()};
  for (const auto& t : tracks) {
    const double d = common::distance({t.x, t.y}, p);
    if (d < best.second) best = {t.track, d};
  }
  return best;
}

TEST_CASE("a single target is tracked closely under one identity", "[rulebased]") {
  Harness h(fieldScenario());
  const std::vector<Mover> movers = {{200, 300, 2.0, 1.0, 40}};  // 20 m/s east, 10 north
  h.run(1, 3, movers);
  const auto first = h.engine.confirmedTracks();
  REQUIRE(first.size() == 1);  // born at the second sighting (confirm_ticks = 2)
  h.run(4, 100, movers);
  const auto tracks = h.engine.confirmedTracks();
  REQUIRE(tracks.size() == 1);
  CHECK(tracks[0].track == first[0].track);
  CHECK(nearestTrack(tracks, movers[0].at(100)).second < 5.0);
  CHECK(tracks[0].vx == Approx(2.0).margin(0.2));
  CHECK(tracks[0].last_seen_tick == 100);
  REQUIRE(h.engine.predictions().size() == 1);
  CHECK(h.engine.predictions()[0].next_position.x == Approx(tracks[0].x + tracks[0].vx));
}

TEST_CASE("two targets crossing in an X keep their identities through the merge and split", "[rulebased]") {
  Harness h(fieldScenario());
  // Paths cross at (600, 600) at tick 100: the clusters merge tens of ticks before and split after.
  const std::vector<Mover> movers = {{400, 400, 2.0, 2.0, 40}, {400, 800, 2.0, -2.0, 35}};
  h.run(1, 10, movers);
  const auto before = h.engine.confirmedTracks();
  REQUIRE(before.size() == 2);
  const auto id_a = nearestTrack(before, movers[0].at(10)).first;
  const auto id_b = nearestTrack(before, movers[1].at(10)).first;
  REQUIRE(id_a != id_b);
  bool merged = false;
  for (std::int32_t t = 11; t <= 200; ++t) {
    h.step(t, detections(t, movers));
    merged = merged || h.engine.lastClusters().size() == 1;
  }
  CHECK(merged);
  CHECK(h.engine.stats().merges > 0);
  const auto after = h.engine.confirmedTracks();
  REQUIRE(after.size() == 2);
  CHECK(nearestTrack(after, movers[0].at(200)).first == id_a);
  CHECK(nearestTrack(after, movers[1].at(200)).first == id_b);
  CHECK(nearestTrack(after, movers[0].at(200)).second < 10.0);
  CHECK(nearestTrack(after, movers[1].at(200)).second < 10.0);
}

TEST_CASE("three clusters merging into one and splitting keep their three identities", "[rulebased]") {
  // 2014 Table 1, 2nd scenario (m per tick of 0.1 s): the three meet near (345, 295) m.
  Harness h(fieldScenario());
  const std::vector<Mover> movers = {{200, 100, 1.3, 1.7, 40}, {150, 260, 2.0, 0.5, 30}, {200, 400, 1.7, -1.3, 30}};
  h.run(1, 10, movers);
  std::vector<common::TrackId> ids;
  for (const auto& m : movers) ids.push_back(nearestTrack(h.engine.confirmedTracks(), m.at(10)).first);
  bool all_in_one = false;
  for (std::int32_t t = 11; t <= 200; ++t) {
    h.step(t, detections(t, movers));
    all_in_one = all_in_one || h.engine.lastClusters().size() == 1;
  }
  CHECK(all_in_one);
  const auto after = h.engine.confirmedTracks();
  REQUIRE(after.size() == 3);
  for (std::size_t k = 0; k < movers.size(); ++k) {
    INFO("target " << k);
    CHECK(nearestTrack(after, movers[k].at(200)).first == ids[k]);
  }
}

TEST_CASE("a target that appears gets a track after confirm_ticks; one that vanishes is deleted", "[rulebased]") {
  Harness h(fieldScenario({{"max_coast_ticks", 5}}));
  const Mover stays{200, 200, 1.5, 0.0, 40};
  const Mover comes{800, 800, -1.0, 0.0, 40};
  h.run(1, 20, {stays});
  REQUIRE(h.engine.confirmedTracks().size() == 1);
  h.run(21, 21, {stays, comes});
  CHECK(h.engine.confirmedTracks().size() == 1);  // one sighting: a candidate
  h.run(22, 22, {stays, comes});
  CHECK(h.engine.confirmedTracks().size() == 2);  // two consecutive sightings: a track
  CHECK(h.engine.stats().births == 2);
  // `comes` falls silent: it coasts 5 ticks (max_coast_ticks) and is deleted at the 6th.
  h.run(23, 27, {stays});
  CHECK(h.engine.confirmedTracks().size() == 2);
  h.run(28, 28, {stays});
  CHECK(h.engine.confirmedTracks().size() == 1);
  CHECK(h.engine.stats().deletions == 1);
}

TEST_CASE("two targets merged at the start become two tracks when they split", "[rulebased]") {
  Harness h(fieldScenario());
  // 30 m apart and diverging: one cluster at first, two later.
  const std::vector<Mover> movers = {{600, 600, -1.5, 0.0, 40}, {630, 600, 1.5, 0.0, 40}};
  h.run(1, 3, movers);
  CHECK(h.engine.confirmedTracks().size() == 1);
  h.run(4, 80, movers);
  const auto tracks = h.engine.confirmedTracks();
  REQUIRE(tracks.size() == 2);
  CHECK(nearestTrack(tracks, movers[0].at(80)).second < 10.0);
  CHECK(nearestTrack(tracks, movers[1].at(80)).second < 10.0);
}

TEST_CASE("with denoise, short scattered noise makes no track and does not move the target's", "[rulebased]") {
  // Pairs of adjacent noisy sensors far from the target, each pair for 2 ticks then elsewhere: long
  // enough for the engine's own 2-tick confirmation, not for the 3-tick persistence test (eq. 11).
  const auto noise = [](std::int32_t tick) {
    std::vector<common::Observation> out;
    const int row = 5 + (tick / 2) % 40;  // a new place every 2 ticks
    for (int i = 40; i <= 41; ++i)
      out.push_back({tick, tick, static_cast<common::SensorId>(row * 50 + i), 12.5 + kDs * i, 12.5 + kDs * row,
                     common::kFalseAlarm, 1});
    return out;
  };
  const std::vector<Mover> movers = {{200, 300, 2.0, 0.0, 40}};
  Harness plain(fieldScenario());
  plain.run(1, 60, movers, noise);
  Harness mitigated(fieldScenario({{"denoise", 1}}));
  mitigated.run(1, 60, movers, noise);
  CHECK(plain.engine.stats().births > 1);  // the noise pairs became tracks
  CHECK(mitigated.engine.stats().births == 1);
  REQUIRE(mitigated.engine.confirmedTracks().size() == 1);
  CHECK(nearestTrack(mitigated.engine.confirmedTracks(), movers[0].at(60)).second < 5.0);
  CHECK(mitigated.engine.stats().detections_kept < mitigated.engine.stats().detections_in);
}

TEST_CASE("the quick solution measures a cluster at its strongest sensor", "[rulebased]") {
  // One tick, confirm_ticks = 1: the track is born at its measurement. Levels 1, 1, 5 in a row at
  // x = 262.5, 287.5, 312.5: the weighted centroid is 2075 / 7 = 296.4, the strongest sensor 312.5.
  common::Scenario s = fieldScenario({{"confirm_ticks", 1}, {"quick_solution", 1}});
  Harness h(s);
  std::vector<common::Observation> row;
  const int levels[] = {1, 1, 5};
  for (int i = 0; i < 3; ++i)
    row.push_back({1, 1, static_cast<common::SensorId>(10 * 50 + 10 + i), 12.5 + kDs * (10 + i), 262.5, 0, levels[i]});
  h.step(1, row);
  REQUIRE(h.engine.confirmedTracks().size() == 1);
  CHECK(h.engine.confirmedTracks()[0].x == Approx(312.5));  // (12, 10), not the centroid 296.4
}

TEST_CASE("a measurement lag of L ticks shifts a new track forward by L velocities", "[rulebased]") {
  // z = x - L v (the centroid shows where the target was L ticks ago): with L = 2 and v = 2 m per
  // tick the born track sits 4 m ahead of its measurement.
  const std::vector<Mover> movers = {{400, 412.5, 2.0, 0.0, 40}};
  Harness lagged(fieldScenario({{"measurement_lag", 2}}));
  Harness plain(fieldScenario());
  lagged.run(1, 2, movers);
  plain.run(1, 2, movers);
  REQUIRE(lagged.engine.confirmedTracks().size() == 1);
  REQUIRE(plain.engine.confirmedTracks().size() == 1);
  const double vx = plain.engine.confirmedTracks()[0].vx;
  CHECK(lagged.engine.confirmedTracks()[0].x == Approx(plain.engine.confirmedTracks()[0].x + 2.0 * vx));
}

TEST_CASE("a released track is handed over with its state and continues under its id when adopted",
          "[rulebased]") {
  const std::vector<Mover> movers = {{500, 600, 2.0, 0.0, 40}};
  Harness from(fieldScenario());
  from.run(1, 30, movers);
  const auto before = from.engine.confirmedTracks();
  REQUIRE(before.size() == 1);
  const auto handoff = from.engine.release(before[0].track, 1);
  CHECK(handoff.track == before[0].track);
  CHECK(handoff.to_supernode == 1);
  CHECK(handoff.last_tick == 30);
  CHECK(handoff.state[0] == before[0].x);
  CHECK(handoff.confirmed);
  CHECK(from.engine.confirmedTracks().empty());
  // The releasing side leaves the target's clusters to the neighbour: no new track there.
  from.run(31, 40, movers);
  CHECK(from.engine.confirmedTracks().empty());

  Harness to(fieldScenario());
  to.run(1, 30, {});
  to.engine.adopt(handoff);
  to.run(31, 60, movers);
  const auto tracks = to.engine.confirmedTracks();
  REQUIRE(tracks.size() == 1);
  CHECK(tracks[0].track == handoff.track);
  CHECK(nearestTrack(tracks, movers[0].at(60)).second < 5.0);
}

TEST_CASE("a decision lag lets delayed reports in and reports the tracks at the newest tick", "[rulebased]") {
  // Every report arrives 2 ticks late. Without a lag the engine has processed each tick before its
  // reports arrive and sees nothing; with decision_lag = 2 it processes tick t - 2 once they are in.
  const std::vector<Mover> movers = {{300, 400, 2.0, 0.0, 40}};
  Harness eager(fieldScenario());
  Harness patient(fieldScenario({{"decision_lag", 2}}));
  for (std::int32_t t = 1; t <= 40; ++t) {
    std::vector<common::Observation> late = t > 2 ? detections(t - 2, movers) : std::vector<common::Observation>{};
    for (auto& o : late) o.tick_delivered = t;
    eager.step(t, late);
    patient.step(t, late);
  }
  CHECK(eager.engine.confirmedTracks().empty());
  const auto tracks = patient.engine.confirmedTracks();
  REQUIRE(tracks.size() == 1);
  // The state of tick 38, predicted two ticks to tick 40.
  CHECK(nearestTrack(tracks, movers[0].at(40)).second < 5.0);
  CHECK(patient.engine.identities()[0].state_tick == 38);

  common::Scenario s = fieldScenario();
  s.tracker.params["decision_lag"] = {10, 7};  // window_size is 10
  CHECK_THROWS_WITH(resolveEngineParams(s),
                    "test.yaml:7: 'tracker.params.decision_lag' 10 must be below 'tracker.window_size' 10");
}

TEST_CASE("the engine is deterministic", "[rulebased]") {
  const std::vector<Mover> movers = {{400, 400, 2.0, 2.0, 40}, {400, 800, 2.0, -2.0, 35}};
  Harness a(fieldScenario());
  Harness b(fieldScenario());
  for (std::int32_t t = 1; t <= 150; ++t) {
    const auto observed = detections(t, movers);
    a.step(t, observed);
    b.step(t, observed);
    REQUIRE(a.engine.confirmedTracks() == b.engine.confirmedTracks());
  }
}

}  // namespace
}  // namespace wsn::supernode::rulebased

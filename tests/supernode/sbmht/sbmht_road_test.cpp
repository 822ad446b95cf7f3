// Algorithm 1 of Pannetier et al. (use_road_network): the road model in the IMM near a road, the
// road model's estimate on the road, and N-scan pruning that keeps a branch per road section (C7).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <numbers>
#include <set>
#include <vector>

#include "common/rng.hpp"
#include "common/sensor_coverage.hpp"
#include "common/terrain.hpp"
#include "supernode/sbmht/sbmht_engine.hpp"
#include "tests/supernode/sbmht/sbmht_test_support.hpp"
#include "tests/supernode/test_support.hpp"

namespace wsn::supernode::sbmht {
namespace {

using test::observation;
using test::sensorAt;
using namespace support;

/// Road "main" along y = 30 from x = 0 to 100 with a junction at (50, 30), where road "branch"
/// leaves towards (100, 60): sections main[0..50], main[50..100] and branch.
std::shared_ptr<const common::Terrain> forkTerrain() {
  common::TerrainConfig config;
  config.roads.push_back({"main", {{0.0, 30.0}, {50.0, 30.0}, {100.0, 30.0}}});
  config.roads.push_back({"branch", {{50.0, 30.0}, {100.0, 60.0}}});
  return std::make_shared<const common::Terrain>(config);
}

/// A harness whose engine sees the fork's roads, with algorithm 1 or 2.
Harness roadHarness(bool use_roads, std::map<std::string, double> params = {}) {
  params["use_road_network"] = use_roads ? 1.0 : 0.0;
  const auto terrain = forkTerrain();
  return Harness(sbmhtScenario(params), [&](EngineContext& c) { c.terrain = terrain; });
}

std::int32_t sectionNear(const common::Terrain& terrain, common::Vec2 p) {
  return static_cast<std::int32_t>(terrain.project(p)->section);
}

TEST_CASE("sbmht algorithm 1 lets a target that drives past a road's dead end leave the road", "[sbmht]") {
  // The target drives east along main at 1 per tick from x = 81 and on past main's end at x = 100,
  // a dead end, to x = 110. While its prediction lies on the road the road model runs on main's
  // second section; once it lies past the end, nothing holds it to the road, though the end stays
  // within the 15 of road_gate_distance until x = 115.
  const auto terrain = forkTerrain();
  Harness h = roadHarness(true);
  auto truth = [](std::int32_t t) { return common::Vec2{80.0 + t, 30.0}; };
  const auto main_east = sectionNear(*terrain, {90.0, 30.0});
  for (std::int32_t t = 1; t <= 30; ++t) {
    h.step(t, {observation(t, t, truth(t).x, truth(t).y)});
    if (t != 15 && t != 25 && t != 30) continue;
    INFO("tick " << t);
    const auto tracks = h.engine.confirmedTracks();
    REQUIRE(tracks.size() == 1);
    CHECK(std::abs(tracks[0].x - truth(t).x) < 1.0);
    for (const auto& leaf : h.engine.leaves())
      if (leaf.tree == tracks[0].track) CHECK(leaf.road_section == (t == 15 ? main_east : -1));
  }
}

TEST_CASE("sbmht algorithm 1 keeps a branch on each road section at a fork where algorithm 2 keeps one (C7)",
          "[sbmht]") {
  // The target drives along "main" at 1 per tick. At tick `fork`, 3 past the junction, two reports
  // fall in its gate: one on main, one on the branch road 1.8 to the side (the branch rises 0.6 per
  // unit of x). Every later tick is a miss, so the branches differ only at the fork: N = 3 ticks
  // later, N-scan pruning decides. Algorithm 2 keeps the best hypothesis's branch alone; algorithm 1
  // also keeps the best branch on the other road section (Nk = 3 allows it).
  const auto terrain = forkTerrain();
  const std::int32_t fork = 33;
  const std::int32_t n = 3;  // n_scan, the default
  auto truth = [](std::int32_t t) { return common::Vec2{20.0 + t, 30.0}; };
  auto run = [&](bool use_roads) {
    // Misses must not end the leaves before N-scan decides (the default max_misses is 3).
    Harness h = roadHarness(use_roads, {{"max_misses", 10.0}});
    const common::TrackId id = common::track_id::birth(0, 1, sensorAt(truth(1).x, truth(1).y));
    std::set<std::vector<std::int32_t>> at_fork;
    std::set<std::int32_t> sections;
    for (std::int32_t t = 1; t <= fork + n; ++t) {
      std::vector<common::Observation> reports;
      if (t < fork) reports.push_back(observation(t, t, truth(t).x, truth(t).y));
      if (t == fork) {
        reports.push_back(observation(t, t, truth(t).x, 30.0));
        reports.push_back(observation(t, t, truth(t).x, 31.8));
      }
      h.step(t, reports);
    }
    for (const auto& leaf : h.engine.leaves()) {
      if (leaf.tree != id) continue;
      const auto took = leaf.reportsAt(fork);
      at_fork.emplace(took.begin(), took.end());
      sections.insert(leaf.road_section);
    }
    return std::make_pair(at_fork, sections);
  };
  const auto [a2_choices, a2_sections] = run(false);
  CHECK(a2_choices.size() == 1);
  CHECK(a2_sections == std::set<std::int32_t>{-1});  // algorithm 2 never assigns a section
  const auto [a1_choices, a1_sections] = run(true);
  CHECK(a1_choices.size() == 2);
  // ...on the two sections past the junction: main's second section and the branch road.
  const std::int32_t main_after = sectionNear(*terrain, {60.0, 30.0});
  const std::int32_t branch = sectionNear(*terrain, {70.0, 42.0});
  CHECK(main_after != branch);
  CHECK(a1_sections == std::set<std::int32_t>{main_after, branch});
}

TEST_CASE("sbmht algorithm 1 puts the road model on the road and follows a road target more closely", "[sbmht]") {
  // A target drives along main (y = 30) at 1.5 per tick; position reports have sigma 3 per axis
  // (measurement_sigma 3). Algorithm 1's road model is confined to the road (its estimate is on
  // the centre line, eq. 6 and C8), which pulls the combined estimate towards it. The paper finds
  // that roads improve precision only weakly. Here the road is known to 1 (road_location_sigma)
  // and the quiet CV model explains a steady speed along the road better than the road model's
  // sigma_d = 1 does, so the road model holds 0.24 of the probability on average (its share at the
  // chain's balance, tau 30 of 70 among the moving models, is 0.43), and the across-road error
  // falls by a fifth (0.85 against 1.08).
  const auto terrain = forkTerrain();
  auto truth = [](std::int32_t t) { return common::Vec2{2.0 + 1.5 * t, 30.0}; };
  auto run = [&](bool use_roads) {
    Harness h = roadHarness(use_roads, {{"measurement_sigma", 3.0}, {"false_alarm_density", 1e-6}});
    double squared_across = 0.0;
    int counted = 0;
    double road_probability = 0.0;
    for (std::int32_t t = 1; t <= 55; ++t) {
      common::Stream rng(11, common::Purpose::kNoiseExceedance, 0, t);
      const common::Vec2 p = truth(t);
      const double x = p.x + 3.0 * rng.normal();
      const double y = p.y + 3.0 * rng.normal();
      h.step(t, {observation(t, t, x, y, 1)});
      const auto tracks = h.engine.confirmedTracks();
      if (t < 15 || tracks.size() != 1) continue;
      squared_across += (tracks[0].y - 30.0) * (tracks[0].y - 30.0);
      ++counted;
      if (!use_roads) continue;
      for (const auto& leaf : h.engine.leaves()) {
        if (!leaf.best) continue;
        // The road model's estimate lies on its section, its velocity along the segment there
        // (past the junction at x = 50 a noisy estimate may be nearer the branch road).
        const auto& road_mode = leaf.imm.modes[SbmhtEngine::kRoadMode];
        REQUIRE(leaf.road_section >= 0);
        const auto& section = terrain->sections()[static_cast<std::size_t>(leaf.road_section)];
        const auto foot = common::footPoint(section.points, {road_mode.x(common::kX), road_mode.x(common::kY)});
        REQUIRE(foot);
        CHECK(foot->distance == Approx(0.0).margin(1e-9));
        const double across = -foot->direction.y * road_mode.x(common::kVx) + foot->direction.x * road_mode.x(common::kVy);
        CHECK(across == Approx(0.0).margin(1e-9));
        road_probability += leaf.imm.probabilities(static_cast<Eigen::Index>(SbmhtEngine::kRoadMode));
      }
    }
    REQUIRE(counted >= 35);  // confirmed under one id from tick 15 on (at most 5 ticks to confirm)
    return std::make_pair(std::sqrt(squared_across / counted), road_probability / counted);
  };
  const auto [a2_across, a2_unused] = run(false);
  const auto [a1_across, a1_road_probability] = run(true);
  INFO("RMS across-road error: algorithm 1 " << a1_across << ", algorithm 2 " << a2_across
                                             << "; mean road-model probability " << a1_road_probability);
  CHECK(a1_road_probability > 0.1);
  CHECK(a1_road_probability < 0.43);  // below its share at balance: the evidence favours the quiet CV model
  CHECK(a1_across < 0.9 * a2_across);
}

TEST_CASE("sbmht algorithm 1 equals algorithm 2 away from the roads", "[sbmht]") {
  // Off road the road model is off: nothing switches into it, so a target that never comes within
  // road_gate_distance (15) of a road has the estimates algorithm 2 gives it, to rounding.
  auto truth = [](std::int32_t t) { return common::Vec2{10.0 + 1.2 * t, 80.0 - 0.2 * t}; };
  auto run = [&](bool use_roads) {
    Harness h = roadHarness(use_roads);
    std::vector<common::TrackEstimate> out;
    for (std::int32_t t = 1; t <= 40; ++t) {
      common::Stream rng(5, common::Purpose::kNoiseExceedance, 0, t);
      const common::Vec2 p = truth(t);
      if (rng.uniform() < 0.1) {
        h.step(t);
      } else {
        h.step(t, {observation(t, t, p.x + 0.4 * rng.normal(), p.y + 0.4 * rng.normal(), 1)});
      }
      for (const auto& leaf : h.engine.leaves()) CHECK(leaf.road_section == -1);
      const auto tracks = h.engine.confirmedTracks();
      out.insert(out.end(), tracks.begin(), tracks.end());
    }
    return out;
  };
  const auto a2 = run(false);
  const auto a1 = run(true);
  REQUIRE(a1.size() == a2.size());
  REQUIRE(a1.size() >= 30);
  for (std::size_t k = 0; k < a1.size(); ++k) {
    CHECK(a1[k].track == a2[k].track);
    CHECK(a1[k].x == Approx(a2[k].x).margin(1e-9));
    CHECK(a1[k].y == Approx(a2[k].y).margin(1e-9));
    CHECK(a1[k].vx == Approx(a2[k].vx).margin(1e-9));
  }
}

/// Where a target that left points[0] `travelled` ago along the polyline is, and its unit direction.
std::pair<common::Vec2, common::Vec2> alongPolyline(const std::vector<common::Vec2>& points, double travelled) {
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    const common::Vec2 a = points[k];
    const common::Vec2 b = points[k + 1];
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    const common::Vec2 u{(b.x - a.x) / length, (b.y - a.y) / length};
    if (travelled <= length || k + 2 == points.size())
      return {{a.x + travelled * u.x, a.y + travelled * u.y}, u};
    travelled -= length;
  }
  return {points.back(), {0.0, 0.0}};
}

TEST_CASE("sbmht follows a target round a bend hidden by a building, algorithm 1 better (S2)", "[sbmht]") {
  // Spec check S2: a target on a curved road through a masked gap. A sensor at (60, -100) places
  // it (R = I) wherever it sees it; the building [55, 65] x [-60, -50] hides the bend (26 ticks).
  // While the models' predictions are hidden, Pe = 0: no likelihood moves (C2), the mode
  // probabilities follow the Markov chain alone and the track coasts. Algorithm 2's CV models run
  // straight on, out of the shadow while the target is still in it, where silence makes them
  // unlikely and the stop model rises to 0.57; algorithm 1's road model follows the bend and stays
  // in the shadow with the target, and the stop model stays at 0.32 or less. Its estimate is nearer
  // the hidden target (mean 6.8 against 8.3 over the hidden ticks; the road model holds only what
  // the chain gives it) and keeps within the gate (TLR 1 against 0.96).
  // TLR here: the share of the ticks after the track's confirmation in which a confirmed track
  // under its first id lies within 15 of the target (an association gate, as the metrics use).
  const std::vector<common::Vec2> road{{0.0, 20.0}, {40.0, 20.0}, {52.0, 26.0}, {60.0, 36.0}, {80.0, 44.0}, {100.0, 48.0}};
  common::TerrainConfig config;
  config.roads.push_back({"bend", road});
  config.masks.push_back({"house", common::MaskKind::kBuilding, {{55, -60}, {65, -60}, {65, -50}, {55, -50}}});
  const auto terrain = std::make_shared<const common::Terrain>(config);
  const common::Vec2 at{60.0, -100.0};
  const common::SensorCoverage camera{1, at, 0.0, 2.0 * std::numbers::pi, 300.0, 0.95,
                                      common::SightBlockers::buildings_and_vegetation};
  const double speed = 1.5;
  const std::int32_t ticks = 70;  // 105 of the road's 108
  struct Outcome {
    double tlr = 0.0;
    double hidden_error = 0.0;  ///< mean distance to the target over the hidden ticks
    double max_stop = 0.0;      ///< largest mu_0 of the best leaf while hidden
    int hidden_ticks = 0;
  };
  auto run = [&](bool use_roads) {
    Harness h(sbmhtScenario({{"use_road_network", use_roads ? 1.0 : 0.0}}), [&](EngineContext& c) {
      c.coverage = {camera};
      c.terrain = terrain;
    });
    Outcome out;
    common::TrackId id = 0;
    int followed = 0;
    int since_confirmed = 0;
    for (std::int32_t t = 1; t <= ticks; ++t) {
      const auto [p, u] = alongPolyline(road, speed * t);
      const bool hidden = common::hiddenBy(terrain.get(), camera.blockers, at, p);
      std::vector<common::Observation> reports;
      if (!hidden)
        reports.push_back(sensed(t, 1, {at.x, at.y, 0.0, 0.0}, common::MeasurementKind::position, p,
                                 {speed * u.x, speed * u.y}, {1.0, 1.0}, 1e-4));
      h.step(t, reports);
      const auto tracks = h.engine.confirmedTracks();
      if (id == 0 && !tracks.empty()) id = tracks.front().track;
      if (id == 0) continue;
      ++since_confirmed;
      const auto* track = findTrack(tracks, id);
      if (track && distance(*track, p) <= 15.0) ++followed;
      if (!hidden) continue;
      REQUIRE(track != nullptr);
      ++out.hidden_ticks;
      out.hidden_error += distance(*track, p);
      const auto* leaf = bestLeaf(h.engine, id);
      REQUIRE(leaf != nullptr);
      out.max_stop = std::max(out.max_stop, leaf->imm.probabilities(0));
    }
    REQUIRE(since_confirmed >= ticks - 5);
    out.tlr = static_cast<double>(followed) / since_confirmed;
    out.hidden_error /= std::max(out.hidden_ticks, 1);
    return out;
  };
  const Outcome a2 = run(false);
  const Outcome a1 = run(true);
  INFO("algorithm 1: TLR " << a1.tlr << ", mean hidden error " << a1.hidden_error << ", max mu0 " << a1.max_stop
                           << "; algorithm 2: TLR " << a2.tlr << ", " << a2.hidden_error << ", " << a2.max_stop
                           << "; hidden " << a1.hidden_ticks << " ticks");
  REQUIRE(a1.hidden_ticks >= 12);  // the building does hide the bend
  CHECK(a1.max_stop < 0.5);        // no stop activation behind the building (C2)
  CHECK(a1.tlr >= 0.9);
  CHECK(a1.tlr >= a2.tlr);
  CHECK(a1.hidden_error < a2.hidden_error);
}

TEST_CASE("sbmht rejects use_road_network outside 0 and 1", "[sbmht]") {
  CHECK_THROWS_WITH(sbmhtScenario({{"use_road_network", 2.0}}), Catch::Contains("use_road_network"));
}

}  // namespace
}  // namespace wsn::supernode::sbmht

#include "supernode/rulebased/rulebased_engine.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "common/rng.hpp"
#include "supernode/gnn/gnn_engine.hpp"
#include "supernode/observation_window.hpp"

namespace wsn::supernode::rulebased {
namespace {

constexpr double kDs = 25.0;
constexpr int kColumns = 50;

/// The paper's field (An et al. 2014 §2): 1250 m square, a 50 x 50 grid at Ds = 25 m, one fusion
/// centre, engine "rulebased" with its defaults except `params`.
common::Scenario fieldScenario(std::initializer_list<std::pair<const char*, double>> params = {}) {
  common::Scenario s;
  s.source_path = "test.yaml";
  s.region = {0.0, 0.0, 1250.0, 1250.0};
  s.sensors.spacing = kDs;
  s.supernodes = {{625.0, 625.0}};
  s.dynamics.process_noise_sigma = 0.0;
  s.tracker.engine = "rulebased";
  for (const auto& [name, value] : params) s.tracker.params[name] = {value, 0};
  resolveEngineParams(s, wsn::common::kNoStatistics);
  return s;
}

/// A target in straight-line motion (metres, metres per tick) heard within its sensing range SR,
/// present from `first` to `last` tick.
struct Mover {
  common::Vec2 origin;  ///< position at tick 0
  common::Vec2 velocity;
  double sensing_range = 40.0;
  std::int32_t first = 1;
  std::int32_t last = std::numeric_limits<std::int32_t>::max();
  common::Vec2 at(std::int32_t tick) const { return origin + static_cast<double>(tick) * velocity; }
  bool present(std::int32_t tick) const { return tick >= first && tick <= last; }
};

common::Vec2 sensorPosition(int i, int j) { return {12.5 + kDs * i, 12.5 + kDs * j}; }
common::SensorId sensorId(int i, int j) { return static_cast<common::SensorId>(j * kColumns + i); }

/// Synthetic detections of `tick`: each grid sensor within SR of a present target reports
/// ws = sum over targets of floor((SR / d)^2) (eq. 4 with alpha = 2 and Pt = SR^2, quantised per
/// target; d floored at 1 m), attributed to the loudest target.
std::vector<common::Observation> detections(std::int32_t tick, const std::vector<Mover>& movers) {
  std::vector<common::Observation> out;
  for (int j = 0; j < kColumns; ++j)
    for (int i = 0; i < kColumns; ++i) {
      const common::Vec2 s = sensorPosition(i, j);
      std::int32_t level = 0;
      double loudest = 0.0;
      common::TargetId target = common::kFalseAlarm;
      for (std::size_t k = 0; k < movers.size(); ++k) {
        if (!movers[k].present(tick)) continue;
        const double d = std::max(common::distance(s, movers[k].at(tick)), 1.0);
        if (d > movers[k].sensing_range) continue;
        const double power = (movers[k].sensing_range / d) * (movers[k].sensing_range / d);
        level += static_cast<std::int32_t>(std::floor(power));
        if (power > loudest) {
          loudest = power;
          target = static_cast<common::TargetId>(k);
        }
      }
      if (target != common::kFalseAlarm) out.push_back({tick, tick, sensorId(i, j), s.x, s.y, target, level});
    }
  return out;
}

/// The smallest sensor id among the detections of `mover` alone at `tick`: the first sensor of
/// its cluster, which names the track born from it (common::track_id::birth).
common::SensorId firstSensor(std::int32_t tick, const Mover& mover) {
  const auto seen = detections(tick, {mover});
  REQUIRE(!seen.empty());
  return seen.front().sensor;  // generated in row-major order
}

/// A window and an engine built by the registry for supernode 0, stepped the way SupernodeTracker
/// steps them, used through the Engine interface.
class Harness {
 public:
  explicit Harness(common::Scenario s)
      : scenario_(std::move(s)), window_(scenario_.tracker.window_size), engine_(makeEngine(engineContext(scenario_, 0))) {}
  Harness(const Harness&) = delete;
  Harness& operator=(const Harness&) = delete;

  void step(std::int32_t tick, const std::vector<common::Observation>& delivered) {
    window_.advanceTo(tick);
    for (const auto& o : delivered) window_.insert(o);
    engine_->step(window_);
  }
  void step(std::int32_t tick, const std::vector<Mover>& movers) { step(tick, detections(tick, movers)); }
  void run(std::int32_t from, std::int32_t to, const std::vector<Mover>& movers) {
    for (std::int32_t t = from; t <= to; ++t) step(t, movers);
  }

  Engine& engine() { return *engine_; }
  std::vector<common::TrackEstimate> tracks() const { return engine_->confirmedTracks(); }
  /// What only the rule-based engine tells: its statistics and last clusters.
  const RulebasedEngine& rulebased() const { return dynamic_cast<const RulebasedEngine&>(*engine_); }

 private:
  common::Scenario scenario_;
  ObservationWindow window_;
  std::unique_ptr<Engine> engine_;
};

struct Nearest {
  common::TrackId track = 0;
  double distance = std::numeric_limits<double>::infinity();
};

/// The track nearest to `p`.
Nearest nearestTrack(const std::vector<common::TrackEstimate>& tracks, common::Vec2 p) {
  Nearest best;
  for (const auto& t : tracks) {
    const double d = common::distance({t.x, t.y}, p);
    if (d < best.distance) best = {t.track, d};
  }
  return best;
}

const common::TrackEstimate* findTrack(const std::vector<common::TrackEstimate>& tracks, common::TrackId id) {
  for (const auto& t : tracks)
    if (t.track == id) return &t;
  return nullptr;
}

/// The Engine contract and the filter's invariants: sorted unique ids, finite states, symmetric
/// covariances with positive variances.
void checkInvariants(const std::vector<common::TrackEstimate>& tracks) {
  for (std::size_t n = 0; n < tracks.size(); ++n) {
    const auto& t = tracks[n];
    if (n > 0) CHECK(tracks[n - 1].track < t.track);
    CHECK(common::isFinite(t));
    for (int r = 0; r < 4; ++r) {
      CHECK(t.covariance[static_cast<std::size_t>(r * 4 + r)] > 0.0);
      for (int c = 0; c < r; ++c)
        CHECK(t.covariance[static_cast<std::size_t>(r * 4 + c)] ==
              Approx(t.covariance[static_cast<std::size_t>(c * 4 + r)]).margin(1e-9));
    }
  }
}

TEST_CASE("the registry builds the rule-based engine for tracker.engine rulebased", "[rulebased]") {
  Harness h(fieldScenario());
  CHECK(h.rulebased().stats().ticks == 0);
  CHECK(h.tracks().empty());
  CHECK(h.engine().predictions().empty());
}

TEST_CASE("a single target is tracked within a few metres under one identity", "[rulebased]") {
  // 20 m/s = 2 m per tick of 0.1 s, heading (0.8, 0.6); SR = 40 m: about 8 detecting sensors.
  Harness h(fieldScenario());
  const Mover target{{300, 400}, {1.6, 1.2}, 40};
  // Tick 1: a birth candidate; tick 2: confirm_ticks = 2 sightings make the track, named after
  // the first sighting's tick and smallest sensor id (common::track_id::birth).
  h.step(1, std::vector{target});
  CHECK(h.tracks().empty());
  const common::TrackId id = common::track_id::birth(0, 1, firstSensor(1, target));
  double squared_error_sum = 0.0;
  for (std::int32_t t = 2; t <= 60; ++t) {
    h.step(t, std::vector{target});
    const auto tracks = h.tracks();
    INFO("tick " << t);
    checkInvariants(tracks);
    REQUIRE(tracks.size() == 1);
    CHECK(tracks[0].track == id);
    CHECK(tracks[0].last_seen_tick == t);
    const double error = common::distance({tracks[0].x, tracks[0].y}, target.at(t));
    // The weighted centroid of an SR = 40 m footprint on the 25 m grid is off the target by at most
    // 5.2 m (3.6 m RMS) over random positions (computed offline from the same generator); the track
    // is never worse than a quarter of Ds, 6.25 m.
    CHECK(error < 0.25 * kDs);
    if (t > 20) squared_error_sum += error * error;
  }
  // Once the two-point velocity has settled the filter averages the centroid errors out: its RMS
  // error over ticks 21-60 is below the centroids' own 3.6 m (1.2 m when this test was written).
  CHECK(std::sqrt(squared_error_sum / 40.0) < 2.5);
  const auto last = h.tracks().at(0);
  CHECK(last.vx == Approx(1.6).margin(0.2));
  CHECK(last.vy == Approx(1.2).margin(0.2));
  // predictions() is the constant-velocity step of the state: x + vx (delta = 1 tick).
  REQUIRE(h.engine().predictions().size() == 1);
  CHECK(h.engine().predictions()[0].track == id);
  CHECK(h.engine().predictions()[0].next_position.x == Approx(last.x + last.vx).margin(1e-9));
  CHECK(h.engine().predictions()[0].next_position.y == Approx(last.y + last.vy).margin(1e-9));
}

/// What a run of crossing targets showed: per tick, the number of clusters and the track nearest
/// to each target.
struct CrossingRun {
  std::vector<std::size_t> clusters;                 ///< index tick - 1
  std::vector<std::size_t> tracks;                   ///< confirmed tracks per tick
  std::vector<std::vector<Nearest>> nearest;         ///< per tick, per target
  std::int64_t merges = 0;
  std::int32_t first_merged = 0;  ///< first tick with fewer clusters than targets (0: none)
  std::int32_t last_merged = 0;   ///< last such tick
};

CrossingRun runCrossing(Harness& h, const std::vector<Mover>& movers, std::int32_t ticks) {
  CrossingRun run;
  for (std::int32_t t = 1; t <= ticks; ++t) {
    h.step(t, movers);
    const auto tracks = h.tracks();
    checkInvariants(tracks);
    run.clusters.push_back(h.rulebased().lastClusters().size());
    run.tracks.push_back(tracks.size());
    std::vector<Nearest> nearest;
    for (const auto& m : movers) nearest.push_back(nearestTrack(tracks, m.at(t)));
    run.nearest.push_back(nearest);
    if (run.clusters.back() < movers.size()) {
      if (run.first_merged == 0) run.first_merged = t;
      run.last_merged = t;
    }
  }
  run.merges = h.rulebased().stats().merges;
  return run;
}

/// Checks that each target's nearest track after the last merge is the one nearest to it at the tick
/// before the first merge, that the identities were distinct, and that no track was lost or added.
void checkIdentitiesKept(const CrossingRun& run, std::size_t targets, std::int32_t ticks) {
  REQUIRE(run.first_merged > 2);  // the tracks were born before the clusters merged
  REQUIRE(run.last_merged < ticks - 10);  // and the clusters split again well before the end
  const auto& before = run.nearest[static_cast<std::size_t>(run.first_merged - 2)];
  for (std::size_t k = 0; k < targets; ++k)
    for (std::size_t l = k + 1; l < targets; ++l) CHECK(before[k].track != before[l].track);
  // Through the merge every identity lives on (Rule 3), and no cluster is taken for a new target.
  for (std::int32_t t = run.first_merged - 1; t <= ticks; ++t) {
    INFO("tick " << t);
    CHECK(run.tracks[static_cast<std::size_t>(t - 1)] == targets);
  }
  for (std::int32_t t = run.last_merged + 1; t <= ticks; ++t)
    for (std::size_t k = 0; k < targets; ++k) {
      INFO("tick " << t << " (merged " << run.first_merged << "-" << run.last_merged << "), target " << k);
      const auto& now = run.nearest[static_cast<std::size_t>(t - 1)][k];
      CHECK(now.track == before[k].track);
    }
  // Once apart, each target is tracked closely again.
  for (std::size_t k = 0; k < targets; ++k) {
    INFO("target " << k);
    CHECK(run.nearest.back()[k].distance < 0.25 * kDs);
  }
}

TEST_CASE("two targets crossing in an X keep their identities through the merge and split", "[rulebased]") {
  // Both at 20 m/s (2 m per tick), crossing at (625, 625) at tick 100 at +-angle from the x axis.
  // With SR = 30-40 m the clusters join when the targets are about SR_a + SR_b + 1.5 Ds apart, so
  // they stay merged for tens of ticks around tick 100 and split again well before tick 200.
  struct Case {
    double sr_a, sr_b, angle_deg;
  };
  const auto c = GENERATE(Case{40, 35, 45}, Case{30, 30, 45}, Case{40, 40, 30}, Case{40, 35, 20}, Case{35, 30, 70});
  INFO("SR " << c.sr_a << " and " << c.sr_b << ", paths at +-" << c.angle_deg << " degrees");
  const double a = c.angle_deg * std::numbers::pi / 180.0;
  const common::Vec2 cross{625, 625};
  const common::Vec2 va{2.0 * std::cos(a), 2.0 * std::sin(a)};
  const common::Vec2 vb{2.0 * std::cos(a), -2.0 * std::sin(a)};
  const std::vector<Mover> movers = {{cross - 100.0 * va, va, c.sr_a}, {cross - 100.0 * vb, vb, c.sr_b}};
  Harness h(fieldScenario());
  const auto run = runCrossing(h, movers, 200);
  CHECK(run.merges > 0);  // Rule 1 merged the pair
  checkIdentitiesKept(run, 2, 200);
}

TEST_CASE("three clusters merging into one and splitting keep their three identities", "[rulebased]") {
  const std::int32_t ticks = 200;
  std::vector<Mover> movers;
  SECTION("2014 Table 1, second scenario: three targets meet near (345, 295)") {
    movers = {{{200, 100}, {1.3, 1.7}, 40}, {{150, 260}, {2.0, 0.5}, 30}, {{200, 400}, {1.7, -1.3}, 30}};
  }
  SECTION("three targets at 120 degrees through one point at tick 100") {
    for (int k = 0; k < 3; ++k) {
      const double a = 0.3 + k * 2.0 * std::numbers::pi / 3.0;
      const common::Vec2 v{2.0 * std::cos(a), 2.0 * std::sin(a)};
      movers.push_back({common::Vec2{625, 625} - 100.0 * v, v, 40.0 - 5.0 * k});
    }
  }
  Harness h(fieldScenario());
  const auto run = runCrossing(h, movers, ticks);
  // All three in one cluster at some tick: two pairs (at least) merged by Rule 1.
  CHECK(std::count(run.clusters.begin(), run.clusters.end(), std::size_t{1}) > 0);
  CHECK(run.merges >= 2);
  checkIdentitiesKept(run, 3, ticks);
}

TEST_CASE("a target that appears mid-run gets a new track after confirm_ticks sightings", "[rulebased]") {
  const std::int32_t confirm = GENERATE(2, 3, 5);
  INFO("confirm_ticks " << confirm);
  Harness h(fieldScenario({{"confirm_ticks", confirm}}));
  // `stays` is tracked from the start; `comes` appears at tick 31, 400 m away from it (beyond the
  // claim reach r_a + r_d + 2 Ds of about 120 m, so its cluster is nobody's: a birth candidate).
  const Mover stays{{200, 200}, {1.5, 0.5}, 40};
  const Mover comes{{900, 900}, {-1.0, 0.0}, 35, 31};
  const std::vector<Mover> movers = {stays, comes};
  h.run(1, 30, movers);
  REQUIRE(h.tracks().size() == 1);
  const common::TrackId old_id = h.tracks()[0].track;
  CHECK(old_id == common::track_id::birth(0, 1, firstSensor(1, stays)));
  // Sightings 1 .. confirm - 1 (ticks 31 .. 29 + confirm) leave it a candidate; the confirm-th
  // sighting, tick 30 + confirm, makes the track, named after its first sighting (tick 31).
  for (std::int32_t t = 31; t < 30 + confirm; ++t) {
    h.step(t, movers);
    INFO("tick " << t);
    CHECK(h.tracks().size() == 1);
  }
  h.step(30 + confirm, movers);
  const auto tracks = h.tracks();
  checkInvariants(tracks);
  REQUIRE(tracks.size() == 2);
  const common::TrackId new_id = common::track_id::birth(0, 31, firstSensor(31, comes));
  CHECK(nearestTrack(tracks, stays.at(30 + confirm)).track == old_id);
  CHECK(nearestTrack(tracks, comes.at(30 + confirm)).track == new_id);
  CHECK(h.rulebased().stats().births == 2);
  h.run(31 + confirm, 60, movers);
  CHECK(h.tracks().size() == 2);
  CHECK(nearestTrack(h.tracks(), comes.at(60)).track == new_id);
  CHECK(nearestTrack(h.tracks(), comes.at(60)).distance < 0.25 * kDs);
}

/// Runs `stays` and `goes` (which falls silent after tick `last_seen`) and checks that `goes`'s track
/// coasts for max_coast_ticks ticks and is deleted at the next, while `stays` keeps its track.
void checkDeletedAfterCoasting(Harness& h, const Mover& stays, const Mover& goes, std::int32_t max_coast) {
  const std::int32_t last_seen = goes.last;
  const std::vector<Mover> movers = {stays, goes};
  h.run(1, last_seen, movers);
  REQUIRE(h.tracks().size() == 2);
  const common::TrackId kept = nearestTrack(h.tracks(), stays.at(last_seen)).track;
  const common::TrackId gone = nearestTrack(h.tracks(), goes.at(last_seen)).track;
  REQUIRE(kept != gone);
  // Misses 1 .. max_coast (ticks last_seen + 1 .. last_seen + max_coast) keep the track, coasting
  // from its last observation; miss max_coast + 1 deletes it.
  for (std::int32_t t = last_seen + 1; t <= last_seen + max_coast; ++t) {
    h.step(t, movers);
    INFO("tick " << t);
    const auto tracks = h.tracks();
    REQUIRE(tracks.size() == 2);
    const auto* coasting = findTrack(tracks, gone);
    REQUIRE(coasting != nullptr);
    CHECK(coasting->last_seen_tick == last_seen);
    CHECK(findTrack(tracks, kept)->last_seen_tick == t);
  }
  h.step(last_seen + max_coast + 1, movers);
  const auto tracks = h.tracks();
  REQUIRE(tracks.size() == 1);
  CHECK(tracks[0].track == kept);
  CHECK(h.rulebased().stats().deletions == 1);
  CHECK(h.rulebased().stats().births == 2);
}

TEST_CASE("a target that disappears is deleted after max_coast_ticks", "[rulebased]") {
  const std::int32_t max_coast = GENERATE(3, 10);  // 10: the default
  INFO("max_coast_ticks " << max_coast);
  Harness h(fieldScenario({{"max_coast_ticks", max_coast}}));
  // Far apart (400 m): the silent target's track has nothing to confuse it with.
  const Mover stays{{200, 600}, {2.0, 0.0}, 40};
  Mover goes{{600, 300}, {0.0, 2.0}, 40};
  goes.last = 30;
  checkDeletedAfterCoasting(h, stays, goes, max_coast);
}

TEST_CASE("a target that disappears 120 m from another is deleted after max_coast_ticks", "[rulebased]") {
  // Two targets side by side, 120 m apart, at the same velocity. Their clusters are separate (the
  // nearest sensors of the two SR = 40 m footprints are at least 120 - 2 * 40 = 40 m > 1.5 Ds apart),
  // so when `goes` falls silent after tick 30 nothing merged: its track should coast and be deleted
  // after max_coast_ticks = 10, at tick 41, like the lone target above.
  // A regression test: with one cluster left for two tracks (Case 2), Rule 1 alone merges the pair,
  // its eq. 22 gap 115.9 - 2 * 35.4 = 45.2 m being within max_merge_gap = 3 Ds = 75 m, although the
  // remaining cluster did not grow (8 sensors before and after); the silent track, re-merged every
  // tick at that gap, then counted merged ticks instead of misses and lived until max_merge_ticks
  // (600 ticks). The engine now keeps a track whose prediction is outside the cluster's reach out of
  // the merge.
  Harness h(fieldScenario());
  const Mover stays{{300, 600}, {2.0, 0.0}, 40};
  Mover goes{{300, 720}, {2.0, 0.0}, 40};
  goes.last = 30;
  checkDeletedAfterCoasting(h, stays, goes, 10);
}

TEST_CASE("two targets merged at the start become two tracks when they split", "[rulebased]") {
  // 30 m apart and diverging at 3 m per tick: one cluster at first (the paper's third assumption,
  // no merged cluster at the start, does not hold), two once the footprints are 1.5 Ds apart.
  const std::vector<Mover> movers = {{{600, 600}, {-1.5, 0.0}, 40}, {{630, 600}, {1.5, 0.0}, 40}};
  Harness h(fieldScenario());
  h.step(1, movers);
  CHECK(h.rulebased().lastClusters().size() == 1);
  for (std::int32_t t = 2; t <= 80; ++t) {
    h.step(t, movers);
    const auto tracks = h.tracks();
    INFO("tick " << t);
    checkInvariants(tracks);
    CHECK(tracks.size() <= 2);  // never more tracks than targets
  }
  CHECK(h.rulebased().lastClusters().size() == 2);
  const auto tracks = h.tracks();
  REQUIRE(tracks.size() == 2);
  const auto a = nearestTrack(tracks, movers[0].at(80));
  const auto b = nearestTrack(tracks, movers[1].at(80));
  CHECK(a.track != b.track);
  CHECK(a.distance < 0.25 * kDs);
  CHECK(b.distance < 0.25 * kDs);
}

/// Environmental noise that lasts a single tick (2013 §3.1 with a duration of 0.1 s): at each tick
/// every sensor whose column + row has the tick's parity is noisy with probability 4 % (about 2 % of
/// all sensors), ws = 1 (eq. 6: between one and two thresholds). The parity alternates, so no
/// sensor is noisy at two consecutive ticks. Sensors within the sensing range of a mover at any of
/// ticks k - 2 .. k + 2 are spared, so that noise never lands on a sensor that also hears a target
/// in the 3-tick persistence window; those just outside it do get noise, which links into the
/// target's cluster.
std::vector<common::Observation> singleTickNoise(std::int32_t tick, const std::vector<Mover>& movers) {
  common::Stream random(2013, common::Purpose::kSensorNoise, 0, tick);
  std::vector<common::Observation> out;
  for (int j = 0; j < kColumns; ++j)
    for (int i = 0; i < kColumns; ++i) {
      if ((i + j + tick) % 2 != 0) continue;
      if (!random.bernoulli(0.04)) continue;
      const common::Vec2 s = sensorPosition(i, j);
      bool near_target = false;
      for (const auto& m : movers)
        for (std::int32_t k = tick - 2; k <= tick + 2; ++k)
          near_target = near_target || common::distance(s, m.at(k)) <= m.sensing_range + 1.0;
      if (!near_target) out.push_back({tick, tick, sensorId(i, j), s.x, s.y, common::kFalseAlarm, 1});
    }
  return out;
}

std::vector<common::Observation> withNoise(std::int32_t tick, const std::vector<Mover>& movers) {
  auto observed = detections(tick, movers);
  const auto noise = singleTickNoise(tick, movers);
  observed.insert(observed.end(), noise.begin(), noise.end());
  return observed;
}

TEST_CASE("with denoise, scattered single-tick noise alone makes no track", "[rulebased]") {
  // About 50 noisy sensors per tick for 100 ticks and no target: the persistence test (eq. 11) needs
  // three consecutive ticks and removes every noisy detection, so nothing is ever clustered.
  Harness h(fieldScenario({{"denoise", 1}}));
  std::int64_t noisy = 0;
  for (std::int32_t t = 1; t <= 100; ++t) {
    const auto noise = singleTickNoise(t, {});
    noisy += static_cast<std::int64_t>(noise.size());
    h.step(t, noise);
    INFO("tick " << t);
    CHECK(h.tracks().empty());
    CHECK(h.rulebased().lastClusters().empty());
  }
  CHECK(noisy > 100 * 30);  // about 2 % of 2500 sensors per tick really were noisy
  CHECK(h.rulebased().stats().detections_in == noisy);
  CHECK(h.rulebased().stats().detections_kept == 0);
  CHECK(h.rulebased().stats().births == 0);
}

TEST_CASE("with denoise, scattered single-tick noise does not move the track", "[rulebased]") {
  // One target at 20 m/s with the noise above, some of it next to the target's footprint. With
  // denoise the noise never passes eq. 11, so the engine sees exactly what it sees without noise:
  // the tracks are identical, bit for bit, at every tick.
  const std::vector<Mover> movers = {{{300, 500}, {2.0, 0.0}, 40}};
  Harness clean(fieldScenario({{"denoise", 1}}));
  Harness noisy(fieldScenario({{"denoise", 1}}));
  Harness plain_clean(fieldScenario());
  Harness plain_noisy(fieldScenario());
  double plain_deviation = 0.0;
  for (std::int32_t t = 1; t <= 80; ++t) {
    clean.step(t, movers);
    noisy.step(t, withNoise(t, movers));
    plain_clean.step(t, movers);
    plain_noisy.step(t, withNoise(t, movers));
    INFO("tick " << t);
    REQUIRE(noisy.tracks() == clean.tracks());
    // Persistence delays the track by two ticks: detections pass from tick 3, the track is born at 4.
    CHECK(noisy.tracks().size() == (t >= 4 ? 1u : 0u));
    const auto a = plain_clean.tracks();
    const auto b = plain_noisy.tracks();
    if (!a.empty() && !b.empty()) plain_deviation = std::max(plain_deviation, std::hypot(a[0].x - b[0].x, a[0].y - b[0].y));
  }
  CHECK(noisy.rulebased().stats().births == 1);
  CHECK(noisy.rulebased().stats().detections_kept == clean.rulebased().stats().detections_kept);
  CHECK(noisy.rulebased().stats().detections_in > clean.rulebased().stats().detections_in);
  CHECK(nearestTrack(noisy.tracks(), movers[0].at(80)).distance < 0.25 * kDs);
  // The noise matters: without denoise the noisy sensors that link into the target's cluster pull
  // its centroid, so the track drifts from the noise-free one (2.3 m at most when this test was
  // written), and pairs of noise clusters seen at consecutive ticks near each other pass for new
  // targets (80 births).
  CHECK(plain_deviation > 1.0);
  CHECK(plain_noisy.rulebased().stats().births > 1);
  CHECK(plain_clean.rulebased().stats().births == 1);
}

TEST_CASE("with quick_solution, a cluster's measurement is its strongest sensor", "[rulebased]") {
  // A new track starts at its last measurement with the two-point velocity (difference of the last
  // two measurements, delta = 1 tick). A row of three sensors with ws = 1, 1, 5 at tick 1 (columns
  // 10-12, row 10) moves one column right at tick 2:
  //   quick solution: z = the ws = 5 sensor, x = 312.5 then 337.5 -> track x = 337.5, vx = 25;
  //   weighted centroid: (262.5 + 287.5 + 5 * 312.5) / 7 = 2112.5 / 7 = 301.79, then 326.79,
  //   vx = 25. Both at y = 262.5.
  const auto row = [](std::int32_t tick, int first_column) {
    std::vector<common::Observation> out;
    const std::int32_t levels[] = {1, 1, 5};
    for (int n = 0; n < 3; ++n) {
      const auto s = sensorPosition(first_column + n, 10);
      out.push_back({tick, tick, sensorId(first_column + n, 10), s.x, s.y, 0, levels[n]});
    }
    return out;
  };
  Harness quick(fieldScenario({{"quick_solution", 1}}));
  Harness centroid(fieldScenario());
  for (Harness* h : {&quick, &centroid}) {
    h->step(1, row(1, 10));
    h->step(2, row(2, 11));
  }
  REQUIRE(quick.tracks().size() == 1);
  CHECK(quick.tracks()[0].x == Approx(337.5).margin(1e-9));
  CHECK(quick.tracks()[0].y == Approx(262.5).margin(1e-9));
  CHECK(quick.tracks()[0].vx == Approx(25.0).margin(1e-9));
  REQUIRE(centroid.tracks().size() == 1);
  CHECK(centroid.tracks()[0].x == Approx(2112.5 / 7.0 + 25.0).margin(1e-9));
  CHECK(centroid.tracks()[0].vx == Approx(25.0).margin(1e-9));

  // A moving target with SR = 40 m: the strongest sensor is within half a diagonal (17.7 m) of
  // it, and the paper (2013 Fig. 3b) finds SR >= 40 m tracks accurately with the quick solution.
  // The born track sits exactly on the strongest sensor of tick 2's cluster.
  const std::vector<Mover> movers = {{{300, 300}, {2.0, 1.0}, 40}};
  Harness moving(fieldScenario({{"quick_solution", 1}}));
  moving.run(1, 2, movers);
  REQUIRE(moving.tracks().size() == 1);
  REQUIRE(moving.rulebased().lastClusters().size() == 1);
  const auto strongest = moving.rulebased().lastClusters()[0].strongest;
  CHECK(moving.tracks()[0].x == strongest.x);
  CHECK(moving.tracks()[0].y == strongest.y);
  moving.run(3, 60, movers);
  REQUIRE(moving.tracks().size() == 1);
  CHECK(nearestTrack(moving.tracks(), movers[0].at(60)).distance < 0.5 * kDs);
}

TEST_CASE("a released track's handoff carries its state, and adopted it continues under its id", "[rulebased]") {
  const std::vector<Mover> movers = {{{500, 600}, {2.0, 0.0}, 40}};
  Harness from(fieldScenario());
  from.run(1, 30, movers);
  const auto before = from.tracks();
  REQUIRE(before.size() == 1);
  const auto& track = before[0];
  const auto handoff = from.engine().release(track.track, 1);
  CHECK(handoff.track == track.track);
  CHECK(handoff.to_supernode == 1);
  CHECK(handoff.last_tick == 30);
  CHECK(handoff.state == std::array<double, 4>{track.x, track.y, track.vx, track.vy});
  CHECK(handoff.covariance == track.covariance);
  // Born at tick 2 with its 2 sightings as hits, then one hit per tick 3-30: 30.
  CHECK(handoff.hits == 30);
  CHECK(handoff.misses == 0);
  CHECK(handoff.confirmed);
  CHECK(from.tracks().empty());
  CHECK(from.engine().predictions().empty());
  // Releasing a track the engine does not have hands over nothing.
  CHECK(from.engine().release(track.track, 1) == common::TrackHandoff{});
  // The releasing side leaves the target's clusters to the neighbour: no new track there.
  from.run(31, 40, movers);
  CHECK(from.tracks().empty());

  Harness to(fieldScenario());
  to.run(1, 30, {});
  to.engine().adopt(handoff);
  // Adopted tracks are confirmed at once, with the handed-over state.
  REQUIRE(to.tracks().size() == 1);
  CHECK(to.tracks()[0].track == handoff.track);
  CHECK(to.tracks()[0].x == handoff.state[0]);
  CHECK(to.tracks()[0].vx == handoff.state[2]);
  CHECK(to.tracks()[0].last_seen_tick == 30);
  for (std::int32_t t = 31; t <= 60; ++t) {
    to.step(t, movers);
    INFO("tick " << t);
    const auto tracks = to.tracks();
    REQUIRE(tracks.size() == 1);
    CHECK(tracks[0].track == handoff.track);
    CHECK(tracks[0].last_seen_tick == t);
  }
  CHECK(to.rulebased().stats().births == 0);
  CHECK(nearestTrack(to.tracks(), movers[0].at(60)).distance < 0.25 * kDs);
}

TEST_CASE("two engines fed the same input produce identical tracks", "[rulebased]") {
  // Three targets that merge and split, with and without noise mitigation (and noise).
  const bool denoise = GENERATE(false, true);
  INFO("denoise " << denoise);
  const std::vector<Mover> movers = {
      {{200, 100}, {1.3, 1.7}, 40}, {{150, 260}, {2.0, 0.5}, 30}, {{200, 400}, {1.7, -1.3}, 30}};
  Harness a(fieldScenario({{"denoise", denoise ? 1.0 : 0.0}}));
  Harness b(fieldScenario({{"denoise", denoise ? 1.0 : 0.0}}));
  for (std::int32_t t = 1; t <= 200; ++t) {
    const auto observed = denoise ? withNoise(t, movers) : detections(t, movers);
    a.step(t, observed);
    b.step(t, observed);
    INFO("tick " << t);
    REQUIRE(a.tracks() == b.tracks());
    const auto pa = a.engine().predictions();
    const auto pb = b.engine().predictions();
    REQUIRE(pa.size() == pb.size());
    for (std::size_t n = 0; n < pa.size(); ++n) {
      CHECK(pa[n].track == pb[n].track);
      CHECK(pa[n].next_position == pb[n].next_position);
    }
  }
  CHECK(a.tracks().size() == 3);
  const auto& sa = a.rulebased().stats();
  const auto& sb = b.rulebased().stats();
  CHECK(sa.merges == sb.merges);
  CHECK(sa.births == sb.births);
  CHECK(sa.deletions == sb.deletions);
  CHECK(sa.detections_kept == sb.detections_kept);
}

TEST_CASE("a measurement lag of L ticks starts a track L velocities ahead of its measurement", "[rulebased]") {
  // z = x - L v (the centroid shows where the target was L ticks ago, docs/RULEBASED.md): with
  // L = 2 the born track sits 2 vx ahead of the unlagged one, which starts at its measurement.
  const std::vector<Mover> movers = {{{400, 412.5}, {2.0, 0.0}, 40}};
  Harness lagged(fieldScenario({{"measurement_lag", 2}}));
  Harness plain(fieldScenario());
  lagged.run(1, 2, movers);
  plain.run(1, 2, movers);
  REQUIRE(lagged.tracks().size() == 1);
  REQUIRE(plain.tracks().size() == 1);
  const auto p = plain.tracks()[0];
  CHECK(lagged.tracks()[0].x == Approx(p.x + 2.0 * p.vx).margin(1e-9));
  CHECK(lagged.tracks()[0].y == Approx(p.y + 2.0 * p.vy).margin(1e-9));
}

TEST_CASE("a decision lag lets delayed reports in and reports the tracks at the newest tick", "[rulebased]") {
  // Every report arrives 2 ticks late. Without a lag the engine processes each tick before its
  // reports arrive and sees nothing; with decision_lag = 2 it processes tick t - 2 once they are in,
  // and reports the state of tick t - 2 predicted to t.
  const Mover mover{{300, 400}, {2.0, 0.0}, 40};
  Harness eager(fieldScenario());
  Harness patient(fieldScenario({{"decision_lag", 2}}));
  for (std::int32_t t = 1; t <= 40; ++t) {
    std::vector<common::Observation> late = t > 2 ? detections(t - 2, {mover}) : std::vector<common::Observation>{};
    for (auto& o : late) o.tick_delivered = t;
    eager.step(t, late);
    patient.step(t, late);
  }
  CHECK(eager.tracks().empty());
  const auto tracks = patient.tracks();
  REQUIRE(tracks.size() == 1);
  CHECK(nearestTrack(tracks, mover.at(40)).distance < 0.25 * kDs);
  CHECK(patient.rulebased().identities().front().state_tick == 38);
  REQUIRE(patient.engine().predictions().size() == 1);
  CHECK(patient.engine().predictions()[0].next_position.x == Approx(tracks[0].x + tracks[0].vx));

  // The lagged tick must still be in the window (window_size 10).
  common::Scenario s = fieldScenario();
  s.tracker.params["decision_lag"] = {10, 7};
  CHECK_THROWS_WITH(resolveEngineParams(s, wsn::common::kNoStatistics),
                    "test.yaml:7: 'tracker.params.decision_lag' 10 must be below 'tracker.window_size' 10");
}

TEST_CASE("fused reports (level 0), one per target, start and keep tracks", "[rulebased]") {
  // Oh's sensors fuse their neighbours' readings (eq. 6): one report per target and tick, level 0.
  // It stands for all the sensors that heard the target, so birth_min_sensors = 2 does not stop it.
  Harness h(fieldScenario());
  for (std::int32_t t = 1; t <= 20; ++t) {
    const common::Vec2 p{300.0 + 2.0 * t, 500.0};
    h.step(t, std::vector<common::Observation>{{t, t, sensorId(12, 20), p.x, p.y, 0, 0}});
  }
  const auto tracks = h.tracks();
  REQUIRE(tracks.size() == 1);
  CHECK(tracks[0].x == Approx(340.0).margin(1.0));
  CHECK(tracks[0].vx == Approx(2.0).margin(0.2));
}

}  // namespace
}  // namespace wsn::supernode::rulebased

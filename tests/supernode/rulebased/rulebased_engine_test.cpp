#include "supernode/rulebased/rulebased_engine.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
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
  resolveEngineParams(s);
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

/// The smallest sensor id among the detections of target `k` alone at `tick`: the first sensor of
/// its cluster, which names the track born from it (gnn::birthTrackId).
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
      : scenario_(std::move(s)), window_(scenario_.tracker.window_size), engine_(makeEngine({scenario_, 0})) {}
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

TEST_CASE("explore single", "[explore]") {
  Harness h(fieldScenario());
  const Mover m{{300, 400}, {1.6, 1.2}, 40};
  for (int t = 1; t <= 60; ++t) {
    h.step(t, std::vector<Mover>{m});
    const auto tr = h.tracks();
    if (tr.empty()) { std::printf("t%d none\n", t); continue; }
    const auto p = m.at(t);
    std::printf("t%d n=%zu id=%llx err=%.2f v=(%.2f,%.2f) clusters=%zu\n", t, tr.size(), (unsigned long long)tr[0].track, std::hypot(tr[0].x-p.x, tr[0].y-p.y), tr[0].vx, tr[0].vy, h.rulebased().lastClusters().size());
  }
  std::printf("first sensor %u id %llx\n", firstSensor(1, m), (unsigned long long)gnn::birthTrackId(0, 1, firstSensor(1, m)));
}
void explore(const char* name, std::vector<Mover> movers, int ticks, bool verbose=false) {
  Harness h(fieldScenario());
  std::vector<common::TrackId> ids_before(movers.size());
  std::size_t prev_clusters = 0;
  bool merged_seen = false;
  std::printf("== %s\n", name);
  for (int t = 1; t <= ticks; ++t) {
    h.step(t, movers);
    const auto tr = h.tracks();
    const auto nc = h.rulebased().lastClusters().size();
    std::vector<Nearest> near;
    for (auto& m : movers) near.push_back(nearestTrack(tr, m.at(t)));
    if (verbose || nc != prev_clusters || t == ticks) {
      std::printf("t%d tracks=%zu clusters=%zu merges=%lld births=%lld del=%lld |", t, tr.size(), nc, (long long)h.rulebased().stats().merges, (long long)h.rulebased().stats().births, (long long)h.rulebased().stats().deletions);
      for (auto& n : near) std::printf(" %llx:%.1f", (unsigned long long)(n.track & 0xffffffffff), n.distance);
      std::printf("\n");
    }
    prev_clusters = nc;
  }
}
TEST_CASE("explore cross", "[explore]") {
  const double r = std::sqrt(2.0);
  const common::Vec2 c{625, 625};
  auto X = [&](double sa, double sb, double ang) {
    const double vx = 2*std::cos(ang), vy = 2*std::sin(ang);
    return std::vector<Mover>{{c - 100.0 * common::Vec2{vx, vy}, {vx, vy}, sa}, {c - 100.0 * common::Vec2{vx, -vy}, {vx, -vy}, sb}};
  };
  explore("X 40/35 45deg", X(40, 35, M_PI/4), 200);
  explore("X 40/40 45deg", X(40, 40, M_PI/4), 200);
  explore("X 30/30 45deg", X(30, 30, M_PI/4), 200);
  explore("X 40/35 30deg", X(40, 35, M_PI/6), 200);
  explore("X 40/35 20deg", X(40, 35, M_PI/9), 200);
  explore("X 40/35 60deg", X(40, 35, M_PI/3), 200);
  explore("X 40/35 80deg", X(40, 35, 80*M_PI/180), 200);
  explore("table1 s2", {{{200, 100}, {1.3, 1.7}, 40}, {{150, 260}, {2.0, 0.5}, 30}, {{200, 400}, {1.7, -1.3}, 30}}, 200);
  explore("table1 s1", {{{200, 100}, {1.5, 1.5}, 40}, {{150, 260}, {2.0, 0.5}, 30}, {{170, 500}, {1.5, 0.1}, 40}}, 400);
  auto star = [&](double sr) {
    std::vector<Mover> m;
    for (int k = 0; k < 3; ++k) { double a = k * 2*M_PI/3 + 0.3; common::Vec2 v{2*std::cos(a), 2*std::sin(a)}; m.push_back({c - 100.0*v, v, sr}); }
    return m;
  };
  explore("star 40", star(40), 200);
  explore("star 30", star(30), 200);
}
TEST_CASE("explore more", "[explore2]") {
  explore("merged start diverge", {{{600, 600}, {-1.5, 0}, 40}, {{630, 600}, {1.5, 0}, 40}}, 80, true);
  explore("merged start same place diverge angle", {{{600, 600}, {2, 0.5}, 40}, {{600, 600}, {2, -0.5}, 35}}, 120);
  explore("merged start parallel then", {{{400, 600}, {2, 0}, 40}, {{400, 620}, {2, 0.2}, 35}}, 150);
  explore("overtake", {{{200, 600}, {3, 0}, 40}, {{300, 610}, {1, 0}, 35}}, 200);
  explore("head-on offset", {{{300, 600}, {2, 0}, 40}, {{900, 615}, {-2, 0}, 35}}, 300);
  explore("vanish while merged", {{{400, 400}, {1.4, 1.4}, 40, 1, 90}, {{400, 800}, {1.4, -1.4}, 35}}, 250);
  explore("appear next", {{{400, 400}, {2, 0}, 40}, {{470, 400}, {2, 0}, 40, 30}}, 100);
}
TEST_CASE("explore vanish near", "[explore3]") {
  for (double sep : {100.0, 110.0, 120.0, 130.0, 140.0, 150.0, 160.0}) {
    char name[64]; std::snprintf(name, sizeof name, "vanish parallel sep %.0f", sep);
    explore(name, {{{300, 600}, {2, 0}, 40}, {{300, 600 + sep}, {2, 0}, 40, 1, 30}}, 100);
  }
  explore("vanish static sep 120", {{{600, 600}, {0, 0}, 40}, {{600, 720}, {0, 0}, 40, 1, 30}}, 100);
  explore("vanish crossing-ish 120", {{{300, 600}, {2, 0}, 40}, {{300, 720}, {2, -0.3}, 40, 1, 30}}, 100);
}

}  // namespace
}  // namespace wsn::supernode::rulebased

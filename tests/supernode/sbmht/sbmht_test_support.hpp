// Helpers shared by the sbmht engine's tests: a scenario with the engine's defaults, a harness that
// steps it, and noise-free measurements of any kind a field sensor reports.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/messages.hpp"
#include "common/scenario_config.hpp"
#include "supernode/engine.hpp"
#include "supernode/observation_window.hpp"
#include "supernode/sbmht/measurement_models.hpp"
#include "supernode/sbmht/sbmht_engine.hpp"

namespace wsn::supernode::sbmht::support {

/// A scenario with one supernode at the centre of [0, 100]^2 and resolved "sbmht" defaults
/// (PD 0.9, lambda_fa 1e-4, lambda_nt 1e-5, sigma 0.5, N = 3, 20 hypotheses).
inline common::Scenario sbmhtScenario(std::map<std::string, double> params = {}) {
  common::Scenario s;
  s.source_path = "test.yaml";
  s.supernodes = {{50.0, 50.0}};
  s.tracker.engine = "sbmht";
  s.tracker.window_size = 10;
  for (const auto& [key, value] : params) s.tracker.params[key] = common::EngineParam{value, 1, false};
  resolveEngineParams(s, common::kNoStatistics);
  return s;
}

/// A window and an sbmht engine of supernode 0 of `s`; `adjust` may add to the engine's context
/// what a scenario built in code lacks (the sensors' coverage, the terrain).
struct Harness {
  explicit Harness(common::Scenario s, const std::function<void(EngineContext&)>& adjust = {})
      : scenario(std::move(s)), window(scenario.tracker.window_size), engine(contextOf(scenario, adjust)) {}
  static EngineContext contextOf(const common::Scenario& s, const std::function<void(EngineContext&)>& adjust) {
    EngineContext context = engineContext(s, 0);
    if (adjust) adjust(context);
    return context;
  }
  void step(std::int32_t tick, const std::vector<common::Observation>& delivered = {}) {
    window.advanceTo(tick);
    for (const auto& o : delivered) window.insert(o);
    engine.step(window);
  }
  common::Scenario scenario;
  ObservationWindow window;
  SbmhtEngine engine;
};

inline const common::TrackEstimate* findTrack(const std::vector<common::TrackEstimate>& tracks, common::TrackId id) {
  for (const auto& t : tracks)
    if (t.track == id) return &t;
  return nullptr;
}

/// The leaf of tree `tree` in the best hypothesis, or nullptr.
inline const SbmhtEngine::Leaf* bestLeaf(const SbmhtEngine& engine, common::TrackId tree) {
  for (const auto& leaf : engine.leaves())
    if (leaf.tree == tree && leaf.best) return &leaf;
  return nullptr;
}

inline double distance(const common::TrackEstimate& e, common::Vec2 p) { return std::hypot(e.x - p.x, e.y - p.y); }

/// What a sensor at `pose` measures of the target at p moving at v, noise-free, as an observation
/// of tick t carrying its noise R (diagonal `variances`) and clutter density.
inline common::Observation sensed(std::int32_t t, common::SensorId sensor, common::SensorPose pose, common::MeasurementKind kind,
                           common::Vec2 p, common::Vec2 v, std::vector<double> variances, double clutter_density) {
  MeasurementModel model;
  model.kind = kind;
  model.sensor = pose;
  common::StateVector x;
  x << p.x, p.y, v.x, v.y;
  const MeasurementVector z = model.predict(x);
  common::Measurement m;
  m.kind = kind;
  m.values.assign(z.data(), z.data() + z.size());
  const std::size_t n = variances.size();
  m.noise.assign(n * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) m.noise[i * n + i] = variances[i];
  m.sensor = pose;
  m.clutter_density = clutter_density;
  common::Observation o{t, t, sensor, pose.x, pose.y, 0};
  o.measurement = common::MeasurementRef(std::move(m));
  return o;
}

constexpr double kDegree = 3.14159265358979323846 / 180.0;

}  // namespace wsn::supernode::sbmht::support

// The supernode tracking-engine interface: one small contract that every engine (gnn, mcmcda,
// rulebased, ...) implements, plus the registry that maps scenario names to engines.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/messages.hpp"
#include "common/param_spec.hpp"
#include "common/registry.hpp"
#include "common/scenario_config.hpp"
#include "common/scenario_error.hpp"
#include "supernode/observation_window.hpp"

namespace wsn::supernode {

/// What an engine is built from: its own slice of the scenario, split off at the role edge by
/// engineContext(), never the whole scenario.
struct EngineContext {
  std::string engine;                ///< the registered name (tracker.engine)
  std::uint32_t supernode = 0;       ///< index of the supernode running it: its track-id space
  common::Rect region;
  std::uint64_t seed = 0;            ///< run.seed
  common::DynamicsConfig dynamics;   ///< the targets' motion model, Oh eq. (8)
  double sensor_spacing = 1.0;       ///< Ds (sensors.spacing): the rule-based engine's length unit
  std::int32_t window_size = 10;     ///< ws (tracker.window_size)
  std::map<std::string, common::EngineParam> params;  ///< tracker.params, resolved (every default present)
  /// Where each sensor of this supernode's tracking group looks and how well it detects there, for
  /// a sensor model that places its sensors one by one (common/sensor_coverage.hpp); empty otherwise.
  std::vector<common::SensorCoverage> coverage;
  /// The roads and masks; null without a `terrain:` section.
  std::shared_ptr<const common::Terrain> terrain;
  /// The whole field's common::meanSensedProbability over the region (every supernode's sensors):
  /// the average the derived detection probability stands for; 0 without coverage.
  double coverage_region_mean = 0.0;
};

/// How the context's sensors see over the field (common::DetectionShare): where a miss weighs what
/// the sensors would have seen; uniform without coverage.
inline common::DetectionShare detectionShare(const EngineContext& context) {
  return common::DetectionShare(context.coverage, context.terrain, context.coverage_region_mean);
}

/// The context of supernode `supernode`'s engine; scenario.tracker.params must be resolved.
EngineContext engineContext(const common::Scenario& scenario, std::uint32_t supernode);

/// A live track's predicted position at the next tick, for handoff decisions.
struct TrackPrediction {
  common::TrackId track = 0;
  common::Vec2 next_position;
};

/// A tracking engine owns its tracks; the supernode feeds it a window per tick.
class Engine {
 public:
  virtual ~Engine() = default;
  /// Continues a track that a neighbouring supernode handed over (its state is at
  /// handoff.last_tick, the tick before the one about to be stepped).
  virtual void adopt(const common::TrackHandoff& handoff) = 0;
  /// Processes the window after it advanced to window.newestTick() and delayed
  /// observations went into their own slots.
  virtual void step(const ObservationWindow& window) = 0;
  /// Confirmed tracks at the newest tick, sorted by track id.
  virtual std::vector<common::TrackEstimate> confirmedTracks() const = 0;
  /// The estimate of `tick`, an earlier tick still in the window, revised with everything the
  /// window has received since (fixed-lag, smoothed): what the settled stream reports once the
  /// tick leaves the window. nullopt for an engine that does not revise the past; the live
  /// estimate it gave at that tick then stands (SupernodeTracker keeps it).
  virtual std::optional<std::vector<common::TrackEstimate>> revisedTracks(std::int32_t tick) const {
    (void)tick;
    return std::nullopt;
  }
  /// Predicted next-tick position of every live track (tentative ones included), sorted by id.
  virtual std::vector<TrackPrediction> predictions() const = 0;
  /// Removes a live track and returns what the receiving supernode needs to continue it.
  virtual common::TrackHandoff release(common::TrackId track, std::uint32_t to_supernode) = 0;
};

using common::ParamSpec;
namespace config = common::config;

/// One registered engine.
struct EngineSpec {
  std::string name;
  std::string description;
  std::vector<ParamSpec> params;
  std::function<std::unique_ptr<Engine>(const EngineContext&)> create;
  /// The measurement kinds its observations may carry (a sensor model's measurement_kinds);
  /// the scenario check rejects a sensor model whose reports it cannot use.
  std::vector<std::string> accepts = {"position"};
  /// Optional: checks the resolved parameters against the rest of the scenario; throws
  /// common::ScenarioError "file:line: ..." when they do not fit.
  std::function<void(const common::Scenario&)> check;
};

/// All engines, in registration order.
const common::Registry<EngineSpec>& engineRegistry();

/// Checks scenario.tracker.engine and .params against the registry and fills in defaults, the
/// derived ones from `statistics` (noted in scenario.derived); throws common::ScenarioError
/// "file:line: ..." on an unknown engine or parameter or a value out of range.
void resolveEngineParams(common::Scenario& scenario, const common::StatisticsSource& statistics);

/// Builds the engine context.engine names; throws std::invalid_argument for an unknown name.
std::unique_ptr<Engine> makeEngine(const EngineContext& context);

/// Throws std::logic_error naming the engine and the kind when `observation` measures a kind
/// `engine` does not declare in `accepts`. The scenario check rejects such pairings, so this only
/// fires on a bug; it fails loudly rather than letting a position engine read a bearing as x, y.
void requireAccepted(const EngineSpec& engine, const common::Observation& observation);

/// The kinds `engine` accepts as a bit set (bit k for MeasurementKind k), so that the per-observation
/// check in a supernode's tick is one test instead of a search by name.
std::uint32_t acceptedKindMask(const EngineSpec& engine);

}  // namespace wsn::supernode

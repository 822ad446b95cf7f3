// The scenario's configuration: plain structs, one per section, every parameter of a run named
// as in the papers with the paper's values as defaults. No loading code here: the field tables
// (common/scenario_schema.hpp) describe each key once, and scenario/ loads and writes them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "common/faults.hpp"
#include "common/geometry.hpp"
#include "common/sensor_coverage.hpp"
#include "common/terrain.hpp"

namespace wsn::common {

struct Scenario;

/// One sensor of a `list` layout as the file places it (ONERA §II-A, Table I: each sensor has its
/// own type, pose and coverage). Angles stay in the file's degrees here so that a resolved file
/// reads back to equal values; common/sensor_layout.hpp turns them into radians. A zero fov, range
/// or height leaves the sensor model's default for the type.
struct PlacedSensorConfig {
  std::string name;
  std::string type;  ///< a sensor type of the scenario's sensor model (sensor_model.kind)
  Vec2 position;     ///< true position; the believed one adds the localisation error
  double heading_deg = 0.0;  ///< centre of the field of view, counter-clockwise from +x
  double fov_deg = 0.0;      ///< width of the field of view, in (0, 360]; 0: the type's default
  double range = 0.0;        ///< coverage radius; 0: the type's default
  double height = 0.0;       ///< mast height (cameras); 0: the type's default
  int line = 0;              ///< the item's line, for rules checked once the sensor model is known
  int type_line = 0;
  /// Equal in what they place; the lines only serve messages.
  friend bool operator==(const PlacedSensorConfig& a, const PlacedSensorConfig& b) {
    const auto values = [](const PlacedSensorConfig& s) {
      return std::tie(s.name, s.type, s.position, s.heading_deg, s.fov_deg, s.range, s.height);
    };
    return values(a) == values(b);
  }
};

/// Sensor placement over the region.
struct SensorLayoutConfig {
  enum class Kind { kGrid, kRandom, kList };
  Kind kind = Kind::kGrid;
  /// Grid: separation between neighbouring sensors; sensors sit at cell centres, so a
  /// 100 x 100 region with spacing 1 holds sensors at 0.5, 1.5, ..., 99.5 (Oh §VII).
  double spacing = 1.0;
  /// Random: number of sensors placed uniformly over the region. List: the list's length.
  std::uint32_t count = 10000;
  /// List: every sensor, in id order.
  std::vector<PlacedSensorConfig> list;
  friend bool operator==(const SensorLayoutConfig&, const SensorLayoutConfig&) = default;
};

/// A sensor model's own settings: every key of `sensor_model` besides kind and sensing_range.
/// Each model (a plugin folder under node/, registered in node/sensor_model_registry.cpp) defines
/// its struct, derived through SensorModelSettingsOf, and its field tables; the loader reads and
/// writes them through the registry, so a new model adds no field here.
class SensorModelSettings {
 public:
  virtual ~SensorModelSettings() = default;
  virtual bool equals(const SensorModelSettings& other) const = 0;
  /// Each sensor's coverage, for trackers that weigh a miss by where a sensor looks (ONERA eq. 15);
  /// empty for a model whose sensors all look alike (its detection probability is then uniform).
  virtual std::vector<SensorCoverage> coverage(const Scenario&) const { return {}; }
};

/// The base of a model's settings struct S (which defines ==): equality by value within a model.
template <typename S>
class SensorModelSettingsOf : public SensorModelSettings {
 public:
  bool equals(const SensorModelSettings& other) const override {
    const auto* same = dynamic_cast<const S*>(&other);
    return same != nullptr && static_cast<const S&>(*this) == *same;
  }
  friend bool operator==(const SensorModelSettingsOf&, const SensorModelSettingsOf&) { return true; }
};

/// Which sensors the field has (`kind`, a name of the sensor-model registry), how far a sensor
/// detects a target, and the model's own settings.
struct SensorModelConfig {
  std::string kind = "signal_strength";
  /// Rs: a sensor detects a target within it (Oh §VII; acoustic sensors: a target's default
  /// sensing range SR). Node tiles are made of cells of side 2 Rs (common/sensor_layout.hpp).
  double sensing_range = 1.5;
  /// The model's own keys; null in a scenario built in code, which then has the model's defaults.
  /// Shared and immutable, so copies of a scenario stay cheap.
  std::shared_ptr<const SensorModelSettings> settings;

  friend bool operator==(const SensorModelConfig& a, const SensorModelConfig& b) {
    if (a.kind != b.kind || a.sensing_range != b.sensing_range) return false;
    if (a.settings == nullptr || b.settings == nullptr) return a.settings == b.settings;
    return a.settings->equals(*b.settings);
  }
};

/// The settings of model S in `config`: S's defaults when it holds none; throws std::logic_error
/// when it holds another model's.
template <typename S>
const S& settingsOf(const SensorModelConfig& config) {
  static const S defaults;
  if (config.settings == nullptr) return defaults;
  const auto* settings = dynamic_cast<const S*>(config.settings.get());
  if (settings == nullptr)
    throw std::logic_error("sensor_model.kind '" + config.kind + "' holds another model's settings");
  return *settings;
}

/// Oh §VII-B: a sensor believes it is at s* + N(0, sigma^2 I).
struct LocalisationConfig {
  double sigma = 0.0;
  friend bool operator==(const LocalisationConfig&, const LocalisationConfig&) = default;
};

/// What a target is: the classes of ONERA eq. (1), made exclusive (docs/ONERA.md §4).
enum class TargetClass { kUnknown, kWheeledLight, kWheeledHeavy, kTracked, kHuman, kGroup, kAerial };

/// The classes' names in the scenario (`class:`) and the output files, in the enum's order.
inline const std::vector<std::string>& targetClassNames() {
  static const std::vector<std::string> names{"unknown", "wheeled_light", "wheeled_heavy", "tracked",
                                              "human",   "group",         "aerial"};
  return names;
}
inline const std::string& targetClassName(TargetClass c) {
  return targetClassNames().at(static_cast<std::size_t>(c));
}

/// A halt of a waypoint target: `ticks` ticks at rest at waypoints[at].
struct WaypointStop {
  std::int32_t at = 0;
  std::int32_t ticks = 0;
  friend bool operator==(const WaypointStop&, const WaypointStop&) = default;
};

/// One explicitly scripted target: alive on ticks [appear_tick, disappear_tick).
struct TargetSpec {
  std::int32_t appear_tick = 1;
  std::int32_t disappear_tick = 0;  ///< 0: until the end of the run (or leaving the region)
  /// At appear_tick; a waypoint target's are its first waypoint and its first leg at `speed`.
  Vec2 position;
  Vec2 velocity;  ///< per tick
  /// This target's sensing range SR (how loud it is), for models that read it (acoustic sensors);
  /// 0 = sensor_model.sensing_range.
  double sensing_range = 0.0;
  /// A target that drives a route: from waypoints[0] along the polyline at `speed` per tick,
  /// halting at `stops`, gone after the last waypoint (common/truth.cpp). Empty: it moves with
  /// `velocity` under eq. (8).
  std::vector<Vec2> waypoints;
  double speed = 0.0;  ///< per tick, for a waypoint target with one speed (0 when `speeds` gives them)
  /// Per tick, one per waypoint: the speed as the target passes it. Along a leg the speed changes at
  /// a constant acceleration from one waypoint's to the next's. Empty: `speed` throughout.
  std::vector<double> speeds;
  std::vector<WaypointStop> stops;  ///< in route order
  TargetClass target_class = TargetClass::kUnknown;
  friend bool operator==(const TargetSpec&, const TargetSpec&) = default;

  /// Its highest speed per tick: |velocity| under eq. (8), on a route `speed` or the most of `speeds`.
  double topSpeed() const {
    if (waypoints.empty()) return std::hypot(velocity.x, velocity.y);
    double top = speed;
    for (const double v : speeds) top = std::max(top, v);
    return top;
  }
};

/// Speed classes of Oh §VII-A: |vx|, |vy| uniform in [min, max] per tick, random signs.
enum class SpeedClass { kSlow, kMedium, kFast };

struct TargetsConfig {
  std::vector<TargetSpec> scripted;
  /// Random births: Poisson(birth_rate * V) new targets per tick, uniform over the region.
  double birth_rate = 0.0;
  /// Each randomly born target alive at t-1 disappears at t with this probability (Oh §III-A,
  /// pz); scripted targets keep their scripted lifetime.
  double death_probability = 0.0;
  SpeedClass speed_class = SpeedClass::kMedium;
  /// Targets drawn per seed at random times (Oh §VII-A: "10 targets appear and disappear at random
  /// times"): each lives a whole number of ticks in [lifetime_min, lifetime_max] that fits the run,
  /// with a speed-class velocity, from a start whose straight path stays in the region.
  std::int32_t count = 0;
  std::int32_t lifetime_min = 25;
  std::int32_t lifetime_max = 45;
  friend bool operator==(const TargetsConfig&, const TargetsConfig&) = default;
};

/// Dynamics, Oh eq. (8): x_{t+delta} = A x_t + G w_t, w ~ N(0, diag(q^2, q^2)).
struct DynamicsConfig {
  double delta = 1.0;
  double process_noise_sigma = 0.15;
  friend bool operator==(const DynamicsConfig&, const DynamicsConfig&) = default;
};

/// Network model, Oh §V.
struct NetworkConfig {
  /// Radio range defining the communication graph; calibrated so that the default scenario
  /// reproduces the loss and delay counts of Oh §VII-E (see docs/NETWORK.md).
  double communication_range = 11.6;
  double pte = 0.3;  ///< transmission failure rate per edge
  double pde = 0.3;  ///< per-hop delay rate
  friend bool operator==(const NetworkConfig&, const NetworkConfig&) = default;
};

/// A numeric engine parameter as written in the file; line 0 when it is a filled-in default.
struct EngineParam {
  double value = 0.0;
  int line = 0;
  /// Written `auto`: the component's default (derived where it has one); the name is still
  /// checked, and resolution replaces the entry.
  bool automatic = false;
  /// Equal by value: the line only serves messages.
  friend bool operator==(const EngineParam& a, const EngineParam& b) { return a.value == b.value; }
};

/// Supernode tracker: which engine and its parameters (validated by the engine registry).
struct TrackerConfig {
  std::string engine = "mcmcda";
  int engine_line = 0;
  /// Sliding window of ws ticks of delivered observations (Oh §VI, ws = 10).
  std::int32_t window_size = 10;
  std::map<std::string, EngineParam> params;
  /// Equal in what they configure; engine_line only serves messages.
  friend bool operator==(const TrackerConfig& a, const TrackerConfig& b) {
    return a.engine == b.engine && a.window_size == b.window_size && a.params == b.params;
  }
};

/// Track-level association at the aggregator (Oh §VI): which method and its parameters
/// (validated by the aggregator's association registry, like tracker.params).
struct AggregatorConfig {
  std::string association = "mcmcda";
  int association_line = 0;
  std::map<std::string, EngineParam> params;
  /// Equal in what they configure; association_line only serves messages.
  friend bool operator==(const AggregatorConfig& a, const AggregatorConfig& b) {
    return a.association == b.association && a.params == b.params;
  }
};

/// Metric settings. Lengths in region units (sensor separations).
struct MetricsConfig {
  double ospa_c = 5.0;         ///< OSPA cut-off c (Schuhmacher, Vo & Vo 2008)
  double ospa_p = 2.0;         ///< OSPA order p
  /// eps_x_gated: eq. (10) over the matches closer than this only (a far pair of an unrelated track
  /// and target says nothing about localisation)
  double eps_x_gate = 3.0;
  double gospa_c = 5.0;        ///< GOSPA cut-off c (alpha = 2)
  double gospa_p = 2.0;        ///< GOSPA order p
  double mot_threshold = 3.0;  ///< CLEAR-MOT match threshold T (Bernardin & Stiefelhagen 2008)
  double quality_gate = 3.0;   ///< RSE/TLR/<dx>: a track counts for its target only within this distance
  /// Boundary events: a target this close to the bisector of its two nearest supernodes is at a
  /// tracking-group boundary (aggregator/boundary.hpp)
  double boundary_band = 5.0;
  friend bool operator==(const MetricsConfig&, const MetricsConfig&) = default;
};

/// Whether a run's participants authenticate and are held to the run's permissions (DDS
/// Security, docs/SECURITY.md).
enum class RunSecurity { kOn, kOff };
/// How a secured run protects each RTPS message: a MAC (sign), or AES-GCM encryption with its MAC.
enum class MessageProtection { kSign, kEncrypt };

/// Run length, seed and process layout.
struct RunConfig {
  std::int32_t ticks = 100;  ///< T
  std::uint64_t seed = 1;
  std::int32_t node_processes = 2;       ///< one sensor tile per node process
  std::int32_t max_ticks_in_flight = 3;  ///< back-pressure bound of the lockstep pipeline
  /// Processes the supernodes run in (multi-process runs): each holds a group of consecutive
  /// supernodes as threads on one DDS participant. 0: derived (supernodeProcesses()).
  std::int32_t supernode_processes = 0;
  RunSecurity security = RunSecurity::kOn;
  MessageProtection message_protection = MessageProtection::kEncrypt;
  friend bool operator==(const RunConfig&, const RunConfig&) = default;
};

struct Scenario {
  std::string source_path;  ///< the file it was loaded from, for messages
  std::string name = "unnamed";
  Rect region{0.0, 0.0, 100.0, 100.0};
  SensorLayoutConfig sensors;
  SensorModelConfig sensor_model;
  LocalisationConfig localisation;
  TargetsConfig targets;
  DynamicsConfig dynamics;
  std::vector<Vec2> supernodes;
  NetworkConfig network;
  TrackerConfig tracker;
  AggregatorConfig aggregator;
  MetricsConfig metrics;
  RunConfig run;
  TerrainConfig terrain;  ///< roads and masks; empty unless the file has `terrain:`
  /// What goes wrong in the cluster during the run, in file order; empty unless the file has `faults:`.
  std::vector<FaultSpec> faults;
  /// The keys whose values the loader derived because the file left them out ("sensor_model.beta"),
  /// with how; the resolved scenario.yaml notes them. Not part of equality: a resolved file gives
  /// every value explicitly, so loading it derives nothing, yet it is the same scenario.
  std::map<std::string, std::string> derived;

  /// Equal in every value of the run; where it was loaded from (source_path) does not count.
  friend bool operator==(const Scenario& a, const Scenario& b) {
    const auto values = [](const Scenario& s) {
      return std::tie(s.name, s.region, s.sensors, s.sensor_model, s.localisation, s.targets, s.dynamics, s.supernodes,
                      s.network, s.tracker, s.aggregator, s.metrics, s.run, s.terrain, s.faults);
    };
    return values(a) == values(b);
  }
};

}  // namespace wsn::common

#include "observation_model/observation_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "common/report_merging.hpp"
#include "common/rng.hpp"
#include "common/scenario_schema.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "network_model/calibration.hpp"
#include "network_model/role_config.hpp"
#include "network_model/topology.hpp"
#include "node/sensor_model_registry.hpp"
#include "node/tiling.hpp"

namespace wsn::observation_model {
namespace {

using common::Derived;

/// The simulation's own seed: the statistics describe the model, not one run's realisation.
constexpr std::uint64_t kProbeSeed = 0x0b5e7a7105eedULL;
/// Scored probe samples to aim for: the sensing probability is then known to about +-0.02.
constexpr double kWantedSamples = 1200.0;
/// Probe targets live this many ticks; the ticks after the first are scored (a model whose
/// reports depend on the target's past, like the acoustic one, sees a target that already moved).
/// Each generation ends with ticks without probes, on which the false reports are counted: near
/// a target, noise is absorbed by its report (Oh eq. 6 elects one sensor), which would bias the
/// count low.
constexpr std::int32_t kProbeLife = 3;
constexpr std::int32_t kEmptyTicks = 2;
constexpr std::int32_t kGenerationTicks = kProbeLife + kEmptyTicks;

/// The speed class as the scenario file spells it (the targets table owns the names).
std::string speedClassName(const common::TargetsConfig& targets) {
  return common::schema::targets().find("speed_class")->get_text(targets);
}

using common::shortNumber;

/// The scenario's sensor field under the probe's seed.
common::SensorFieldConfig probeField(const common::Scenario& scenario) {
  common::SensorFieldConfig field = common::sensorFieldConfig(scenario);
  field.seed = kProbeSeed;
  return field;
}

/// More reports per heard target and tick than this (on average) means the model reports every
/// detecting sensor: a model that fuses (Oh eq. 6, ADMAN) lands at 1 up to a rare duplicate.
constexpr double kOneReportPerTarget = 1.1;

struct SensorMeasurement {
  double reports_per_target = 0.0;
  double merge_radius = 0.0;
  double position_sigma = 0.0;
  double sensing_probability = 0.0;
  double false_report_density = 0.0;
  std::size_t samples = 0;
  std::size_t detected = 0;
  std::int32_t ticks = 0;
  std::int32_t empty_ticks = 0;
};

/// Where the probe targets go: a lattice of nx x ny cells over the region less a margin, one probe
/// per cell jittered by up to `jitter`, for `generations` generations.
struct ProbeLattice {
  double jitter = 0.0;
  double margin = 0.0;
  std::int64_t nx = 1;
  std::int64_t ny = 1;
  double cell_x = 0.0;
  double cell_y = 0.0;
  std::int32_t generations = 0;
};

/// Probes far enough apart that their reports never mix, and enough generations of them for
/// kWantedSamples scored samples.
ProbeLattice probeLattice(const common::Scenario& scenario, double rms_speed) {
  const common::SensorLayoutConfig& placement = scenario.sensors;
  const common::Rect& region = scenario.region;
  double reach = scenario.sensor_model.sensing_range;
  for (const auto& t : scenario.targets.scripted) reach = std::max(reach, t.sensing_range);
  const double spacing = placement.kind == common::SensorLayoutConfig::Kind::kGrid
                             ? placement.spacing
                             : std::sqrt(region.area() / std::max<double>(1.0, placement.count));
  // Reports of two probes must never interact: Oh eq. 6 elects over 2 Rs, so keep 5 Rs between
  // probes plus the jitter that moves each over a whole sensor cell.
  ProbeLattice lattice;
  lattice.jitter = std::max(spacing, reach);
  const double pitch = 5.0 * reach + 2.0 * lattice.jitter + rms_speed * kProbeLife;
  lattice.margin = reach;
  const auto fit = [&](double extent) {
    return std::max<std::int64_t>(1, std::llround(std::floor((extent - 2 * lattice.margin) / pitch)));
  };
  lattice.nx = fit(region.width());
  lattice.ny = fit(region.height());
  lattice.cell_x = (region.width() - 2 * lattice.margin) / static_cast<double>(lattice.nx);
  lattice.cell_y = (region.height() - 2 * lattice.margin) / static_cast<double>(lattice.ny);
  const auto per_generation = static_cast<double>(lattice.nx * lattice.ny * (kProbeLife - 1));
  lattice.generations =
      static_cast<std::int32_t>(std::clamp(std::ceil(kWantedSamples / per_generation), 4.0, 400.0));
  return lattice;
}

/// Generation g's simulation: kGenerationTicks long with its own noise seed, one straight-moving
/// probe per lattice cell, at its jittered aim at its first scored tick.
common::TruthConfig probeGeneration(const common::Scenario& scenario, const ProbeLattice& lattice, std::int32_t g,
                                    double rms_speed) {
  const common::Rect& region = scenario.region;
  common::TruthConfig truth_config;
  truth_config.region = region;
  truth_config.dynamics = scenario.dynamics;
  truth_config.dynamics.process_noise_sigma = 0.0;  // probes move straight: only the sensors are measured
  truth_config.seed = kProbeSeed + static_cast<std::uint64_t>(g);
  truth_config.ticks = kGenerationTicks;
  std::vector<common::TargetSpec>& probes = truth_config.targets.scripted;
  common::Stream stream(kProbeSeed, common::Purpose::kDerivationProbe, static_cast<std::uint64_t>(g), 0);
  const double jitter = lattice.jitter;
  const double cell_x = lattice.cell_x;
  const double cell_y = lattice.cell_y;
  for (std::int64_t i = 0; i < lattice.nx; ++i)
    for (std::int64_t j = 0; j < lattice.ny; ++j) {
      const double cx = region.x_min + lattice.margin + (static_cast<double>(i) + 0.5) * cell_x;
      const double cy = region.y_min + lattice.margin + (static_cast<double>(j) + 0.5) * cell_y;
      const common::Vec2 aim{cx + stream.uniform(-jitter, jitter) * std::min(1.0, 0.5 * cell_x / (jitter + 1e-12)),
                             cy + stream.uniform(-jitter, jitter) * std::min(1.0, 0.5 * cell_y / (jitter + 1e-12))};
      const double heading = stream.uniform(0.0, 2.0 * std::numbers::pi);
      const common::Vec2 v{rms_speed * std::cos(heading), rms_speed * std::sin(heading)};
      common::TargetSpec probe;  // at `aim` at its first scored tick
      probe.appear_tick = 1;
      probe.disappear_tick = 1 + kProbeLife;
      probe.position = {aim.x - v.x, aim.y - v.y};
      probe.velocity = v;
      if (!scenario.targets.scripted.empty())  // loud and quiet targets in the scenario's mix
        probe.sensing_range =
            scenario.targets.scripted[static_cast<std::size_t>(g * lattice.nx * lattice.ny + i * lattice.ny + j) %
                                      scenario.targets.scripted.size()]
                .sensing_range;
      probes.push_back(probe);
    }
  return truth_config;
}

/// One tick on which every probe was live and had been for a tick: its reports and the truth.
struct ScoredTick {
  std::vector<common::Report> reports;
  std::vector<common::TargetState> targets;
};

/// What the sensor model reported over every generation of probes.
struct ProbeReports {
  std::vector<ScoredTick> scored;
  std::size_t clutter = 0;  ///< false reports on the ticks without probes
  std::int32_t empty_ticks = 0;
  std::int32_t ticks = 0;
};

/// Runs the scenario's sensor model over its whole field as one tile, generation by generation.
/// Each generation is a simulation of its own: a model's cost per tick may grow with every target
/// it was ever given (the acoustic model keeps each target's trajectory), so the probes of one
/// generation never meet the others.
ProbeReports runProbes(const common::Scenario& scenario, const common::SensorLayout& layout, double rms_speed) {
  const auto tiles = node::makeTiles(layout, 1);
  const ProbeLattice lattice = probeLattice(scenario, rms_speed);
  ProbeReports out;
  for (std::int32_t g = 0; g < lattice.generations; ++g) {
    const common::TruthConfig truth_config = probeGeneration(scenario, lattice, g, rms_speed);
    const common::Truth truth(truth_config);
    const node::TileContext context{scenario.sensor_model, truth_config.seed, truth_config.targets.scripted, layout,
                                    tiles.front(), truth, &scenario.terrain};
    const auto sensors = node::makeTileSensors(context);
    out.ticks += truth_config.ticks;
    for (std::int32_t tick = 1; tick <= truth_config.ticks; ++tick) {
      (void)sensors->sense(tick);
      auto reports = sensors->report(tick, {});
      const std::int32_t phase = tick - 1;
      if (phase >= kProbeLife) {
        // Only reports of no target: a model with propagation delay (sound) still hears the
        // probes that just ended, and those reports name them.
        out.clutter += static_cast<std::size_t>(std::count_if(
            reports.begin(), reports.end(), [](const common::Report& r) { return r.target == common::kFalseAlarm; }));
        ++out.empty_ticks;
      }
      if (phase >= 1 && phase < kProbeLife) out.scored.push_back({std::move(reports), truth.at(tick)});
    }
  }
  return out;
}

/// A model that reports a target more than once a tick (every detecting sensor, unfused) is
/// merged before tracking: the radius that joins one target's reports to its strongest one (at
/// the 95th percentile of target-ticks). Only positions count: a report of another kind is never
/// merged (common::mergeNearby), and a bearing or radar plot lies at its sensor, not at its target.
void measureMerging(const std::vector<ScoredTick>& scored, SensorMeasurement& m) {
  std::size_t labelled = 0, targets_heard = 0;
  std::vector<double> joining;
  for (const auto& tick : scored) {
    std::map<common::TargetId, std::vector<common::Report>> of_target;
    for (const auto& r : tick.reports)
      if (r.target != common::kFalseAlarm && r.measurement.kind() == common::MeasurementKind::position)
        of_target[r.target].push_back(r);
    for (const auto& [id, own] : of_target) {
      labelled += own.size();
      ++targets_heard;
      if (own.size() > 1) joining.push_back(common::reachFromStrongest(std::span<const common::Report>(own)));
    }
  }
  const double per_target = targets_heard > 0 ? static_cast<double>(labelled) / static_cast<double>(targets_heard) : 0.0;
  m.reports_per_target = per_target;
  if (per_target > kOneReportPerTarget && !joining.empty()) {
    std::sort(joining.begin(), joining.end());
    // The nearest-rank 95th percentile.
    const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(joining.size())));
    m.merge_radius = joining[std::clamp<std::size_t>(rank, 1, joining.size()) - 1];
  }
}

/// The share of probe samples with a report and the rms error per axis of each probe's nearest
/// report, after merging with m.merge_radius.
void measureDetection(const std::vector<ScoredTick>& scored, SensorMeasurement& m) {
  double squared_error = 0.0;
  for (const auto& tick : scored) {
    const std::vector<common::Report> reports =
        common::mergeNearby(std::span<const common::Report>(tick.reports), m.merge_radius);
    // probe -> the error of its nearest report
    std::map<common::TargetId, std::pair<double, double>> nearest_error;
    for (const auto& r : reports) {
      if (r.target == common::kFalseAlarm) continue;
      for (const auto& t : tick.targets) {
        if (t.id != r.target) continue;
        const double ex = r.x - t.x;
        const double ey = r.y - t.y;
        const auto it = nearest_error.find(t.id);
        if (it == nearest_error.end() ||
            ex * ex + ey * ey < it->second.first * it->second.first + it->second.second * it->second.second)
          nearest_error[t.id] = {ex, ey};
      }
    }
    for (const auto& t : tick.targets) {
      ++m.samples;
      const auto it = nearest_error.find(t.id);
      if (it == nearest_error.end()) continue;
      ++m.detected;
      squared_error += it->second.first * it->second.first + it->second.second * it->second.second;
    }
  }
  m.sensing_probability = m.samples > 0 ? static_cast<double>(m.detected) / static_cast<double>(m.samples) : 0.0;
  m.position_sigma = m.detected > 0 ? std::sqrt(squared_error / (2.0 * static_cast<double>(m.detected))) : 0.0;
}

/// Runs the scenario's sensor model over its whole field as one tile, with probe targets on a
/// jittered lattice far enough apart that their reports never mix, and compares the reports
/// with them.
SensorMeasurement measureSensorModel(const common::Scenario& scenario, const common::SensorLayout& layout,
                                     double rms_speed) {
  const ProbeReports probes = runProbes(scenario, layout, rms_speed);
  SensorMeasurement m;
  m.ticks = probes.ticks;
  measureMerging(probes.scored, m);
  measureDetection(probes.scored, m);
  // None seen is not none: with no false report in n ticks, the rate is below 3 per n ticks with
  // 95 % confidence (the rule of three), and that bound is what the model may rely on. A density
  // of exactly 0 also makes an engine's posterior brittle: one report that fits no track then
  // costs without limit (MCMCDA at pde = 0.6 lost most targets at lambda_f = 1e-12).
  m.false_report_density = static_cast<double>(std::max<std::size_t>(probes.clutter, 3)) /
                           (scenario.region.area() * static_cast<double>(probes.empty_ticks));
  m.empty_ticks = probes.empty_ticks;
  return m;
}

/// The shares of reports that reach their supernode's window, and at once: Oh eq. (7) over the
/// hop histogram.
/// The network's part of the statistics: delivery into the window, on time, and by each lag.
void deriveDeliveryStatistics(const common::Scenario& scenario, const common::SensorLayout& layout,
                              common::ObservationStatistics& stats) {
  const network_model::Topology topology(network_model::topologyConfig(scenario), layout.truePositions());
  const auto ratios =
      network_model::expectedRatios(topology, scenario.network.pte, scenario.network.pde, scenario.tracker.window_size);
  const double in_window =
      std::clamp(1.0 - ratios.lost_to_total - ratios.delayed_to_total + ratios.delayed_in_window_to_total, 0.0, 1.0);
  const double on_time = std::clamp(1.0 - ratios.lost_to_total - ratios.delayed_to_total, 0.0, 1.0);
  stats.delivery_probability = {in_window, "Oh eq. 7 over the topology: lost " + shortNumber(ratios.lost_to_total) +
                                               ", delayed past the window " +
                                               shortNumber(ratios.delayed_to_total - ratios.delayed_in_window_to_total)};
  stats.on_time_probability = {on_time, "Oh eq. 7 over the topology: lost " + shortNumber(ratios.lost_to_total) +
                                            ", delayed " + shortNumber(ratios.delayed_to_total)};
  stats.arrival_by_lag = ratios.arrived_by_lag;
}

}  // namespace

void deriveTargetStatistics(const common::Scenario& scenario, common::ObservationStatistics& stats) {
  const auto& targets = scenario.targets;
  const common::Rect& region = scenario.region;
  const double area = region.area();
  const double ticks = std::max(1, scenario.run.ticks);
  const double q = scenario.dynamics.process_noise_sigma * scenario.dynamics.delta;
  stats.region_area = area;
  stats.sensor_spacing = scenario.sensors.spacing;  // the rule-based engine's unit Ds, as its context has it
  stats.process_noise_sigma = scenario.dynamics.process_noise_sigma;
  stats.delta = scenario.dynamics.delta;
  stats.window_size = scenario.tracker.window_size;
  stats.run_ticks = scenario.run.ticks;

  // How many targets each source brings over the run, to weigh their speeds and lifetimes. Drawn
  // targets (targets.count) move like born ones and live a drawn lifetime like scripted ones.
  const double drawn = targets.count;
  const double drawn_longest = std::min<double>(targets.lifetime_max, ticks);
  const double drawn_life = 0.5 * (std::min<double>(targets.lifetime_min, drawn_longest) + drawn_longest);
  const double random_born = targets.birth_rate * area * ticks;
  const double born = random_born + drawn;
  const auto scripted = static_cast<double>(targets.scripted.size());
  const double all = born + scripted;

  const common::SpeedInterval speed = common::speedInterval(targets.speed_class);
  const double class_ms = (speed.min * speed.min + speed.min * speed.max + speed.max * speed.max) / 3.0;
  double scripted_ms = 0.0;
  double scripted_max = 0.0;
  double scripted_life = 0.0;
  double longest_life = targets.birth_rate > 0.0 ? ticks : drawn > 0.0 ? drawn_longest : 0.0;
  for (const auto& t : targets.scripted) {
    scripted_ms += 0.5 * (t.velocity.x * t.velocity.x + t.velocity.y * t.velocity.y);
    scripted_max = std::max({scripted_max, std::abs(t.velocity.x), std::abs(t.velocity.y)});
    const double end = t.disappear_tick > 0 ? std::min<double>(t.disappear_tick, ticks + 1) : ticks + 1;
    const double life = std::max(1.0, end - t.appear_tick);
    scripted_life += life;
    longest_life = std::max(longest_life, life);
  }
  const double velocity_ms = all > 0.0 ? (born * class_ms + scripted_ms) / all : class_ms;
  stats.velocity_sigma = {
      std::sqrt(velocity_ms),
      born > 0.0 && scripted > 0.0 ? "rms of the speed class '" + speedClassName(targets) +
                                         "' and the scripted velocities, weighted by count"
      : scripted > 0.0 ? "rms of the scripted velocities per axis"
                       : "rms per axis of the speed class '" + speedClassName(targets) + "' (Oh §VII-A)"};

  // Oh eq. (8) lets the velocity wander by q per tick on each axis: over a life of L ticks by
  // q sqrt(L); two of those on top of the largest initial component bound nearly every target.
  const double axis_max = std::max(born > 0.0 ? speed.max : 0.0, scripted_max);
  const double drift = 2.0 * q * std::sqrt(std::max(1.0, longest_life));
  stats.max_speed = {std::sqrt(2.0) * (axis_max + drift), "sqrt 2 x (largest initial speed per axis " + shortNumber(axis_max) +
                                                              " + 2 q sqrt(longest life " + shortNumber(longest_life) +
                                                              " ticks) = " + shortNumber(drift) + ")"};

  // The weakest target: the smallest sensing range of a scripted target, or the sensor model's
  // when any target takes it (drawn, born, or scripted without its own).
  double weakest = INFINITY;
  bool model_range = born > 0.0;
  for (const auto& t : targets.scripted) {
    if (t.sensing_range > 0.0)
      weakest = std::min(weakest, t.sensing_range);
    else
      model_range = true;
  }
  if (model_range || !std::isfinite(weakest)) weakest = std::min(weakest, scenario.sensor_model.sensing_range);
  const double density = scenario.sensors.kind == common::SensorLayoutConfig::Kind::kGrid
                             ? 1.0 / (scenario.sensors.spacing * scenario.sensors.spacing)
                             : scenario.sensors.count / area;
  stats.sensors_per_weakest_target = {density * std::numbers::pi * weakest * weakest,
                                      "sensor density " + shortNumber(density) + " x pi SR^2 at the weakest SR " +
                                          shortNumber(weakest)};

  // Births: the Poisson rate per area, and scripted targets spread over the run.
  stats.birth_density = {targets.birth_rate + (scripted + drawn) / (area * ticks),
                         "targets.birth_rate + " + shortNumber(scripted + drawn) +
                             " scripted and drawn targets over the region and run"};

  // A born target ends by pz or by leaving the region: the mean chord of a convex region is
  // pi A / perimeter (Cauchy), crossed at the rms speed sqrt 2 x velocity sigma.
  const double perimeter = 2.0 * (region.width() + region.height());
  const double chord = std::numbers::pi * area / perimeter;
  const double exit = std::min(1.0, std::sqrt(2.0 * class_ms) * scenario.dynamics.delta / chord);
  const double random_end = 1.0 - (1.0 - targets.death_probability) * (1.0 - exit);
  // A drawn target ends after its lifetime, or sooner when it crosses the region first.
  const double drawn_end = drawn > 0.0 ? std::max(1.0 / drawn_life, exit) : 0.0;
  const double born_end = born > 0.0 ? (random_born * random_end + drawn * drawn_end) / born : random_end;
  const double scripted_end = scripted > 0.0 ? scripted / scripted_life : 0.0;
  const double termination = all > 0.0 ? (born * born_end + scripted * scripted_end) / all : born_end;
  stats.termination_probability = {
      termination, born > 0.0 && scripted > 0.0 ? "death_probability and leaving the region (mean chord " + shortNumber(chord) +
                                                      "), drawn lifetimes, weighted with 1 / the scripted lifetimes"
                   : scripted > 0.0
                       ? "1 / the mean scripted lifetime " + shortNumber(scripted_life / scripted) + " ticks"
                       : "targets.death_probability and leaving the region (mean chord pi A / perimeter = " +
                             shortNumber(chord) + " at the rms speed)" +
                             (drawn > 0.0 ? "; drawn targets: 1 / their mean lifetime " + shortNumber(drawn_life) +
                                                " ticks, or leaving the region if sooner"
                                          : "")};
}

common::ObservationStatistics observationStatistics(const common::Scenario& scenario) {
  common::ObservationStatistics stats;
  deriveTargetStatistics(scenario, stats);
  // One layout for the probe and the topology, with the probe's own seed (a random layout and
  // localisation errors are drawn once, not per run seed).
  const common::SensorLayout layout(probeField(scenario));
  const SensorMeasurement m = measureSensorModel(scenario, layout, std::sqrt(2.0) * stats.velocity_sigma.value);
  const std::string probe =
      " over " + std::to_string(m.samples) + " probe samples of sensor_model '" + scenario.sensor_model.kind + "'";
  stats.report_merge_radius = {
      m.merge_radius, m.merge_radius > 0.0
                          ? "the reach of one target's same-tick reports from its strongest, 95th percentile (" +
                                shortNumber(m.reports_per_target) + " reports per heard target and tick" + probe + ")"
                          : shortNumber(m.reports_per_target) + " reports per heard target and tick" + probe +
                                ": none to merge"};
  stats.position_sigma = {m.position_sigma, std::string(m.merge_radius > 0.0 ? "rms error per axis of the merged report"
                                                                             : "rms report error per axis") +
                                                probe};
  stats.sensing_probability = {m.sensing_probability, "share of probe targets with a report" + probe};
  stats.false_report_density = {m.false_report_density,
                                "false reports per area and tick on " + std::to_string(m.empty_ticks) +
                                    " ticks without targets of sensor_model '" + scenario.sensor_model.kind +
                                    "' (at least 3: the rule of three when none is seen)"};
  deriveDeliveryStatistics(scenario, layout, stats);
  return stats;
}

common::StatisticsSource lazyStatistics(const common::Scenario& scenario) {
  auto cache = std::make_shared<std::optional<common::ObservationStatistics>>();
  return [&scenario, cache]() -> const common::ObservationStatistics& {
    if (!cache->has_value()) *cache = observationStatistics(scenario);
    return **cache;
  };
}

}  // namespace wsn::observation_model

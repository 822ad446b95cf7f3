// Cost of the ADMAN model (node/adman: eq. 1 readings, the two-stage GLRT, the attach rules and
// MLMC localisation): every tick of scenarios/adman_three_targets.yaml (49 sensors, 3 targets) and
// of the same model over a 30 x 30 grid of the same pitch with more targets, factorised and joint,
// as seconds per sensor and tick (the unit of the other sensor-model benchmarks) and per target
// report, which is where MLMC's cost goes.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>

#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/adman/adman_field.hpp"
#include "node/adman/config.hpp"
#include "node/tiling.hpp"
#include "scenario/loader.hpp"

namespace {

using wsn::node::adman::AdmanSettings;
using wsn::node::adman::Localisation;

/// The shipped scenario (grid = 0) or a grid x grid field of its pitch crossed by `targets`
/// targets in rows; joint or factorised MLMC.
wsn::common::Scenario scenarioWith(std::int64_t grid, std::int64_t targets, bool joint) {
  auto s = wsn::scenario::loadScenario(WSN_SCENARIO_DIR "/adman_three_targets.yaml");
  auto settings = std::make_shared<AdmanSettings>(wsn::common::settingsOf<AdmanSettings>(s.sensor_model));
  settings->localisation = joint ? Localisation::joint : Localisation::factorised;
  s.sensor_model.settings = settings;
  if (grid > 0) {
    const double pitch = settings->sensor_pitch;
    const double side = static_cast<double>(grid) * pitch;
    s.region = {-pitch / 2.0, -pitch / 2.0, side - pitch / 2.0, side - pitch / 2.0};
    s.supernodes = {{side / 2.0, side / 2.0}};
    s.targets.scripted.clear();
    for (std::int64_t k = 0; k < targets; ++k) {
      wsn::common::TargetSpec target;
      target.position = {0.0, (static_cast<double>(k) + 0.5) * side / static_cast<double>(targets) - pitch / 2.0};
      target.velocity = {1.5, 0.3};
      s.targets.scripted.push_back(target);
    }
  }
  return s;
}

/// One iteration: read() then report() for every tick of the run on one tile holding every sensor.
void senseRun(benchmark::State& state) {
  const auto scenario = scenarioWith(state.range(0), state.range(1), state.range(2) != 0);
  const wsn::common::Truth truth(truthConfig(scenario));
  const wsn::common::SensorLayout layout(sensorFieldConfig(scenario));
  const auto tiles = wsn::node::makeTiles(layout, 1);
  const wsn::node::adman::AdmanField field(wsn::common::settingsOf<AdmanSettings>(scenario.sensor_model),
                                           scenario.run.seed, layout, tiles.front(), truth);
  std::size_t reports = 0;
  for (auto _ : state) {
    reports = 0;
    for (std::int32_t t = 1; t <= scenario.run.ticks; ++t) reports += field.report(t, field.read(t), {}).size();
    benchmark::DoNotOptimize(reports);
  }
  const double sensor_ticks = static_cast<double>(layout.size()) * scenario.run.ticks;
  state.counters["s_per_sensor_tick"] =
      benchmark::Counter(sensor_ticks, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["s_per_report"] = benchmark::Counter(
      static_cast<double>(reports), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["reports_per_tick"] = static_cast<double>(reports) / scenario.run.ticks;
}

// {grid side (0: the shipped scenario), targets, joint}
BENCHMARK(senseRun)
    ->Args({0, 3, 0})
    ->Args({0, 3, 1})
    ->Args({30, 10, 0})
    ->Args({30, 10, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace

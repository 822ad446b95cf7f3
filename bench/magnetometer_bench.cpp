// Cost of the magnetometer model (Oh et al. 2005 §VIII, node/magnetometer): every tick of
// scenarios/oh_testbed.yaml (45 sensors, 2 cars, 5 samples a tick) and of the same model over the
// 100 x 100 grid of Oh §VII with 2 and 10 cars, as seconds per sensor and tick, the unit the
// acoustic benchmark also reports.
#include <benchmark/benchmark.h>

#include <cstdint>

#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/magnetometer/magnetometer_field.hpp"
#include "node/tiling.hpp"
#include "scenario/loader.hpp"

namespace {

/// The testbed (grid = 0) or a grid x grid field of pitch 1 with `cars` cars crossing it.
wsn::common::Scenario scenarioWith(std::int64_t grid, std::int64_t cars) {
  auto s = wsn::scenario::loadScenario(WSN_SCENARIO_DIR "/oh_testbed.yaml");
  if (grid > 0) {
    const auto side = static_cast<double>(grid);
    s.region = {-0.5, -0.5, side - 0.5, side - 0.5};
    s.supernodes = {{side / 2.0, side / 2.0}};
    s.targets.scripted.clear();
    for (std::int64_t k = 0; k < cars; ++k) {
      wsn::common::TargetSpec car;
      car.position = {-0.5, (static_cast<double>(k) + 0.5) * side / static_cast<double>(cars)};
      car.velocity = {0.5, 0.05};
      s.targets.scripted.push_back(car);
    }
  }
  return s;
}

/// One iteration: detect() for every tick of the run on one tile holding every sensor.
void detectRun(benchmark::State& state) {
  const auto scenario = scenarioWith(state.range(0), state.range(1));
  const wsn::common::Truth truth(truthConfig(scenario));
  const wsn::common::SensorLayout layout(sensorFieldConfig(scenario));
  const auto tiles = wsn::node::makeTiles(layout, 1);
  std::size_t reports = 0;
  for (auto _ : state) {
    wsn::node::magnetometer::MagnetometerField field(
        wsn::node::magnetometer::fieldConfigOf(scenario.sensor_model, scenario.run.seed), layout, tiles.front(), truth);
    reports = 0;
    for (std::int32_t t = 1; t <= scenario.run.ticks; ++t) reports += field.detect(t).size();
    benchmark::DoNotOptimize(reports);
  }
  const double sensor_ticks = static_cast<double>(layout.size()) * scenario.run.ticks;
  state.counters["s_per_sensor_tick"] =
      benchmark::Counter(sensor_ticks, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["reports_per_tick"] = static_cast<double>(reports) / scenario.run.ticks;
}

// {grid side (0: the testbed as shipped), cars}
BENCHMARK(detectRun)->Args({0, 2})->Args({100, 2})->Args({100, 10})->Unit(benchmark::kMillisecond);

}  // namespace

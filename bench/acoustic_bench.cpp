// Cost of the acoustic Doppler detection model (An et al. 2014 eq. 1-4, node/acoustic): every
// detection of 20 s (200 ticks of 0.1 s, 4000 detection steps of 0.005 s) on the paper's 50 x 50 grid
// for 2-5 targets, the setting of the paper's Fig. 16a, where MATLAB needed 835 s (2 targets) to
// 1897 s (5 targets) of CPU. The targets are the first n of scenarios/an2014_scenario3.yaml (15-25 m/s,
// SR 30-40 m); one tile holds the whole grid. Also with Noise 3 (2013), which adds every sensor's noise draw.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>

#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/acoustic/acoustic_field.hpp"
#include "node/tiling.hpp"
#include "scenario/loader.hpp"

namespace {

wsn::common::Scenario scenarioWith(std::int64_t targets, bool noise) {
  auto s = wsn::scenario::loadScenario(WSN_SCENARIO_DIR "/an2014_scenario3.yaml");
  s.targets.scripted.resize(static_cast<std::size_t>(targets));
  s.run.ticks = 200;
  if (noise) {
    auto settings = std::make_shared<wsn::node::acoustic::AcousticSettings>(
        wsn::common::settingsOf<wsn::node::acoustic::AcousticSettings>(s.sensor_model));
    settings->environmental_noise.components = *wsn::node::acoustic::noisePreset("noise3");
    s.sensor_model.settings = settings;
  }
  return s;
}

/// One iteration: detect() for every tick of the 20 s run; the counter gives seconds per 20-s run.
void detectRun(benchmark::State& state, bool noise) {
  const auto scenario = scenarioWith(state.range(0), noise);
  const wsn::common::Truth truth(truthConfig(scenario));
  const wsn::common::SensorLayout layout(sensorFieldConfig(scenario));
  const auto tiles = wsn::node::makeTiles(layout, 1);
  const wsn::node::acoustic::AcousticField field(wsn::node::acoustic::fieldConfigOf(scenario), layout, tiles.front(), truth);
  std::size_t detections = 0;
  for (auto _ : state) {
    detections = 0;
    for (std::int32_t t = 1; t <= scenario.run.ticks; ++t) detections += field.detect(t).size();
    benchmark::DoNotOptimize(detections);
  }
  state.counters["s_per_20s_run"] =
      benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["detections_per_tick"] = static_cast<double>(detections) / scenario.run.ticks;
  // The unit the magnetometer benchmark reports too.
  state.counters["s_per_sensor_tick"] =
      benchmark::Counter(static_cast<double>(layout.size()) * scenario.run.ticks,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_AcousticDetection(benchmark::State& state) { detectRun(state, false); }
void BM_AcousticDetectionNoise3(benchmark::State& state) { detectRun(state, true); }

BENCHMARK(BM_AcousticDetection)->DenseRange(2, 5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AcousticDetectionNoise3)->Arg(1)->Arg(5)->Unit(benchmark::kMillisecond);

}  // namespace

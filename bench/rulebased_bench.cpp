// Cost of the fusion centre (An et al. 2014 §5.4, Fig. 16b): one SupernodeTracker::step of the
// rule-based engine per tick of 0.1 s -- clustering, merge/split association and Kalman filters,
// plus the noise mitigation of An et al. 2013 where the scenario turns it on. The input is what the
// acoustic sensors of the shipped scenarios report (node/acoustic, one tile, no network faults),
// computed once before timing. The paper's MATLAB took 0.01-0.016 s per call for 2-5 targets.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>
#include <vector>

#include "common/messages.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/acoustic/acoustic_field.hpp"
#include "node/tiling.hpp"
#include "scenario/loader.hpp"
#include "supernode/supernode_tracker.hpp"

namespace {

struct Input {
  wsn::common::Scenario scenario;
  std::vector<std::vector<wsn::common::Observation>> per_tick;  ///< index = tick; [0] unused
  double detections_per_tick = 0.0;
};

/// The scenario's detections of every tick, delivered at once to supernode 0.
Input loadInput(const std::string& name) {
  Input in;
  in.scenario = wsn::scenario::loadScenario(std::string(WSN_SCENARIO_DIR "/") + name + ".yaml");
  wsn::supernode::resolveEngineParams(in.scenario, wsn::common::kNoStatistics);
  const wsn::common::Truth truth(truthConfig(in.scenario));
  const wsn::common::SensorLayout layout(sensorFieldConfig(in.scenario));
  const auto tiles = wsn::node::makeTiles(layout, 1);
  const wsn::node::acoustic::AcousticField field(wsn::node::acoustic::fieldConfigOf(in.scenario), layout, tiles.front(), truth);
  in.per_tick.resize(static_cast<std::size_t>(in.scenario.run.ticks) + 1);
  std::size_t total = 0;
  for (std::int32_t t = 1; t <= in.scenario.run.ticks; ++t) {
    for (const auto& r : field.detect(t))
      in.per_tick[static_cast<std::size_t>(t)].push_back({t, t, r.sensor, r.x, r.y, r.target, r.power_level});
    total += in.per_tick[static_cast<std::size_t>(t)].size();
  }
  in.detections_per_tick = static_cast<double>(total) / in.scenario.run.ticks;
  return in;
}

/// One iteration tracks the whole scenario with a fresh tracker; the counter gives seconds per tick.
void runScenario(benchmark::State& state, const std::string& name) {
  const Input in = loadInput(name);
  const auto ticks = in.scenario.run.ticks;
  for (auto _ : state) {
    wsn::supernode::SupernodeTracker tracker(wsn::supernode::supernodeConfig(in.scenario, 0));
    std::size_t tracks = 0;
    for (std::int32_t t = 1; t <= ticks; ++t) tracks += tracker.step(t, in.per_tick[static_cast<std::size_t>(t)], {}).tracks.size();
    benchmark::DoNotOptimize(tracks);
  }
  state.counters["s_per_call"] =
      benchmark::Counter(static_cast<double>(ticks), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["detections_per_tick"] = in.detections_per_tick;
  state.counters["targets"] = static_cast<double>(in.scenario.targets.scripted.size());
}

BENCHMARK_CAPTURE(runScenario, scenario1_3_targets, std::string("an2014_scenario1"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(runScenario, scenario2_3_targets, std::string("an2014_scenario2"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(runScenario, scenario3_5_targets, std::string("an2014_scenario3"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(runScenario, noise3_denoise_1_target, std::string("an2013_noise3"))->Unit(benchmark::kMillisecond);

}  // namespace

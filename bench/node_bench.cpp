// Cost of one sensor tile per tick: detection (Oh eq. 5) plus neighbour election and centre of
// mass (Oh eq. 6), for the paper's 100 x 100 field and a 1000 x 1000 field (10^6 sensors), each
// as a single tile with 10 targets.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "common/rng.hpp"
#include "common/scenario_config.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/signal_strength/sensor_field.hpp"
#include "node/tiling.hpp"

namespace {

using wsn::common::TargetState;

/// A square field of side `side` (spacing 1) with the paper's sensor model, as one tile.
struct Field {
  explicit Field(double side) : scenario(makeScenario(side)), layout(sensorFieldConfig(scenario)), tiles(wsn::node::makeTiles(layout, 1)),
                                field(wsn::node::signal_strength::SignalStrengthSettings{}, scenario.sensor_model.sensing_range,
                                      scenario.run.seed, layout, tiles[0]) {}
  static wsn::common::Scenario makeScenario(double side) {
    wsn::common::Scenario s;
    s.region = {0.0, 0.0, side, side};
    s.run.seed = 1;
    return s;
  }
  /// 10 targets at fixed random positions, drifting one unit per 10 ticks.
  std::vector<TargetState> targetsAt(std::int32_t tick) const {
    std::vector<TargetState> targets;
    const double side = scenario.region.width();
    for (int k = 0; k < 10; ++k) {
      wsn::common::Stream place(7, wsn::common::Purpose::kTruthInitial, static_cast<std::uint64_t>(k), 0);
      const double x = place.uniform(5.0, side - 5.0) + 0.1 * (tick % 40);
      const double y = place.uniform(5.0, side - 5.0) + 0.07 * (tick % 40);
      targets.push_back({k, x, y, 0.1, 0.07});
    }
    return targets;
  }
  wsn::common::Scenario scenario;
  wsn::common::SensorLayout layout;
  std::vector<wsn::node::Tile> tiles;
  wsn::node::SensorField field;
};

void detectAndFuse(benchmark::State& state) {
  const Field f(static_cast<double>(state.range(0)));
  std::int32_t tick = 0;
  std::int64_t readings = 0;
  std::int64_t reports = 0;
  for (auto _ : state) {
    ++tick;
    const auto targets = f.targetsAt(tick);
    const auto own = f.field.detect(tick, targets);
    const auto fused = f.field.fuse(tick, own, {}, targets);
    readings += static_cast<std::int64_t>(own.size());
    reports += static_cast<std::int64_t>(fused.size());
    benchmark::DoNotOptimize(fused.data());
  }
  state.counters["sensors"] = static_cast<double>(f.layout.size());
  state.counters["readings/tick"] = benchmark::Counter(static_cast<double>(readings), benchmark::Counter::kAvgIterations);
  state.counters["reports/tick"] = benchmark::Counter(static_cast<double>(reports), benchmark::Counter::kAvgIterations);
}

void detectOnly(benchmark::State& state) {
  const Field f(static_cast<double>(state.range(0)));
  std::int32_t tick = 0;
  for (auto _ : state) {
    ++tick;
    const auto targets = f.targetsAt(tick);
    benchmark::DoNotOptimize(f.field.detect(tick, targets).data());
  }
}

void fuseOnly(benchmark::State& state) {
  const Field f(static_cast<double>(state.range(0)));
  const auto targets = f.targetsAt(1);
  const auto own = f.field.detect(1, targets);
  for (auto _ : state) benchmark::DoNotOptimize(f.field.fuse(1, own, {}, targets).data());
}

}  // namespace

// Time per tick: one iteration is one tick of one tile.
BENCHMARK(detectAndFuse)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(detectOnly)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(fuseOnly)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

// Cost of one supernode tick of the MCMCDA engine (Oh et al. §VI; ws = 10, nmc = 1000): one
// SupernodeTracker::step, i.e. slide the window, build the association problem, run the chain,
// derive identities and tracks. Also the Markov chain alone (Sampler on a fixed Problem).
//
// Load: what one supernode of scenarios/oh_quadrants.yaml sees, measured from a real run (seed 1):
// its quadrant is 50 x 50, about 1.5 live targets are in it on average, each target's fused report
// reaches the supernode with probability ~0.7 per tick (error ~0.1 per axis), ~30% of delivered
// reports arrive 1-3 ticks late, and ~1.1 false alarms per tick arrive, uniform over the quadrant.
// A synthetic generator reproduces those rates, so that the benchmark needs neither the sensor
// field nor the network model, and scales them (targets and false alarms alike) to 2x and 4x.
//
// The same supernode tick of the GNN and sbmht engines on the same loads (engineTick), so that
// the engines' costs per supernode per tick compare at one load (docs/ONERA.md §8).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/messages.hpp"
#include "common/rng.hpp"
#include "common/scenario_config.hpp"
#include "supernode/engine.hpp"
#include "supernode/mcmcda/mcmcda_engine.hpp"
#include "supernode/mcmcda/problem.hpp"
#include "supernode/mcmcda/sampler.hpp"
#include "supernode/observation_window.hpp"
#include "supernode/supernode_tracker.hpp"

namespace {

using wsn::common::Observation;
using wsn::common::Purpose;
using wsn::common::Stream;

constexpr std::int32_t kWindowSize = 10;     // Oh §VII: ws = 10
constexpr std::int64_t kIterations = 1000;   // nmc per tick
constexpr std::int32_t kTicks = 2000;        // pre-generated; a timing run that needs more replays them
constexpr std::int32_t kWarmUpTicks = 20;    // the window is full after 10; 10 more give tracks anchors
constexpr std::uint64_t kSeed = 1;

// The 1x load (see the header). The quadrant is the lower-left one of oh_quadrants.yaml.
constexpr double kSide = 50.0;
constexpr double kDeliveryProbability = 0.7;
constexpr double kFusedSigma = 0.1;
constexpr double kLateProbability = 0.3;
constexpr std::int32_t kMaxLate = 3;
constexpr double kFalseAlarmsPerTick = 1.1;
// A target is born uniformly in the quadrant and lives 51-60 ticks (the scripted lifetimes of
// oh_quadrants.yaml) or until it leaves the quadrant, whichever comes first: ~20 ticks on average
// (about as long as a real target stays in one quadrant), so 0.073 births per tick keep 1.5 targets
// alive on average (measured over 20000 ticks; the timed ticks' mean is the "targets" counter).
constexpr double kBirthsPerTick = 0.073;
constexpr double kMinSpeed = 0.4;  // |vx|, |vy| per tick: oh_quadrants.yaml's scripted range
constexpr double kMaxSpeed = 1.3;

/// Deliveries of ticks 1..kTicks under the synthetic load, plus the truth needed for counters.
struct Load {
  std::vector<std::vector<Observation>> delivered;  ///< index = tick_delivered; [0] unused
  std::vector<std::int32_t> live_targets;           ///< index = tick

  std::span<const Observation> at(std::int32_t tick) const { return delivered[static_cast<std::size_t>(tick)]; }
};

/// Row-major grid sensor of the cell holding (x, y) on oh_quadrants.yaml's 100 x 100 grid.
wsn::common::SensorId sensorAt(double x, double y) {
  const auto cell = [](double v) { return static_cast<wsn::common::SensorId>(std::clamp(std::floor(v), 0.0, 99.0)); };
  return cell(y) * 100u + cell(x);
}

/// Ticks a delivered report is late: 0 with probability 1 - kLateProbability, else 1, 2 or 3 with
/// falling probabilities, as eq. (7)'s negative binomial over a few hops puts most of a delay's
/// mass on one tick (geometric with success 0.7, capped at kMaxLate).
std::int32_t lateness(Stream& stream) {
  if (!stream.bernoulli(kLateProbability)) return 0;
  return static_cast<std::int32_t>(std::min<std::uint64_t>(1 + stream.geometric(0.7), kMaxLate));
}

/// The deterministic synthetic load at `scale` times the 1x rates. Every draw comes from a stream
/// keyed by (seed, purpose, entity, tick), so a load never depends on generation order.
Load makeLoad(std::int32_t scale, double process_noise_sigma) {
  struct Target {
    std::int32_t id;
    std::int32_t dies;  // first tick it is gone
    double x, y, vx, vy;
  };
  Load load;
  load.delivered.resize(kTicks + 1);
  load.live_targets.resize(kTicks + 1);
  // The scale is part of every key so that the loads are independent draws, not sharing their first targets.
  const auto key = [scale](std::int64_t entity) {
    return static_cast<std::uint64_t>(scale) << 32 | static_cast<std::uint64_t>(entity);
  };
  const auto deliver = [&](Observation o, Stream& network) {
    if (!network.bernoulli(kDeliveryProbability)) return;
    o.tick_delivered = o.tick_generated + lateness(network);
    if (o.tick_delivered <= kTicks) load.delivered[static_cast<std::size_t>(o.tick_delivered)].push_back(o);
  };
  std::vector<Target> live;
  std::int32_t next_id = 0;
  for (std::int32_t t = 1; t <= kTicks; ++t) {
    // Eq. (8) with delta = 1: x += v + q/2 w, v += q w.
    for (auto& target : live) {
      Stream noise(kSeed, Purpose::kTruthProcessNoise, key(target.id), t);
      const double wx = process_noise_sigma * noise.normal();
      const double wy = process_noise_sigma * noise.normal();
      target.x += target.vx + 0.5 * wx;
      target.y += target.vy + 0.5 * wy;
      target.vx += wx;
      target.vy += wy;
    }
    std::erase_if(live, [t](const Target& target) {
      return t >= target.dies || target.x < 0.0 || target.x > kSide || target.y < 0.0 || target.y > kSide;
    });
    // Births on a regular schedule rather than Poisson, as oh_quadrants.yaml scripts them (one
    // every ~5 ticks over the field): random birth counts would make the load of the few hundred
    // ticks a benchmark run times stray from the nominal one by 10% and more.
    const double rate = kBirthsPerTick * scale;
    const auto births = static_cast<std::int32_t>(std::floor(t * rate) - std::floor((t - 1) * rate));
    for (std::int32_t n = 0; n < births; ++n) {
      Stream initial(kSeed, Purpose::kTruthInitial, key(next_id), 0);
      const auto velocity = [&initial] {
        return (initial.bernoulli(0.5) ? 1.0 : -1.0) * initial.uniform(kMinSpeed, kMaxSpeed);
      };
      Target target{next_id++, 0, initial.uniform(0.0, kSide), initial.uniform(0.0, kSide), 0.0, 0.0};
      target.vx = velocity();
      target.vy = velocity();
      target.dies = t + 51 + static_cast<std::int32_t>(initial.below(10));
      live.push_back(target);
    }
    load.live_targets[static_cast<std::size_t>(t)] = static_cast<std::int32_t>(live.size());

    for (const auto& target : live) {
      Stream sensing(kSeed, Purpose::kSensorNoise, key(target.id), t);
      const double x = target.x + kFusedSigma * sensing.normal();
      const double y = target.y + kFusedSigma * sensing.normal();
      Stream network(kSeed, Purpose::kNetworkLoss, key(target.id), t);
      deliver(Observation{t, 0, sensorAt(x, y), x, y, target.id}, network);
    }
    // The false-alarm rate is that of *delivered* reports, so false alarms are generated at the
    // rate divided by the delivery probability and then go through the same network.
    Stream clutter(kSeed, Purpose::kNoiseExceedance, key(0), t);
    for (auto n = clutter.poisson(kFalseAlarmsPerTick * scale / kDeliveryProbability); n > 0; --n) {
      const double x = clutter.uniform(0.0, kSide);
      const double y = clutter.uniform(0.0, kSide);
      deliver(Observation{t, 0, sensorAt(x, y), x, y, wsn::common::kFalseAlarm}, clutter);
    }
  }
  return load;
}

/// One supernode (the quadrant's centre) running `engine` with its defaults, as
/// `wsntrack run scenarios/oh_quadrants.yaml --set tracker.engine=ENGINE` would, for one quadrant.
/// With a single supernode nothing is handed over: a target leaving the quadrant simply ends.
const wsn::common::Scenario& benchScenario(const std::string& engine = "mcmcda") {
  static std::map<std::string, wsn::common::Scenario> scenarios;
  auto found = scenarios.find(engine);
  if (found != scenarios.end()) return found->second;
  wsn::common::Scenario s;
  s.source_path = "mcmcda_bench";
  s.region = {0.0, 0.0, kSide, kSide};
  s.supernodes = {{kSide / 2, kSide / 2}};
  s.run.seed = kSeed;
  s.tracker.engine = engine;
  s.tracker.window_size = kWindowSize;
  if (engine == "mcmcda") s.tracker.params["iterations"] = {static_cast<double>(kIterations), 0};
  wsn::supernode::resolveEngineParams(s, wsn::common::kNoStatistics);
  return scenarios.emplace(engine, std::move(s)).first->second;
}

/// Loads are built once per scale and shared by every run and repetition of a benchmark.
const Load& loadAt(std::int32_t scale) {
  static std::map<std::int32_t, std::unique_ptr<Load>> loads;
  auto& load = loads[scale];
  if (!load) load = std::make_unique<Load>(makeLoad(scale, benchScenario().dynamics.process_noise_sigma));
  return *load;
}

/// A fresh tracker stepped through ticks 1..kWarmUpTicks; returns the next tick to step.
std::int32_t warmUp(std::unique_ptr<wsn::supernode::SupernodeTracker>& tracker, const Load& load,
                    const std::string& engine) {
  tracker =
      std::make_unique<wsn::supernode::SupernodeTracker>(wsn::supernode::supernodeConfig(benchScenario(engine), 0));
  for (std::int32_t t = 1; t <= kWarmUpTicks; ++t) tracker->step(t, load.at(t), {});
  return kWarmUpTicks + 1;
}

void engineTick(benchmark::State& state, const std::string& engine) {
  const auto scale = static_cast<std::int32_t>(state.range(0));
  const Load& load = loadAt(scale);
  std::unique_ptr<wsn::supernode::SupernodeTracker> tracker;
  std::int32_t tick = warmUp(tracker, load, engine);
  double window_observations = 0.0;
  double tracks = 0.0;
  double targets = 0.0;
  for (auto _ : state) {
    if (tick > kTicks) {
      // Ticks only move forward, so the load is replayed by a new tracker; its set-up is untimed.
      state.PauseTiming();
      tick = warmUp(tracker, load, engine);
      state.ResumeTiming();
    }
    const auto out = tracker->step(tick, load.at(tick), {});
    benchmark::DoNotOptimize(out.tracks.data());
    window_observations += out.observations_in_window;
    tracks += static_cast<double>(out.tracks.size());
    targets += load.live_targets[static_cast<std::size_t>(tick)];
    ++tick;
  }
  using benchmark::Counter;
  state.counters["obs/window"] = Counter(window_observations, Counter::kAvgIterations);
  state.counters["tracks"] = Counter(tracks, Counter::kAvgIterations);
  state.counters["targets"] = Counter(targets, Counter::kAvgIterations);
  if (engine == "mcmcda")
    state.counters["chain_it/s"] = Counter(static_cast<double>(kIterations * state.iterations()), Counter::kIsRate);
  state.counters["ticks/s"] = Counter(static_cast<double>(state.iterations()), Counter::kIsRate);
}

void supernodeTick(benchmark::State& state) { engineTick(state, "mcmcda"); }

/// The window of the load at `scale` whose size is the median over ticks after the warm-up, as a
/// Problem of its observations. Without the engine's anchors (the summaries of tracks older than
/// the window), which add about one observation per live track.
wsn::supernode::mcmcda::Problem typicalProblem(std::int32_t scale) {
  const Load& load = loadAt(scale);
  wsn::supernode::ObservationWindow window(kWindowSize);
  std::vector<std::size_t> sizes(kTicks + 1, 0);
  for (std::int32_t t = 1; t <= kTicks; ++t) {
    window.advanceTo(t);
    for (const auto& o : load.at(t)) window.insert(o);
    sizes[static_cast<std::size_t>(t)] = window.size();
  }
  std::vector<std::size_t> steady(sizes.begin() + kWarmUpTicks + 1, sizes.end());
  std::nth_element(steady.begin(), steady.begin() + static_cast<std::ptrdiff_t>(steady.size() / 2), steady.end());
  const std::size_t median = steady[steady.size() / 2];
  const auto tick = static_cast<std::int32_t>(
      std::find(sizes.begin() + kWarmUpTicks + 1, sizes.end(), median) - sizes.begin());

  // Replay up to that tick: the window keeps no history to rewind.
  wsn::supernode::ObservationWindow typical(kWindowSize);
  for (std::int32_t t = 1; t <= tick; ++t) {
    typical.advanceTo(t);
    for (const auto& o : load.at(t)) typical.insert(o);
  }
  std::vector<wsn::supernode::mcmcda::ProblemObservation> observations;
  for (std::int32_t t = typical.oldestTick(); t <= tick; ++t)
    for (const auto& o : typical.slot(t)) observations.push_back({o.tick_generated, o.x, o.y, false, {}});
  const auto params = wsn::supernode::mcmcda::McmcdaParams::fromContext(wsn::supernode::engineContext(benchScenario(), 0));
  return wsn::supernode::mcmcda::Problem(params.model, std::move(observations), tick);
}

void samplerChain(benchmark::State& state) {
  const auto problem = typicalProblem(static_cast<std::int32_t>(state.range(0)));
  using wsn::supernode::mcmcda::ProposalSets;
  wsn::supernode::mcmcda::Sampler sampler(problem, state.range(1) == 0 ? ProposalSets::kRescan : ProposalSets::kKept);
  Stream rng(kSeed, Purpose::kTracker, 0, problem.lastTick());
  // The engine starts each tick's chain near the mode (previous best plus a greedy guess); one
  // untimed chain from the empty partition gets this one there too.
  sampler.run(kIterations, rng);
  for (auto _ : state) {
    sampler.run(kIterations, rng);
    benchmark::DoNotOptimize(sampler.logPosterior());
  }
  using benchmark::Counter;
  state.counters["obs"] = static_cast<double>(problem.size());
  state.counters["chain_it/s"] = Counter(static_cast<double>(kIterations * state.iterations()), Counter::kIsRate);
}

}  // namespace

// One iteration = one supernode tick at 1x, 2x and 4x the load of one oh_quadrants supernode.
BENCHMARK(supernodeTick)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);
// The same ticks of the other window engines.
BENCHMARK_CAPTURE(engineTick, gnn, std::string("gnn"))->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(engineTick, sbmht, std::string("sbmht"))->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);
// One iteration = one chain of nmc iterations on the median window of the same loads, and of
// 16x and 64x (windows the size of the aggregator's at city scale), with the proposal sets found
// by rescans (second argument 0) or kept (1): what sets kKeepProposalSetsFrom.
BENCHMARK(samplerChain)
    ->ArgsProduct({{1, 2, 4, 16, 64}, {0, 1}})
    ->ArgNames({"load", "kept"})
    ->Unit(benchmark::kMillisecond);

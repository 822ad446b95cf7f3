// The stop-mode metric (aggregator/metric/stop_mode.cpp) against a hand-counted run.
#include <catch2/catch.hpp>

#include <cstdint>
#include <optional>
#include <vector>

#include "aggregator/metric/metric.hpp"
#include "common/truth.hpp"
#include "tests/aggregator/test_support.hpp"

namespace wsn::aggregator {
namespace {

TEST_CASE("stop_mode averages the stop probability apart while stopped and while moving", "[metric][stop_mode]") {
  // Target 0 stands still at ticks 1-2 and moves at tick 3; target 1 moves throughout. Target 0's
  // track says .9, .7, then .2; target 1's .1 at ticks 1 and 3 and nothing (an engine without a
  // stop model) at tick 2. A far track is false: not counted.
  auto metric = metricRegistry().at("stop_mode").create(common::MetricsConfig{}, {{50, 50}});
  const std::vector<std::optional<double>> track0{0.9, 0.7, 0.2};
  const std::vector<std::optional<double>> track1{0.1, std::nullopt, 0.1};
  for (std::int32_t t = 1; t <= 3; ++t) {
    const double vx = t == 3 ? 1.0 : 0.0;
    const std::vector<common::TargetState> truth{test::target(0, 0, 0, vx), test::target(1, 10, 0, 0.0, 2.0)};
    std::vector<common::TrackEstimate> tracks{test::track(1, 0, 0), test::track(2, 10, 0), test::track(3, 500, 500)};
    tracks[0].stop_probability = track0[static_cast<std::size_t>(t - 1)];
    tracks[1].stop_probability = track1[static_cast<std::size_t>(t - 1)];
    tracks[2].stop_probability = 1.0;
    metric->add(MetricTick{t, truth, tracks});
  }
  const Json summary = metric->finish().summary;
  INFO(summary.dump(2));
  // Stopped: (.9 + .7) / 2. Moving: target 0's .2 and target 1's two .1, (.2 + .1 + .1) / 3.
  CHECK(summary.at("ticks_stopped") == 2);
  CHECK(summary.at("mean_stop_probability_stopped").get<double>() == Approx(0.8));
  CHECK(summary.at("ticks_moving") == 3);
  CHECK(summary.at("mean_stop_probability_moving").get<double>() == Approx(0.4 / 3.0));
  CHECK(summary.at("ticks_without_stop_model") == 1);
  const Json& targets = summary.at("targets");
  REQUIRE(targets.size() == 2);
  CHECK(targets[0].at("ticks_stopped") == 2);
  CHECK(targets[0].at("mean_stop_probability_moving").get<double>() == Approx(0.2));
  CHECK(targets[1].at("ticks_stopped") == 0);
  CHECK(targets[1].at("mean_stop_probability_stopped").is_null());
  CHECK(targets[1].at("mean_stop_probability_moving").get<double>() == Approx(0.1));
}

TEST_CASE("stop_mode is null for an engine without a stop model", "[metric][stop_mode]") {
  auto metric = metricRegistry().at("stop_mode").create(common::MetricsConfig{}, {{50, 50}});
  metric->add(MetricTick{1, {test::target(0, 0, 0)}, {test::track(1, 0, 0)}});
  const Json summary = metric->finish().summary;
  CHECK(summary.at("ticks_stopped") == 0);
  CHECK(summary.at("mean_stop_probability_stopped").is_null());
  CHECK(summary.at("ticks_without_stop_model") == 1);
}

}  // namespace
}  // namespace wsn::aggregator

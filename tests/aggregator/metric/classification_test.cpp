// The classification metric (aggregator/metric/classification.cpp) against a hand-counted run.
#include <catch2/catch.hpp>

#include <vector>

#include "aggregator/metric/metric.hpp"
#include "common/truth.hpp"
#include "tests/aggregator/test_support.hpp"

namespace wsn::aggregator {
namespace {

using common::TargetClass;

/// beta with `p` on class index `index` and the rest spread evenly over the other five.
std::vector<double> declaring(std::size_t index, double p = 0.9) {
  std::vector<double> beta(6, (1.0 - p) / 5.0);
  beta[index] = p;
  return beta;
}

TEST_CASE("classification counts true against declared class over the unique assignment", "[metric][classification]") {
  // A human (target 0), a light wheeled vehicle (1) and a target of no known class (2), three ticks.
  // Target 0's track declares human, then group, then nothing (uniform); target 1's light wheeled
  // every tick; target 2's human. A fourth track far from everyone is a false track: not counted.
  auto human = test::target(0, 0, 0);
  human.target_class = TargetClass::kHuman;
  auto car = test::target(1, 10, 0);
  car.target_class = TargetClass::kWheeledLight;
  const auto unknown = test::target(2, 50, 0);
  const std::vector<common::TargetState> truth{human, car, unknown};
  const std::vector<std::vector<double>> human_track{declaring(3), declaring(4), std::vector<double>(6, 1.0 / 6.0)};

  auto metric = metricRegistry().at("classification").create(common::MetricsConfig{}, {{50, 50}});
  for (std::int32_t t = 1; t <= 3; ++t) {
    std::vector<common::TrackEstimate> tracks{test::track(1, 0, 0), test::track(2, 10, 0), test::track(3, 50, 0),
                                              test::track(4, 500, 500)};
    tracks[0].class_probabilities = human_track[static_cast<std::size_t>(t - 1)];
    tracks[1].class_probabilities = declaring(0);
    tracks[2].class_probabilities = declaring(3);
    tracks[3].class_probabilities = declaring(5);
    metric->add(MetricTick{t, truth, tracks});
  }
  const Json summary = metric->finish().summary;
  INFO(summary.dump(2));
  // Over the targets of known class: 6 associated ticks, 5 with a class declared, 4 right.
  CHECK(summary.at("ticks_associated") == 6);
  CHECK(summary.at("ticks_declared") == 5);
  CHECK(summary.at("ticks_correct") == 4);
  CHECK(summary.at("declared_share").get<double>() == Approx(5.0 / 6.0));
  CHECK(summary.at("class_accuracy").get<double>() == Approx(0.8));
  const Json& confusion = summary.at("confusion");
  CHECK(confusion.at("human").at("human") == 1);
  CHECK(confusion.at("human").at("group") == 1);
  CHECK(confusion.at("human").at("none") == 1);
  CHECK(confusion.at("human").at("aerial") == 0);
  CHECK(confusion.at("wheeled_light").at("wheeled_light") == 3);
  CHECK(confusion.at("unknown").at("human") == 3);
  CHECK_FALSE(confusion.contains("tracked"));  // no tracked target: no row
  const Json& targets = summary.at("targets");
  REQUIRE(targets.size() == 3);
  CHECK(targets[0].at("class") == "human");
  CHECK(targets[0].at("class_accuracy").get<double>() == Approx(0.5));
  CHECK(targets[1].at("class_accuracy").get<double>() == Approx(1.0));
  CHECK(targets[2].at("class") == "unknown");
  CHECK(targets[2].at("ticks_declared") == 3);
  CHECK(targets[2].at("class_accuracy").is_null());  // nothing to compare with
}

TEST_CASE("classification of a run without class evidence is empty, not wrong", "[metric][classification]") {
  auto metric = metricRegistry().at("classification").create(common::MetricsConfig{}, {{50, 50}});
  const std::vector<common::TargetState> truth{test::target(0, 0, 0)};
  const std::vector<common::TrackEstimate> tracks{test::track(1, 0, 0)};
  metric->add(MetricTick{1, truth, tracks});
  const Json summary = metric->finish().summary;
  CHECK(summary.at("ticks_associated") == 0);  // the target's class is not known
  CHECK(summary.at("declared_share").is_null());
  CHECK(summary.at("class_accuracy").is_null());
  CHECK(summary.at("confusion").at("unknown").at("none") == 1);
}

}  // namespace
}  // namespace wsn::aggregator

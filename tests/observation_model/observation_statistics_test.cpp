// The statistics a scenario's own models give its observations: measured by simulating the sensor
// field, computed from the network model and the target model; checked against Oh et al.'s
// equations and hand-computed values.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "common/sensor_layout.hpp"
#include "network_model/link_model.hpp"
#include "network_model/role_config.hpp"
#include "network_model/topology.hpp"
#include "observation_model/observation_statistics.hpp"
#include "scenario/overrides.hpp"

using namespace wsn;
using common::Scenario;

namespace {

std::vector<scenario::ScenarioOverride> overridesOf(const std::vector<std::string>& sets) {
  std::vector<scenario::ScenarioOverride> overrides;
  for (const auto& text : sets) overrides.push_back(scenario::parseOverride(text));
  return overrides;
}

Scenario shipped(const std::string& name, const std::vector<std::string>& sets = {}) {
  return scenario::loadScenario(std::string(WSN_SCENARIO_DIR) + "/" + name + ".yaml", overridesOf(sets));
}

}  // namespace

TEST_CASE("without sensor noise every probe target is reported and nothing else is") {
  // oh_single_supernode: noise_sigma = 0, so z >= eta only within Rs of a target (Oh eq. 5).
  const auto stats = observation_model::observationStatistics(shipped("oh_single_supernode"));
  CHECK(stats.sensing_probability.value == 1.0);
  // None seen on the probe's empty ticks: the rule-of-three bound, 3 reports over them.
  CHECK(stats.false_report_density.value > 0.0);
  CHECK(stats.false_report_density.value < 1e-4);
  CHECK_THAT(stats.false_report_density.how, Catch::Matchers::Contains("rule of three"));
  // The weighted centre of mass of the sensors within Rs = 1.5 on a unit grid errs by a
  // fraction of the spacing, never by more than Rs.
  CHECK(stats.position_sigma.value > 0.0);
  CHECK(stats.position_sigma.value < 0.5);
  CHECK(stats.delivery_probability.value == 1.0);  // pte = pde = 0
}

TEST_CASE("the probe counts false reports at the exceedance rate of eq. 5") {
  // oh_quadrants: 10^4 sensors, eta = 2, noise_sigma = 0.62: q = P(w >= 2 / 0.62) = 6.28e-4 per
  // sensor and tick, 6.28 exceedances per tick over 10^4 area. Almost all are alone within 2 Rs,
  // so each is elected and reported (Oh eq. 6): about 6.3e-4 reports per area and tick. The probe
  // counts 34 empty ticks (about 213 reports, +-7 %).
  const auto stats = observation_model::observationStatistics(shipped("oh_quadrants"));
  const double q = 0.5 * std::erfc(2.0 / 0.62 / std::sqrt(2.0));
  CHECK(q == Approx(6.28e-4).epsilon(0.01));
  CHECK(stats.false_report_density.value > 0.8 * q);
  CHECK(stats.false_report_density.value < 1.15 * q);
}

TEST_CASE("delivery is the in-window share of Oh eq. 7 over the topology") {
  // With pde = 0 nothing is delayed: the delivered share is the mean of pts(pte, hops) over the
  // sensors, unreachable ones counting 0.
  Scenario s = shipped("oh_quadrants", {"network.pde=0"});
  const auto stats = observation_model::observationStatistics(s);
  s.run.seed = 0x0b5e7a7105eedULL;  // the probe's own layout seed (a grid does not depend on it)
  const common::SensorLayout layout(common::sensorFieldConfig(s));
  const network_model::Topology topology(network_model::topologyConfig(s), layout.truePositions());
  double delivered = 0.0;
  for (const auto hops : topology.allHops()) delivered += network_model::successProbability(s.network.pte, hops);
  delivered /= static_cast<double>(topology.sensorCount());
  CHECK(stats.delivery_probability.value == Approx(delivered).epsilon(1e-12));
  CHECK(stats.detectionProbability() == Approx(stats.sensing_probability.value * delivered));
}

TEST_CASE("the statistics describe the model, the same for every seed") {
  const auto a = observation_model::observationStatistics(shipped("oh_quadrants"));
  const auto b = observation_model::observationStatistics(shipped("oh_quadrants", {"run.seed=77"}));
  CHECK(a.position_sigma.value == b.position_sigma.value);
  CHECK(a.sensing_probability.value == b.sensing_probability.value);
  CHECK(a.false_report_density.value == b.false_report_density.value);
  CHECK(a.delivery_probability.value == b.delivery_probability.value);
}

TEST_CASE("localisation error widens the report error") {
  const auto exact = observation_model::observationStatistics(shipped("oh_single_supernode"));
  const auto sloppy =
      observation_model::observationStatistics(shipped("oh_single_supernode", {"localisation.sigma=1"}));
  // A report averages the believed positions of a few sensors, each off by N(0, 1) per axis:
  // its error grows well beyond the exact grid's, yet stays below one sensor's sigma.
  CHECK(sloppy.position_sigma.value > 3.0 * exact.position_sigma.value);
  CHECK(sloppy.position_sigma.value < 1.0);
}

TEST_CASE("target statistics follow the speed class, births, deaths and the region") {
  Scenario s;  // 100 x 100, T = 100, q = 0.15 by default
  s.region = {0, 0, 100, 100};
  s.run.ticks = 100;
  s.dynamics.process_noise_sigma = 0.15;
  s.targets.speed_class = common::SpeedClass::kFast;  // |v| per axis uniform in [2, 5]
  s.targets.birth_rate = 2e-5;
  s.targets.death_probability = 0.05;
  common::ObservationStatistics stats;
  observation_model::deriveTargetStatistics(s, stats);
  // E v^2 = (a^2 + a b + b^2) / 3 = (4 + 10 + 25) / 3 = 13.
  CHECK(stats.velocity_sigma.value == Approx(std::sqrt(13.0)));
  // sqrt 2 (5 + 2 x 0.15 x sqrt 100) = sqrt 2 x 8.
  CHECK(stats.max_speed.value == Approx(8.0 * std::sqrt(2.0)));
  CHECK(stats.birth_density.value == Approx(2e-5));
  // Mean chord pi A / perimeter = pi 10^4 / 400 = 78.54, crossed at sqrt(2 x 13) = 5.10 per tick.
  const double exit = std::sqrt(26.0) / (std::numbers::pi * 1e4 / 400.0);
  CHECK(stats.termination_probability.value == Approx(1.0 - 0.95 * (1.0 - exit)));
}

TEST_CASE("scripted targets give their own velocities, lifetimes and birth rate") {
  Scenario s;
  s.region = {0, 0, 100, 100};
  s.run.ticks = 50;
  s.dynamics.process_noise_sigma = 0.0;
  s.targets.birth_rate = 0.0;
  const auto scripted = [](std::int32_t appear, std::int32_t disappear, common::Vec2 position, common::Vec2 velocity) {
    common::TargetSpec spec;
    spec.appear_tick = appear;
    spec.disappear_tick = disappear;
    spec.position = position;
    spec.velocity = velocity;
    return spec;
  };
  s.targets.scripted = {scripted(1, 21, {10, 10}, {3, 4}), scripted(11, 0, {50, 50}, {-1, 0})};
  common::ObservationStatistics stats;
  observation_model::deriveTargetStatistics(s, stats);
  // Per-axis mean square: (9 + 16 + 1 + 0) / 4 = 6.5.
  CHECK(stats.velocity_sigma.value == Approx(std::sqrt(6.5)));
  CHECK(stats.max_speed.value == Approx(4.0 * std::sqrt(2.0)));  // no process noise: no drift
  // Two targets over 10^4 x 50 ticks; lifetimes 20 and 40 (ticks 11 .. 50): 2 / 60.
  CHECK(stats.birth_density.value == Approx(2.0 / (1e4 * 50.0)));
  CHECK(stats.termination_probability.value == Approx(2.0 / 60.0));
}

TEST_CASE("a model that reports every detecting sensor is merged at the reach of one target's reports") {
  // oh_testbed: a car excites about two magnetometers a tick (unfused, Oh §VIII). Its reports are
  // the sensors of a unit grid around it, so the reach from the strongest to the others is 1 (a
  // side neighbour) or sqrt 2 (a diagonal one): the 95th percentile is sqrt 2.
  const auto stats = observation_model::observationStatistics(shipped("oh_testbed"));
  CHECK(stats.report_merge_radius.value == Approx(std::sqrt(2.0)));
  CHECK_THAT(stats.report_merge_radius.how, Catch::Matchers::Contains("reports per heard target and tick"));
  CHECK_THAT(stats.position_sigma.how, Catch::Matchers::Contains("merged report"));
  // A merged report lies within about a pitch of its car.
  CHECK(stats.position_sigma.value > 0.1);
  CHECK(stats.position_sigma.value < 0.6);
}

TEST_CASE("a model that fuses its readings has nothing to merge") {
  // Oh eq. 6 elects one sensor per target: about one report per heard target and tick.
  for (const std::string name : {"oh_single_supernode", "adman_three_targets"}) {
    INFO(name);
    const auto stats = observation_model::observationStatistics(shipped(name));
    CHECK(stats.report_merge_radius.value == 0.0);
    CHECK_THAT(stats.report_merge_radius.how, Catch::Matchers::Contains("none to merge"));
  }
}

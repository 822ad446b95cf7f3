// Engine parameters left out of a scenario (or written `auto`) follow its own models: derived at
// load time, noted in the resolved scenario.yaml, overridden by an explicit value.
#include <catch2/catch.hpp>

#include "observation_model/observation_statistics.hpp"
#include "scenario/loader.hpp"
#include "scenario/overrides.hpp"
#include "scenario/writer.hpp"
#include "supernode/engine.hpp"

using namespace wsn;
using common::Scenario;
using Catch::Matchers::Contains;

namespace {

std::vector<scenario::ScenarioOverride> overridesOf(const std::vector<std::string>& sets) {
  std::vector<scenario::ScenarioOverride> overrides;
  for (const auto& text : sets) overrides.push_back(scenario::parseOverride(text));
  return overrides;
}

void resolve(Scenario& s) { supernode::resolveEngineParams(s, observation_model::lazyStatistics(s)); }

Scenario resolved(const std::string& name, const std::vector<std::string>& sets = {}) {
  return scenario::loadScenario(std::string(WSN_SCENARIO_DIR) + "/" + name + ".yaml", overridesOf(sets), resolve);
}

double param(const Scenario& s, const std::string& name) { return s.tracker.params.at(name).value; }

}  // namespace

TEST_CASE("parameters left out are derived and the resolved file says how") {
  const Scenario s = resolved("oh_quadrants");
  for (const char* name : {"detection_probability", "false_alarm_density", "birth_density", "termination_probability",
                           "measurement_sigma", "initial_velocity_sigma", "max_speed", "max_gap",
                           "confirm_observations"})
    CHECK(s.derived.contains(std::string("tracker.params.") + name));
  CHECK_FALSE(s.derived.contains("tracker.params.iterations"));  // no physical meaning: a fixed default
  CHECK(param(s, "iterations") == 1000);
  const std::string yaml = scenario::resolvedScenarioYaml(s);
  // pd = sensing 1 x the share of a window tick's reports there at the newest tick, averaged over
  // the ten lags: 0.345 on time rising to 0.725 delivered into the window (Oh eq. 7 at pte = pde =
  // 0.3 over the quadrant topology), 0.658. At the newest tick only the undelayed reports are
  // there, 0.345: a run of misses as rare as 1 % would take 0.655^k <= 0.01, k = 11, so the gap is
  // capped at ws = 10.
  CHECK(param(s, "detection_probability") == Approx(0.658).margin(0.005));
  CHECK_THAT(yaml, Contains("    max_gap: 10  # derived: smallest k with (1 - pd)^k <= 0.01 at pd 0.3454 on time"));
}

TEST_CASE("the resolved file loads back to the same parameters") {
  const Scenario s = resolved("oh_quadrants");
  Scenario again = scenario::parseScenario(scenario::resolvedScenarioYaml(s), "resolved.yaml");
  resolve(again);
  CHECK(again.tracker.params == s.tracker.params);
  CHECK(again.derived.empty());  // every value is now written out
}

TEST_CASE("an explicit value overrides the derivation and auto asks for it again") {
  const Scenario set = resolved("oh_quadrants", {"tracker.params.max_speed=4"});
  CHECK(param(set, "max_speed") == 4.0);
  CHECK_FALSE(set.derived.contains("tracker.params.max_speed"));
  const Scenario automatic =
      resolved("oh_quadrants", {"tracker.params.max_speed=4", "tracker.params.max_speed=auto"});
  CHECK(automatic.derived.contains("tracker.params.max_speed"));
  CHECK(param(automatic, "max_speed") == param(resolved("oh_quadrants"), "max_speed"));
}

TEST_CASE("a derived value outside the parameter's range is kept in range and says so") {
  // No loss, no delay, no noise: pd would be 1, beyond the admissible 0.999.
  const Scenario s = resolved("oh_single_supernode");
  CHECK(param(s, "detection_probability") == 0.999);
  CHECK_THAT(s.derived.at("tracker.params.detection_probability"), Contains("kept in range"));
}

TEST_CASE("MCMCDA's maximum speed covers the fast class") {
  // Oh §VII-A fast: |v| per axis up to 5, a speed up to 5 sqrt 2 = 7.07 per tick. The old fixed
  // default of 3 found no fast target at all.
  const Scenario s = resolved("oh_single_supernode", {"targets.speed_class=fast"});
  CHECK(param(s, "max_speed") > 5.0 * std::sqrt(2.0));
  CHECK(param(s, "initial_velocity_sigma") > 3.0);
}

TEST_CASE("MCMCDA's measurement sigma follows the localisation error") {
  const double exact = param(resolved("oh_single_supernode"), "measurement_sigma");
  const double sloppy = param(resolved("oh_single_supernode", {"localisation.sigma=2"}), "measurement_sigma");
  CHECK(sloppy > 5.0 * exact);
}

TEST_CASE("GNN confirms at the first report without clutter and waits for more under heavy clutter") {
  const Scenario clean = resolved("oh_single_supernode", {"tracker.engine=gnn"});
  CHECK(param(clean, "confirm_hits") == 1);
  const Scenario cluttered =
      resolved("oh_quadrants", {"tracker.engine=gnn", "sensor_model.noise_sigma=0.8"});
  CHECK(param(cluttered, "confirm_hits") >= 3);
  CHECK(param(cluttered, "confirm_window") >= param(cluttered, "confirm_hits"));
  // Judged at the newest tick, where reports are still arriving: pd 0.345 on time rising to 0.725 in
  // the window (the in-window pd alone gave 4, taking every late report for a miss).
  CHECK(param(cluttered, "max_misses") == 5);
}

TEST_CASE("GNN does not delete a track whose newest reports are only late") {
  // pte = 0, pde = 0.3: every report arrives (pd 0.9999 in the window), but only 0.477 of them on
  // time. Judged by the in-window pd, one miss deleted the track; a late report is not a miss.
  const Scenario delayed = resolved("oh_quadrants", {"tracker.engine=gnn", "network.pte=0"});
  CHECK(param(delayed, "max_misses") == 4);
  const Scenario on_time = resolved("oh_quadrants", {"tracker.engine=gnn", "network.pte=0", "network.pde=0"});
  CHECK(param(on_time, "max_misses") == 1);
}

TEST_CASE("MCMCDA reports a target at its first observation without clutter and waits under clutter") {
  // No clutter: lambda_f is the probe's rule-of-three floor (6.25e-6 over 1e4), so reporting lone
  // reports costs 0.0625 false track-ticks per tick, against 0.2 births per tick that would each
  // wait 1 / pd = 1 tick for a second report.
  CHECK(param(resolved("oh_single_supernode"), "confirm_observations") == 1);
  CHECK(param(resolved("oh_quadrants", {"sensor_model.noise_sigma=0.8"}), "confirm_observations") >= 3);
}

TEST_CASE("a misspelt parameter written auto is still an unknown parameter") {
  CHECK_THROWS_WITH(resolved("oh_quadrants", {"tracker.params.max_sped=auto"}),
                    Catch::Matchers::Contains("unknown parameter 'max_sped'"));
}

TEST_CASE("a derivation that reads a parameter derived after it is a programming error, named") {
  // Derivations run in table order: 'a' reading 'b', derived later, must fail loudly rather than
  // read a missing value.
  std::vector<common::ParamSpec> specs(2);
  specs[0].name = "a";
  specs[1].name = "b";
  for (auto& spec : specs) {
    spec.max = 10.0;
    spec.derivation = {"test", [](const common::StatisticsSource&, const std::map<std::string, common::EngineParam>& r) {
                         return common::Derived{r.at("b").value, "reads b"};
                       }};
  }
  specs[1].derivation.derive = [](const common::StatisticsSource&, const std::map<std::string, common::EngineParam>&) {
    return common::Derived{1.0, "fixed"};
  };
  const common::ObservationStatistics none;
  const common::StatisticsSource statistics = [&none]() -> const common::ObservationStatistics& { return none; };
  std::map<std::string, common::EngineParam> params;
  CHECK_THROWS_WITH(common::resolveParams("s.yaml", "tracker.params", "engine 'x'", specs, params, statistics),
                    Catch::Matchers::Contains("'tracker.params.a'") &&
                        Catch::Matchers::Contains("derived after it"));
}

TEST_CASE("the rule-based residual-noise and birth cluster sizes follow the weakest target's sensors") {
  // An et al. 2013 at Ds = 25 m: a target of sensing range SR is heard by pi SR^2 / 625 sensors on
  // average: 4.52 at SR 30 (the file), 2.01 at 20, 1.13 at 15. Half of that, at most 2: 2, 1, 0
  // (Noise_find off), and a birth needs at least one sensor.
  const Scenario shipped = resolved("an2013_noise3");
  CHECK(param(shipped, "noise_cluster_sensors") == 2);
  CHECK(param(shipped, "birth_min_sensors") == 2);
  const Scenario sr20 = resolved("an2013_noise3", {"targets.scripted[0].sensing_range=20"});
  CHECK(param(sr20, "noise_cluster_sensors") == 1);
  CHECK(param(sr20, "birth_min_sensors") == 1);
  const Scenario sr15 = resolved("an2013_noise3", {"targets.scripted[0].sensing_range=15"});
  CHECK(param(sr15, "noise_cluster_sensors") == 0);
  CHECK(param(sr15, "birth_min_sensors") == 1);
  CHECK_THAT(scenario::resolvedScenarioYaml(sr15), Contains("at the weakest SR 15"));
}

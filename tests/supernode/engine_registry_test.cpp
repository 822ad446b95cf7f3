#include "supernode/engine.hpp"

#include <bit>
#include <catch2/catch.hpp>

#include "supernode/gnn/gnn_engine.hpp"

namespace wsn::supernode {
namespace {

common::Scenario scenarioFrom(const std::string& engine, int engine_line) {
  common::Scenario s;
  s.source_path = "runs/s.yaml";
  s.tracker.engine = engine;
  s.tracker.engine_line = engine_line;
  return s;
}

TEST_CASE("the registry lists gnn with sane parameter specifications", "[registry]") {
  const auto& registry = engineRegistry();
  REQUIRE_FALSE(registry.empty());
  CHECK(registry.front().name == "gnn");
  for (const auto& engine : registry) {
    CHECK_FALSE(engine.description.empty());
    CHECK(engine.create);
    for (const auto& p : engine.params) {
      INFO(engine.name << "." << p.name);
      CHECK(p.min <= p.default_value);
      CHECK(p.default_value <= p.max);
      CHECK_FALSE(p.description.empty());
    }
  }
}

TEST_CASE("resolving fills in every default with line 0 and keeps given values", "[registry]") {
  auto s = scenarioFrom("gnn", 3);
  s.tracker.params["gate_chi2"] = {5.99, 12};
  resolveEngineParams(s, wsn::common::kNoStatistics);
  const auto& params = s.tracker.params;
  REQUIRE(params.size() == 7);
  CHECK(params.at("gate_chi2").value == 5.99);
  CHECK(params.at("gate_chi2").line == 12);
  CHECK(params.at("measurement_sigma").value == 0.5);
  CHECK(params.at("measurement_sigma").line == 0);
  CHECK(params.at("confirm_hits").value == 3.0);
  CHECK(params.at("confirm_window").value == 5.0);
  CHECK(params.at("max_misses").value == 3.0);
  CHECK(params.at("initial_velocity_sigma").value == 2.0);
  CHECK(params.at("merge_radius").value == 0.0);

  auto again = s;  // resolving a resolved scenario changes nothing
  resolveEngineParams(again, wsn::common::kNoStatistics);
  CHECK(again.tracker.params.size() == s.tracker.params.size());
  for (const auto& [name, p] : s.tracker.params) {
    CHECK(again.tracker.params.at(name).value == p.value);
    CHECK(again.tracker.params.at(name).line == p.line);
  }
}

TEST_CASE("an unknown engine is reported with file, line and the known engines", "[registry]") {
  auto s = scenarioFrom("kalman", 7);
  REQUIRE_THROWS_MATCHES(resolveEngineParams(s, wsn::common::kNoStatistics), common::ScenarioError,
                         Catch::Message("runs/s.yaml:7: unknown tracker engine 'kalman'; expected one of: gnn, mcmcda, rulebased, sbmht"));
}

TEST_CASE("an unknown parameter is reported with its line and the engine's parameters", "[registry]") {
  auto s = scenarioFrom("gnn", 7);
  s.tracker.params["gate"] = {3.0, 9};
  REQUIRE_THROWS_MATCHES(
      resolveEngineParams(s, wsn::common::kNoStatistics), common::ScenarioError,
      Catch::Message("runs/s.yaml:9: unknown parameter 'gate' for engine 'gnn'; expected one of: measurement_sigma, "
                     "initial_velocity_sigma, gate_chi2, max_misses, confirm_hits, confirm_window, merge_radius"));
}

TEST_CASE("a parameter out of range is reported with the admissible range", "[registry]") {
  auto s = scenarioFrom("gnn", 7);
  s.tracker.params["gate_chi2"] = {-1.0, 4};
  REQUIRE_THROWS_MATCHES(resolveEngineParams(s, wsn::common::kNoStatistics), common::ScenarioError,
                         Catch::Message("runs/s.yaml:4: 'tracker.params.gate_chi2' must be in [0.1, 1000], got -1"));

  s.tracker.params["gate_chi2"] = {std::nan(""), 4};
  CHECK_THROWS_AS(resolveEngineParams(s, wsn::common::kNoStatistics), common::ScenarioError);
}

TEST_CASE("a count parameter must be a whole number", "[registry]") {
  auto s = scenarioFrom("gnn", 7);
  s.tracker.params["confirm_hits"] = {2.5, 5};
  REQUIRE_THROWS_MATCHES(resolveEngineParams(s, wsn::common::kNoStatistics), common::ScenarioError,
                         Catch::Message("runs/s.yaml:5: 'tracker.params.confirm_hits' must be a whole number, got 2.5"));
}

TEST_CASE("every measurement kind an engine or sensor model names is a known kind", "[registry]") {
  // acceptedKindMask skips a name that is no kind, so a misspelt one would only show when the
  // first observation of that kind arrived: every name must resolve.
  for (const auto& engine : engineRegistry()) {
    INFO(engine.name);
    CHECK_FALSE(engine.accepts.empty());
    for (const auto& kind : engine.accepts) CHECK(common::measurementKindNamed(kind).has_value());
    CHECK(std::popcount(acceptedKindMask(engine)) == static_cast<int>(engine.accepts.size()));
  }
}

TEST_CASE("makeEngine builds the engine the scenario names", "[registry]") {
  auto s = scenarioFrom("gnn", 1);
  resolveEngineParams(s, wsn::common::kNoStatistics);
  const auto engine = makeEngine(engineContext(s, 0));
  REQUIRE(engine != nullptr);
  CHECK(dynamic_cast<gnn::GnnEngine*>(engine.get()) != nullptr);
  CHECK(engine->confirmedTracks().empty());
}

}  // namespace
}  // namespace wsn::supernode

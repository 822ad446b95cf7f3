// The catalogue of `wsntrack components --json` (launcher/catalogue.cpp): it lists every registered
// component, and every quantity it gives the Python side is where metrics.json really has it.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "aggregator/association.hpp"
#include "aggregator/metric/metric.hpp"
#include "aggregator/run_scorer.hpp"
#include "common/scenario_schema.hpp"
#include "launcher/components.hpp"
#include "node/sensor_model_registry.hpp"
#include "supernode/engine.hpp"

namespace wsn::launcher {
namespace {

using Json = nlohmann::json;

std::vector<std::string> namesIn(const Json& list) {
  std::vector<std::string> names;
  for (const auto& entry : list) names.push_back(entry.at("name").get<std::string>());
  return names;
}

template <typename Registry>
std::vector<std::string> namesOf(const Registry& registry) {
  std::vector<std::string> names;
  for (const auto& entry : registry) names.push_back(entry.name);
  return names;
}

/// The value at `path` (keys) under `document`, or nullptr where the path ends early.
const Json* at(const Json& document, const Json& path) {
  const Json* node = &document;
  for (const auto& key : path) {
    if (!node->is_object() || !node->contains(key.get<std::string>())) return nullptr;
    node = &node->at(key.get<std::string>());
  }
  return node;
}

/// metrics.json of a two-tick run with one target and one track near it, scored as the live and
/// the settled stream.
Json scoredMetricsJson() {
  const common::MetricsConfig config;
  std::vector<aggregator::RunScores> streams;
  for (const char* stream : {aggregator::kLiveStream, aggregator::kSettledStream}) {
    aggregator::RunScorer scorer(stream, config, {{0.0, 0.0}});
    for (std::int32_t tick = 1; tick <= 2; ++tick) {
      common::TargetState target;
      target.x = tick;
      common::TrackEstimate track;
      track.track = 1;
      track.x = tick + 0.1;
      scorer.add(tick, {target}, {track});
    }
    streams.push_back(scorer.finish());
  }
  aggregator::RunInfo info;
  info.ticks = 2;
  return Json::parse(aggregator::metricsJson(info, streams, 1.0, 2.0));
}

TEST_CASE("the catalogue lists every registered component, key and file", "[launcher][catalogue]") {
  const Json catalogue = Json::parse(componentsJson());
  CHECK(catalogue.at("catalogue_version") == 1);
  CHECK(namesIn(catalogue.at("sensor_models")) == namesOf(node::sensorModelRegistry()));
  CHECK(namesIn(catalogue.at("engines")) == namesOf(supernode::engineRegistry()));
  CHECK(namesIn(catalogue.at("associations")) == namesOf(aggregator::associationRegistry()));
  CHECK(namesIn(catalogue.at("metrics")) == namesOf(aggregator::metricRegistry()));
  std::size_t keys = 0;
  for (const auto& table : common::schema::keyTables()) keys += table.fields.size();
  CHECK(catalogue.at("scenario_keys").size() == keys);
  const auto pte = std::find_if(catalogue.at("scenario_keys").begin(), catalogue.at("scenario_keys").end(),
                                [](const Json& k) { return k.at("key") == "network.pte"; });
  REQUIRE(pte != catalogue.at("scenario_keys").end());
  CHECK(pte->at("label") == "transmission failure rate pte");
  CHECK(pte->at("unit") == "per hop");
  CHECK(pte->at("default") == 0.3);
  for (const char* file : {"truth.csv", "observations.csv", "tracks.csv", "tracks_supernode.csv",
                           "tracks_settled.csv", "metrics_per_tick.csv"})
    CHECK_FALSE(catalogue.at("run_files").at(file).empty());
  CHECK(catalogue.at("target_classes").at(0) == "unknown");
  CHECK(catalogue.at("track_id").at("owner_shift") == 48);
}

TEST_CASE("every quantity of the catalogue is where metrics.json has it, in both streams", "[launcher][catalogue]") {
  const Json catalogue = Json::parse(componentsJson());
  const Json metrics = scoredMetricsJson();
  const Json* settled = at(metrics, catalogue.at("streams").at("settled"));
  REQUIRE(settled != nullptr);
  std::size_t checked = 0;
  for (const auto& metric : catalogue.at("metrics"))
    for (const auto& quantity : metric.at("quantities")) {
      INFO(quantity.at("name"));
      for (const Json* block : {&metrics, settled}) {
        const Json* value = at(*block, quantity.at("path"));
        REQUIRE(value != nullptr);
        CHECK((value->is_number() || value->is_null()));
        if (!quantity.at("defined").empty()) {
          const Json* flag = at(*block, quantity.at("defined"));
          REQUIRE(flag != nullptr);
          CHECK(flag->is_boolean());
        }
      }
      CHECK_FALSE(quantity.at("title").get<std::string>().empty());
      CHECK_FALSE(quantity.at("label").get<std::string>().empty());
      ++checked;
    }
  CHECK(checked >= 15);
  // The one-target run is scored: the paths do not just exist, they hold its numbers.
  CHECK(metrics.at("eps_k") == 0.0);
  CHECK(metrics.at("clear_mot").at("mota") == 1.0);
}

TEST_CASE("a quantity path the metrics do not write is caught by the lookup", "[launcher][catalogue]") {
  // The negative control of the case above: a path one key off finds nothing.
  const Json metrics = scoredMetricsJson();
  CHECK(at(metrics, Json::array({"clear_mot", "mota"})) != nullptr);
  CHECK(at(metrics, Json::array({"clear_mot", "motaa"})) == nullptr);
  CHECK(at(metrics, Json::array({"eps_k", "deeper"})) == nullptr);
}

}  // namespace
}  // namespace wsn::launcher

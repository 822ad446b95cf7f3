// `wsntrack components --json`: the one machine-readable catalogue of what this build of wsntrack
// knows, which the Python package reads instead of restating it (python/wsntrack/catalogue.py).
#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "aggregator/association.hpp"
#include "aggregator/metric/metric.hpp"
#include "aggregator/run_files.hpp"
#include "aggregator/run_scorer.hpp"
#include "common/config/field_table.hpp"
#include "common/measurement.hpp"
#include "common/output.hpp"
#include "common/scenario_schema.hpp"
#include "common/track_id.hpp"
#include "common/version.hpp"
#include "launcher/components.hpp"
#include "launcher/run_directory.hpp"
#include "network_model/run_files.hpp"
#include "node/sensor_model_registry.hpp"
#include "supernode/engine.hpp"

namespace wsn::launcher {
namespace {

using Json = nlohmann::ordered_json;

/// The catalogue's layout; raised when a key changes meaning or goes away (readers check it).
constexpr int kCatalogueVersion = 1;

/// A figure's label for a scenario key, from its doc's first clause: the clause and the key
/// ("transmission failure rate pte"), a long clause alone, the key and a symbol ("window_size (ws)"),
/// or the key where the clause reads badly (code, or over 40 characters). The unit goes beside it.
std::string keyLabel(const std::string& key, const std::string& doc) {
  const auto end = doc.find_first_of(".;,(");
  std::string clause = doc.substr(0, end);
  while (!clause.empty() && clause.back() == ' ') clause.pop_back();
  if (clause.empty() || clause.size() > 40 || clause.find('`') != std::string::npos) return key;
  if (clause.find(' ') == std::string::npos) return key + " (" + clause + ")";  // a symbol: "window_size (ws)"
  if (clause.size() > 30 || clause.rfind(key, 0) == 0) return clause;  // names it well enough alone
  return clause + " " + key;
}

/// A key's default as the JSON number it is, or its text where it is none ("auto: ...", a name).
Json defaultValue(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (!text.empty() && end == text.c_str() + text.size()) return value;
  return text;
}

Json keyJson(const std::string& section, const common::config::FieldDoc& f) {
  const std::string path = section.empty() ? f.key : section + "." + f.key;
  return Json{{"key", path},
              {"label", keyLabel(f.key, f.doc)},
              {"unit", f.unit},
              {"default", defaultValue(f.default_text)},
              {"range", f.range_text},
              {"meaning", f.doc}};
}

Json keyTablesJson(const std::vector<common::config::KeyTable>& tables) {
  Json keys = Json::array();
  for (const auto& table : tables)
    for (const auto& f : table.fields) keys.push_back(keyJson(table.section, f));
  return keys;
}

Json paramsJson(const std::vector<common::ParamSpec>& params) {
  Json out = Json::array();
  for (const auto& p : params)
    out.push_back(Json{{"name", p.name},
                       {"unit", p.unit},
                       {"default", p.derived() ? Json(nullptr) : Json(p.default_value)},
                       {"derived_from", p.derived() ? Json(p.derivation.summary) : Json(nullptr)},
                       {"min", p.min},
                       {"max", p.max},
                       {"whole", p.integer},
                       {"meaning", p.description}});
  return out;
}

Json sensorModelsJson() {
  Json out = Json::array();
  for (const auto& model : node::sensorModelRegistry()) {
    Json types = Json::object();
    for (const auto& type : model.settings.sensor_types) {
      Json defaults = Json::object();
      for (const auto& table : model.settings.key_tables())
        if (table.section == "sensor_model." + type)
          for (const auto& f : table.fields) defaults[f.key] = defaultValue(f.default_text);
      types[type] = std::move(defaults);
    }
    out.push_back(Json{{"name", model.name},
                       {"description", model.description},
                       {"measurement_kinds", model.measurement_kinds},
                       {"keys", keyTablesJson(model.settings.key_tables())},
                       {"target_keys", model.settings.target_keys},
                       {"sensor_types", std::move(types)}});
  }
  return out;
}

Json metricsJson() {
  Json out = Json::array();
  const common::MetricsConfig defaults;
  for (const auto& metric : aggregator::metricRegistry()) {
    Json columns = Json::array();
    for (const auto& c : metric.create(defaults, {})->columns())
      columns.push_back(Json{{"name", c.name}, {"whole", c.whole}});
    Json quantities = Json::array();
    for (const auto& q : metric.quantities)
      quantities.push_back(Json{{"name", q.name},
                                {"title", q.title},
                                {"label", q.label},
                                {"unit", q.unit},
                                {"path", q.path},
                                {"defined", q.defined},
                                {"meaning", q.meaning}});
    out.push_back(Json{{"name", metric.name},
                       {"description", metric.description},
                       {"settings", metric.settings},
                       {"per_tick_columns", std::move(columns)},
                       {"quantities", std::move(quantities)}});
  }
  return out;
}

/// network.json's numbers a sweep can tabulate or put on an axis, as the network model lists them.
Json networkQuantitiesJson() {
  Json out = Json::array();
  for (const auto& q : network_model::networkQuantities())
    out.push_back(Json{{"name", q.name}, {"title", q.title}, {"label", q.label}, {"unit", ""},
                       {"path", {q.key}}, {"defined", Json::array()}, {"meaning", q.meaning}});
  return out;
}

Json runFilesJson() {
  // metrics_per_tick.csv's header is the scorer's, as the aggregator writes it.
  const std::string per_tick = aggregator::RunScorer(aggregator::kLiveStream, common::MetricsConfig{}, {}).csvHeader();
  return Json{{"truth.csv", common::splitCsvLine(kTruthCsvHeader)},
              {"sensors.csv", common::splitCsvLine(kSensorsCsvHeader)},
              {"observations.csv", common::splitCsvLine(network_model::kObservationsHeader)},
              {"tracks_supernode.csv", common::splitCsvLine(aggregator::supernodeTracksCsvHeader())},
              {"tracks.csv", common::splitCsvLine(aggregator::globalTracksCsvHeader())},
              {"tracks_settled.csv", common::splitCsvLine(aggregator::globalTracksCsvHeader())},
              {"metrics_per_tick.csv", common::splitCsvLine(per_tick)}};
}

Json trackIdJson() {
  namespace id = common::track_id;
  return Json{{"owner_shift", id::kOwnerShift},
              {"birth_tick_shift", id::kBirthTickShift},
              {"birth_index_shift", id::kBirthIndexShift},
              {"birth_serial_floor", id::kBirthSerialFloor},
              {"layout",
               "(supernode + 1) << owner_shift | serial for a supernode's track, the serial a counter below "
               "birth_serial_floor or a birth id index << birth_index_shift | tick << birth_tick_shift | sensor; "
               "an id below 1 << owner_shift is one the aggregator minted"},
              {"labels", "S:N (counter N of supernode S), S:tTsK or S:tTsK.J (a birth at tick T from sensor K, "
                         "index J when not 0), gN (minted by the aggregator)"}};
}

}  // namespace

std::string componentsJson() {
  Json out;
  out["catalogue_version"] = kCatalogueVersion;
  out["wsntrack"] = version::describe();
  out["scenario_keys"] = keyTablesJson(common::schema::keyTables());
  out["sensor_models"] = sensorModelsJson();
  Json engines = Json::array();
  for (const auto& engine : supernode::engineRegistry())
    engines.push_back(Json{{"name", engine.name},
                           {"description", engine.description},
                           {"accepts", engine.accepts},
                           {"params", paramsJson(engine.params)}});
  out["engines"] = std::move(engines);
  Json associations = Json::array();
  for (const auto& method : aggregator::associationRegistry())
    associations.push_back(
        Json{{"name", method.name}, {"description", method.description}, {"params", paramsJson(method.params)}});
  out["associations"] = std::move(associations);
  out["metrics"] = metricsJson();
  out["streams"] = Json{{"live", Json::array()}, {"settled", {"streams", "settled"}}};
  out["network_quantities"] = networkQuantitiesJson();
  out["run_files"] = runFilesJson();
  Json kinds = Json::array();
  for (int k = 0; k <= static_cast<int>(common::MeasurementKind::presence); ++k)
    kinds.push_back(std::string(common::measurementKindName(static_cast<common::MeasurementKind>(k))));
  out["measurement_kinds"] = std::move(kinds);
  out["target_classes"] = common::targetClassNames();
  out["observation_fates"] = network_model::kObservationFates;
  out["track_id"] = trackIdJson();
  return out.dump(2) + "\n";
}

}  // namespace wsn::launcher

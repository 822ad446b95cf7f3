#include "launcher/components.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "aggregator/association.hpp"
#include "aggregator/metric/metric.hpp"
#include "common/config/field_table.hpp"
#include "common/scenario_schema.hpp"
#include "node/sensor_model_registry.hpp"
#include "supernode/engine.hpp"

namespace wsn::launcher {
namespace {

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

/// The default column: a number, or `auto` with what the value is derived from.
std::string defaultText(const common::ParamSpec& p) {
  return p.derived() ? "auto: " + p.derivation.summary : common::config::compactNumber(p.default_value);
}

void printParams(std::ostringstream& out, const std::vector<common::ParamSpec>& params) {
  using common::config::compactNumber;
  for (const auto& p : params)
    out << "  " << p.name << (p.unit.empty() ? "" : " [" + p.unit + "]") << " (default " << defaultText(p)
        << ", range [" << compactNumber(p.min) << ", " << compactNumber(p.max) << "]" << (p.integer ? ", whole" : "")
        << "): " << p.description << "\n";
}

void printEngines(std::ostringstream& out) {
  out << "Supernode tracking engines (tracker.engine, tracker.params):\n";
  for (const auto& engine : supernode::engineRegistry()) {
    out << engine.name << ": " << engine.description << "\n  accepts: " << joined(engine.accepts) << "\n";
    printParams(out, engine.params);
  }
  out << "\nAggregator track association (aggregator.association, aggregator.params):\n";
  for (const auto& method : aggregator::associationRegistry()) {
    out << method.name << ": " << method.description << "\n";
    printParams(out, method.params);
  }
}

std::string markdownParamTable(const std::vector<common::ParamSpec>& params) {
  using common::config::compactNumber;
  std::string out = "| parameter | unit | default | range | meaning |\n|-----------|------|---------|-------|---------|\n";
  for (const auto& p : params)
    out += "| `" + p.name + "` | " + (p.unit.empty() ? "—" : p.unit) + " | " + defaultText(p) + " | [" +
           compactNumber(p.min) + ", " + compactNumber(p.max) + "]" + (p.integer ? ", whole" : "") + " | " +
           p.description + " |\n";
  return out;
}

/// `path [unit] (default d, range r): doc`, the shape printParams gives an engine parameter.
void printKey(std::ostringstream& out, const std::string& path, const common::config::FieldDoc& f) {
  out << "  " << path << (f.unit.empty() ? "" : " [" + f.unit + "]") << " (default " << f.default_text << ", range "
      << f.range_text << "): " << f.doc << "\n";
}

/// Prints the rows of `table` whose key is in `keys` (all of them when `keys` is empty).
void printKeys(std::ostringstream& out, const common::config::KeyTable& table, const std::vector<std::string>& keys = {}) {
  for (const auto& f : table.fields)
    if (keys.empty() || std::find(keys.begin(), keys.end(), f.key) != keys.end())
      printKey(out, table.section + "." + f.key, f);
}

/// The scenario keys a sensor model reads: sensing_range, its own and those of scripted targets.
void printSensorModelKeys(std::ostringstream& out, const node::SensorModelSpec& model) {
  using common::config::keyTable;
  printKeys(out, keyTable("", "sensor_model", common::schema::sensorModel()), {"sensing_range"});
  for (const auto& table : model.settings.key_tables()) printKeys(out, table);
  if (!model.settings.target_keys.empty())
    printKeys(out, keyTable("", "targets.scripted[]", common::schema::scriptedTarget()), model.settings.target_keys);
}

void markdownBlock(std::ostringstream& out, const std::string& name, const std::string& table) {
  out << "<!-- table: " << name << " -->\n" << table << "<!-- end table -->\n\n";
}

}  // namespace

std::string componentsMarkdown() {
  std::ostringstream out;
  for (const auto& [name, table] : common::schema::markdownTables()) markdownBlock(out, name, table);
  for (const auto& model : node::sensorModelRegistry())
    for (const auto& table : model.settings.key_tables())
      markdownBlock(out, table.marker, common::config::markdownTable(table.fields));
  for (const auto& engine : supernode::engineRegistry())
    markdownBlock(out, "tracker.params " + engine.name, markdownParamTable(engine.params));
  for (const auto& method : aggregator::associationRegistry())
    markdownBlock(out, "aggregator.params " + method.name, markdownParamTable(method.params));
  return out.str();
}

std::vector<std::string> componentKinds() { return {"sensor-models", "engines", "associations", "metrics"}; }

std::string componentNames(const std::string& kind) {
  std::ostringstream out;
  const auto list = [&out](const auto& registry) {
    for (const auto& entry : registry) out << entry.name << "\n";
  };
  if (kind == "sensor-models")
    list(node::sensorModelRegistry());
  else if (kind == "engines")
    list(supernode::engineRegistry());
  else if (kind == "associations")
    list(aggregator::associationRegistry());
  else if (kind == "metrics")
    list(aggregator::metricRegistry());
  else
    throw std::invalid_argument("--names takes one of " + joined(componentKinds()) + ", got '" + kind + "'");
  return out.str();
}

std::string enginesText() {
  std::ostringstream out;
  printEngines(out);
  return out.str();
}

std::string componentsText() {
  std::ostringstream out;
  out << "Sensor models (sensor_model.kind):\n";
  for (const auto& model : node::sensorModelRegistry()) {
    out << model.name << ": " << model.description << "\n  measures: " << joined(model.measurement_kinds) << "\n";
    printSensorModelKeys(out, model);
  }
  out << "\n";
  printEngines(out);
  out << "\nMetrics (metrics.json keys, metrics_per_tick.csv columns; settings in the scenario's metrics section):\n";
  const common::MetricsConfig defaults;
  for (const auto& metric : aggregator::metricRegistry()) {
    out << metric.name << ": " << metric.description << "\n";
    if (!metric.settings.empty())
      printKeys(out, common::config::keyTable("", "metrics", common::schema::metrics()), metric.settings);
    const auto columns = metric.create(defaults, {})->columns();
    if (!columns.empty()) {
      std::vector<std::string> names;
      for (const auto& c : columns) names.push_back(c.name);
      out << "  per-tick columns: " << joined(names) << "\n";
    }
  }
  return out.str();
}

std::optional<std::string> unacceptedKind(const std::vector<std::string>& reported,
                                          const std::vector<std::string>& accepted) {
  for (const auto& kind : reported)
    if (std::find(accepted.begin(), accepted.end(), kind) == accepted.end()) return kind;
  return std::nullopt;
}

void checkComponentsFit(const common::Scenario& scenario) {
  const auto& model = node::sensorModelRegistry().at(scenario.sensor_model.kind);
  const auto& engine = supernode::engineRegistry().at<common::ScenarioError>(
      scenario.tracker.engine, scenario.source_path + ":" + std::to_string(scenario.tracker.engine_line) + ": ");
  const std::vector<std::string> reported =
      model.scenario_measurement_kinds ? model.scenario_measurement_kinds(scenario) : model.measurement_kinds;
  if (const auto kind = unacceptedKind(reported, engine.accepts))
    throw common::ScenarioError(scenario.source_path + ":" + std::to_string(std::max(scenario.tracker.engine_line, 1)) +
                                ": engine '" + engine.name + "' takes " + joined(engine.accepts) +
                                " measurements, but sensor model '" + model.name + "' reports " + *kind);
}

}  // namespace wsn::launcher

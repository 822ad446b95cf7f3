#include "node/field_sensors/config.hpp"

#include <algorithm>
#include <memory>

#include "common/config/yaml_reader.hpp"
#include "common/config/yaml_writer.hpp"

namespace wsn::node::field_sensors {
namespace {

using common::Scenario;
using common::config::Field;
using common::config::FieldTable;
using common::config::Reader;
using common::config::Section;

/// Every key a type may read, in the order its table lists them.
const std::vector<Field<TypeSettings>>& allTypeFields() {
  using C = TypeSettings;
  using namespace common::config;
  static const std::vector<Field<C>> fields{
      real<C>("detection_probability", &C::detection_probability, kProbability, "",
              "PD: chance that a covered target is detected in a tick"),
      real<C>("false_alarms_per_tick", &C::false_alarms_per_tick, closed(0.0, 1e3), "1/tick",
              "mean of the Poisson number of false alarms per sensor and tick, uniform over its measurement space"),
      real<C>("range", &C::range, kPositive, "distance", "coverage radius of a sensor whose entry gives none"),
      real<C>("fov_deg", &C::fov_deg, openClosed(0.0, 360.0), "degrees",
              "field of view, centred on the heading, of a sensor whose entry gives none"),
      real<C>("height", &C::height, openClosed(0.0, 1e3), "distance", "mast height of a sensor whose entry gives none"),
      real<C>("sigma_bearing_deg", &C::sigma_bearing_deg, openClosed(0.0, 180.0), "degrees", "σθ"),
      real<C>("sigma_elevation_deg", &C::sigma_elevation_deg, openClosed(0.0, 90.0), "degrees", "σφ"),
      real<C>("sigma_range", &C::sigma_range, kPositive, "distance", "σρ"),
      real<C>("sigma_range_rate", &C::sigma_range_rate, kPositive, "distance/tick", "σρ̇"),
      real<C>("max_range_rate", &C::max_range_rate, kPositive, "distance/tick",
              "a false alarm's ρ̇ is uniform in ±this"),
      real<C>("sigma_position", &C::sigma_position, kPositive, "distance",
              "σ per axis of the target around the sensor: R = σ² I"),
  };
  return fields;
}

FieldTable<TypeSettings> buildTypeTable(const SensorType& type) {
  std::vector<std::string> keys = {"detection_probability", "false_alarms_per_tick", "range", "fov_deg"};
  for (const auto& key : type.ownKeys()) keys.push_back(key);
  FieldTable<TypeSettings> table{"sensor_model." + std::string(type.name()), {}};
  const TypeSettings defaults = type.defaults();
  for (const auto& field : allTypeFields()) {
    if (std::find(keys.begin(), keys.end(), field.key) == keys.end()) continue;
    Field<TypeSettings> f = field;
    // The docs' default column is the type's, not TypeSettings{}'s.
    f.default_note = common::config::compactNumber(f.get_number(defaults));
    table.fields.push_back(std::move(f));
  }
  return table;
}

}  // namespace

std::map<std::string, TypeSettings> defaultTypeSettings() {
  std::map<std::string, TypeSettings> types;
  for (const auto& type : sensorTypes()) types.emplace(std::string(type->name()), type->defaults());
  return types;
}

const FieldTable<TypeSettings>& typeTable(const SensorType& type) {
  static const std::map<std::string, FieldTable<TypeSettings>, std::less<>> tables = [] {
    std::map<std::string, FieldTable<TypeSettings>, std::less<>> all;
    for (const auto& t : sensorTypes()) all.emplace(std::string(t->name()), buildTypeTable(*t));
    return all;
  }();
  return tables.find(type.name())->second;
}

const FieldTable<FieldSensorsSettings>& settingsTable() {
  using C = FieldSensorsSettings;
  using namespace common::config;
  static const FieldTable<C> table = [] {
    FieldTable<C> t{"sensor_model",
                    {real<C>("min_speed", &C::min_speed, kNonNegative, "distance/tick",
                             "v_min: no sensor detects a slower target (the spec's eq. 9 assumption)")}};
    for (const auto& type : sensorTypes())
      t.fields.push_back(nested<C>(std::string(type->name()), "mapping", "see below", "see below",
                                   std::string(type->description())));
    return t;
  }();
  return table;
}

SensorModelSettingsSpec settingsSpec() {
  SensorModelSettingsSpec spec;
  spec.keys = settingsTable().sortedKeys();
  for (const auto& type : sensorTypes()) spec.sensor_types.emplace_back(type->name());
  spec.read = [](const Reader& r, const Section* given, Scenario&) {
    auto settings = std::make_shared<FieldSensorsSettings>();
    if (given != nullptr) {
      r.fields(*given, settingsTable(), *settings);
      for (const auto& type : sensorTypes()) {
        const common::config::Entry* e = given->find(type->name());
        if (e == nullptr) continue;
        const FieldTable<TypeSettings>& table = typeTable(*type);
        r.fields(r.section(*e, table), table, settings->types.at(std::string(type->name())));
      }
    }
    return std::shared_ptr<const common::SensorModelSettings>(std::move(settings));
  };
  spec.write = [](std::ostream& out, const Scenario& s) {
    const auto& settings = common::settingsOf<FieldSensorsSettings>(s.sensor_model);
    common::config::writeFields(out, "  ", settingsTable(), settings, s.derived);
    for (const auto& type : sensorTypes()) {
      out << "  " << type->name() << ":\n";
      common::config::writeFields(out, "    ", typeTable(*type), settings.types.at(std::string(type->name())));
    }
  };
  spec.key_tables = [] {
    std::vector<common::config::KeyTable> tables{
        common::config::keyTable("sensor_model field_sensors", "sensor_model", settingsTable())};
    for (const auto& type : sensorTypes())
      tables.push_back(common::config::keyTable(typeTable(*type).section, typeTable(*type).section, typeTable(*type)));
    return tables;
  };
  return spec;
}

}  // namespace wsn::node::field_sensors

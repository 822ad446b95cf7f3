// Writing configuration back as YAML from its field tables: the resolved scenario.yaml writes
// every key of every section this way, in table order, so it always reads back to the same values.
#pragma once

#include <algorithm>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "common/config/field_table.hpp"

namespace wsn::common::config {

/// A mapping key: plain when it is a simple name, quoted otherwise (and when YAML would read the
/// plain word as null).
std::string keyText(const std::string& name);

/// `indent key: value` for every value key of `table` (nested keys are written by the caller) but
/// those in `omitted`, which do not apply to this config. A derived value's key gets
/// "# derived: how" after its value.
template <typename C>
void writeFields(std::ostream& out, const std::string& indent, const FieldTable<C>& table, const C& config,
                 const std::map<std::string, std::string>& derived = {}, const std::vector<std::string>& omitted = {}) {
  for (const auto& field : table.fields) {
    if (field.kind == FieldKind::kNested) continue;
    if (std::find(omitted.begin(), omitted.end(), field.key) != omitted.end()) continue;
    out << indent << field.key << ": " << field.yamlValue(config);
    if (const auto it = derived.find(table.section + "." + field.key); it != derived.end())
      out << "  # derived: " << it->second;
    out << "\n";
  }
}

template <typename C>
void writeSection(std::ostream& out, const std::string& name, const FieldTable<C>& table, const C& config,
                  const std::map<std::string, std::string>& derived = {}, const std::vector<std::string>& omitted = {}) {
  out << name << ":\n";
  writeFields(out, "  ", table, config, derived, omitted);
}

/// "{a: 1, b: 2}": a list item on one line; a key whose value means "not given" is left out.
template <typename C>
std::string flowMapping(const FieldTable<C>& table, const C& config) {
  std::string text;
  for (const auto& field : table.fields) {
    if (field.leftOutOfItem(config)) continue;
    text += (text.empty() ? "{" : ", ") + field.key + ": " + field.yamlValue(config);
  }
  return text + "}";
}

template <typename C>
void writeList(std::ostream& out, const std::string& indent, const std::string& key, const FieldTable<C>& table,
               const std::vector<C>& items, const std::string& derivation = "") {
  if (items.empty()) {
    out << indent << key << ": []\n";
    return;
  }
  out << indent << key << ":" << (derivation.empty() ? "" : "  # derived: " + derivation) << "\n";
  for (const auto& item : items) out << indent << "  - " << flowMapping(table, item) << "\n";
}

}  // namespace wsn::common::config

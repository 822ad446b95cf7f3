// Reading configuration from YAML with "file:line: message" errors: a mapping as a Section of
// Entries checked against the keys a field table allows, each value checked against its key's
// kind and range. The scenario loader and every component that owns a section (sensor models)
// read through it, so every section reports problems the same way.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/config/field_table.hpp"
#include "common/scenario_config.hpp"
#include "common/scenario_error.hpp"

namespace wsn::common::config {

/// A closed integer interval.
struct IntRange {
  std::int64_t lo;
  std::int64_t hi;
  std::string text() const { return "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]"; }
};

/// One key: value pair of a mapping.
struct Entry {
  YAML::Node key;
  YAML::Node value;
};

/// The entries of one mapping in the file, by key, with the mapping's dotted path and line.
struct Section {
  std::string path;  ///< "" for the top level
  int line = 1;
  std::vector<std::pair<std::string, Entry>> entries;  // file order

  const Entry* find(std::string_view key) const {
    for (const auto& [name, entry] : entries)
      if (name == key) return &entry;
    return nullptr;
  }
  std::string pathOf(std::string_view key) const {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
  }
};

/// "a, b, c".
std::string join(const std::vector<std::string>& names);

/// How a node looks, for "got ..." in messages.
std::string describe(const YAML::Node& node);

/// Reads values out of one file's YAML; every failure throws ScenarioError "file:line: message".
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(int line, const std::string& message) const;

  static int lineOf(const YAML::Node& node);
  /// The line of a value; an empty value's mark points past it, so use its key's line.
  static int lineOf(const Entry& entry);

  /// Reads a mapping (an empty value counts as an empty mapping). `names` lists the keys it
  /// may hold; an empty list allows any name (tracker.params).
  Section section(const YAML::Node& node, int line, const std::string& path, std::vector<std::string> names) const;
  Section section(const Entry& entry, const std::string& path, std::vector<std::string> names) const {
    return section(entry.value, lineOf(entry), path, std::move(names));
  }

  /// A finite real number in `range`.
  double numberValue(const Entry& entry, const std::string& path, const Range& range) const;
  /// Any finite real number.
  double anyNumber(const Entry& entry, const std::string& path) const;
  /// A whole number in `range`.
  std::int64_t integerValue(const Entry& entry, const std::string& path, const IntRange& range) const;
  /// A whole number in [0, 2^64 - 1] (seeds), converted exactly.
  std::uint64_t unsigned64Value(const Entry& entry, const std::string& path) const;
  /// A string (any scalar).
  std::string textValue(const Entry& entry, const std::string& path) const;
  /// One of `choices`; returns its index.
  int choiceIndex(const Entry& entry, const std::string& path, const std::vector<std::string>& choices) const;

  /// A mapping whose keys are those of `table`.
  template <typename C>
  Section section(const YAML::Node& node, int line, const FieldTable<C>& table) const {
    return section(node, line, table.section, table.sortedKeys());
  }
  template <typename C>
  Section section(const Entry& entry, const FieldTable<C>& table) const {
    return section(entry.value, lineOf(entry), table.section, table.sortedKeys());
  }
  /// An item of a list, whose keys are those of `table`, at `path` ("supernodes[1]").
  template <typename C>
  Section item(const YAML::Node& node, int line, const std::string& path, const FieldTable<C>& table) const {
    return section(node, line, path, table.sortedKeys());
  }

  /// Reads every value key of `table` that `s` holds into `out`, in table order, each checked
  /// against its kind and range. Nested keys (sub-sections, lists) are left to the caller.
  template <typename C>
  void fields(const Section& s, const FieldTable<C>& table, C& out) const {
    for (const auto& field : table.fields) {
      const Entry* entry = s.find(field.key);
      if (entry == nullptr) continue;
      const std::string path = s.pathOf(field.key);
      switch (field.kind) {
        case FieldKind::kReal:
          field.set_number(out, numberValue(*entry, path, field.range));
          break;
        case FieldKind::kInteger:
          field.set_number(out, static_cast<double>(integerValue(*entry, path,
                                                                 IntRange{static_cast<std::int64_t>(field.range.lo),
                                                                          static_cast<std::int64_t>(field.range.hi)})));
          break;
        case FieldKind::kUnsigned64:
          field.set_unsigned(out, unsigned64Value(*entry, path));
          break;
        case FieldKind::kText:
          field.set_text(out, textValue(*entry, path));
          break;
        case FieldKind::kChoice:
          field.set_text(out, field.choices[static_cast<std::size_t>(choiceIndex(*entry, path, field.choices))]);
          break;
        case FieldKind::kNested:
          break;
      }
    }
  }

  /// Fails naming the missing keys of an item that needs them.
  void require(const Section& s, std::initializer_list<const char*> keys, const std::string& what) const;

 private:
  long double whole(const Entry& entry, const std::string& path) const;

  std::string file_;
};

/// Every number of `table` that `given` (the section as written; null when the file has none)
/// leaves out and that has a derived default: computed from the scenario read so far, checked
/// against the key's range, and noted in s.derived.
template <typename C>
void deriveLeftOut(const Reader& r, const Section* given, const FieldTable<C>& table, C& config, Scenario& s) {
  for (const auto& field : table.fields) {
    if (!field.derive || (given != nullptr && given->find(field.key) != nullptr)) continue;
    const std::string path = table.section + "." + field.key;
    const double value = field.derive(config, s);
    if (!field.range.contains(value))
      r.fail(given != nullptr ? given->line : 1, "'" + path + "' left out is " + field.derivation + " = " +
                                                     compactNumber(value) + ", outside " + field.range.text() +
                                                     "; give " + field.key + " explicitly");
    field.set_number(config, value);
    s.derived[path] = field.derivation;
  }
}

/// The items of a list key: each a mapping read by `read(item, line, path)`.
template <typename F>
void forEachItem(const Reader& r, const Entry& list, const std::string& path, const std::string& shape, F&& read) {
  const int list_line = Reader::lineOf(list);
  std::size_t i = 0;
  for (const auto& item : list.value) {
    const std::string item_path = path + "[" + std::to_string(i++) + "]";
    const int item_line = Reader::lineOf(item) > 0 ? Reader::lineOf(item) : list_line;
    if (!item.IsMap()) r.fail(item_line, "'" + item_path + "' must be a mapping " + shape + ", got " + describe(item));
    read(item, item_line, item_path);
  }
}

/// The line of key `key` in `s` when given, else `fallback`.
inline int lineOr(const Section& s, std::string_view key, int fallback) {
  const Entry* e = s.find(key);
  return e == nullptr ? fallback : Reader::lineOf(*e);
}

}  // namespace wsn::common::config

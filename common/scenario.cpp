// The strict YAML scenario loader (DESIGN principle 6): every key is known, every value has the
// expected type and lies in its range, and every problem is reported as "file:line: message"
// naming the dotted key and what was expected. Also applies command-line overrides (--set) to a
// file's YAML before validating it, and writes a scenario back fully resolved.
#include "common/scenario.hpp"

#include "common/scenario_schema.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>

namespace wsn::common {
namespace {

using config::compactNumber;
using config::FieldKind;
using config::FieldTable;
using config::Range;
using config::yamlNumber;
using schema::kMaxBirthsPerTick;
using schema::kMaxCoordinate;
using schema::kMaxNameLength;
using schema::kMaxSensors;
using schema::kMaxSupernodes;

// ---------------------------------------------------------------------------------------------
// Parsing scalars. std::from_chars is exact and locale-independent, unlike streams.

std::string_view withoutPlus(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  return text;
}

std::optional<double> parseDouble(std::string_view text) {
  text = withoutPlus(text);
  double value = 0.0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec != std::errc{} || result.ptr != text.data() + text.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

/// A whole number written as an integer ("42", "-3", "0x2a") or as a whole float ("1e3", "100.0").
/// Returns nullopt for anything else; `is_number` tells a fraction (2.5) from a non-number.
std::optional<long double> parseWhole(std::string_view text, bool& is_number) {
  text = withoutPlus(text);
  is_number = false;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    std::uint64_t value = 0;
    const auto result = std::from_chars(text.data() + 2, text.data() + text.size(), value, 16);
    if (result.ec == std::errc{} && result.ptr == text.data() + text.size()) {
      is_number = true;
      return static_cast<long double>(value);
    }
    return std::nullopt;
  }
  std::int64_t signed_value = 0;
  auto result = std::from_chars(text.data(), text.data() + text.size(), signed_value);
  if (result.ec == std::errc{} && result.ptr == text.data() + text.size()) {
    is_number = true;
    return static_cast<long double>(signed_value);
  }
  std::uint64_t unsigned_value = 0;
  result = std::from_chars(text.data(), text.data() + text.size(), unsigned_value);
  if (result.ec == std::errc{} && result.ptr == text.data() + text.size()) {
    is_number = true;
    return static_cast<long double>(unsigned_value);
  }
  const auto value = parseDouble(text);
  if (!value) return std::nullopt;
  is_number = true;
  if (*value != std::floor(*value)) return std::nullopt;
  return static_cast<long double>(*value);
}

/// A closed integer interval.
struct IntRange {
  std::int64_t lo;
  std::int64_t hi;
  std::string text() const { return "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]"; }
};

// ---------------------------------------------------------------------------------------------
// The reader: YAML nodes to values, with file:line messages.

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

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

/// A plain scalar, or one explicitly tagged as a number (!!int, !!float); quoted or otherwise
/// tagged scalars are strings.
bool isPlainOrNumericTag(const YAML::Node& node) {
  const std::string& tag = node.Tag();
  return tag == "?" || tag == "tag:yaml.org,2002:int" || tag == "tag:yaml.org,2002:float";
}

/// How a node looks, for "got ..." in messages.
std::string describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsMap()) return "a mapping";
  if (node.IsSequence()) return "a list";
  if (node.Tag() == "!") return "the quoted string '" + node.Scalar() + "'";
  if (!isPlainOrNumericTag(node)) return "'" + node.Scalar() + "' tagged " + node.Tag();
  return "'" + node.Scalar() + "'";
}

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(int line, const std::string& message) const {
    throw ScenarioError(file_ + ":" + std::to_string(std::max(line, 1)) + ": " + message);
  }

  static int lineOf(const YAML::Node& node) {
    const YAML::Mark mark = node.Mark();
    return mark.is_null() ? 0 : mark.line + 1;
  }
  /// The line of a value; an empty value's mark points past it, so use its key's line.
  static int lineOf(const Entry& entry) {
    if (entry.value.IsNull() || lineOf(entry.value) == 0) return lineOf(entry.key);
    return lineOf(entry.value);
  }

  /// Reads a mapping (an empty value counts as an empty mapping). `allowed` lists the keys it
  /// may hold; an empty list allows any name (tracker.params).
  Section section(const YAML::Node& node, int line, const std::string& path, std::vector<std::string> names) const {
    Section s;
    s.path = path;
    s.line = std::max(line, 1);
    std::sort(names.begin(), names.end());
    if (!node.IsDefined() || node.IsNull()) return s;
    if (!node.IsMap()) {
      if (path.empty())
        fail(s.line, "a scenario must be a mapping of sections (" + join(names) + "), got " + describe(node));
      fail(s.line, "'" + path + "' must be a mapping" + (names.empty() ? "" : " of " + join(names)) + ", got " +
                       describe(node));
    }
    for (auto it = node.begin(); it != node.end(); ++it) {
      const YAML::Node key = it->first;
      const int key_line = lineOf(key) > 0 ? lineOf(key) : s.line;
      if (!key.IsScalar())
        fail(key_line, "keys " + where(path) + " must be plain names, got " + describe(key));
      const std::string& name = key.Scalar();
      if (!names.empty() && !std::binary_search(names.begin(), names.end(), name))
        fail(key_line, "unknown key '" + name + "' " + where(path) + "; expected one of: " + join(names));
      if (const Entry* first = s.find(name))
        fail(key_line, "duplicate key '" + name + "' " + where(path) + " (first given on line " +
                           std::to_string(lineOf(first->key)) + ")");
      s.entries.push_back({name, Entry{key, it->second}});
    }
    return s;
  }

  Section section(const Entry& entry, const std::string& path, std::vector<std::string> allowed) const {
    return section(entry.value, lineOf(entry), path, std::move(allowed));
  }

  double numberValue(const Entry& entry, const std::string& path, const Range& range) const {
    const double value = anyNumber(entry, path);
    if (!range.contains(value))
      fail(lineOf(entry), "'" + path + "' must be in " + range.text() + ", got " + entry.value.Scalar());
    return value;
  }

  /// Any finite real number.
  double anyNumber(const Entry& entry, const std::string& path) const {
    const YAML::Node& node = entry.value;
    std::optional<double> value;
    if (node.IsScalar() && isPlainOrNumericTag(node)) value = parseDouble(node.Scalar());
    if (!value) fail(lineOf(entry), "'" + path + "' must be a number, got " + describe(node));
    return *value;
  }

  /// A whole number in `range`.
  std::int64_t integerValue(const Entry& entry, const std::string& path, const IntRange& range) const {
    const long double value = whole(entry, path);
    if (value < static_cast<long double>(range.lo) || value > static_cast<long double>(range.hi))
      fail(lineOf(entry), "'" + path + "' must be in " + range.text() + ", got " + entry.value.Scalar());
    return static_cast<std::int64_t>(value);
  }

  /// A whole number in [0, 2^64 - 1] (seeds), converted exactly.
  std::uint64_t unsigned64Value(const Entry& entry, const std::string& path) const {
    const YAML::Node& node = entry.value;
    if (node.IsScalar() && isPlainOrNumericTag(node)) {  // integer text, decimal or hex: exact
      const std::string_view text = withoutPlus(node.Scalar());
      const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
      const char* last = text.data() + text.size();
      std::uint64_t value = 0;
      const auto result = std::from_chars(text.data() + (hex ? 2 : 0), last, value, hex ? 16 : 10);
      if (result.ec == std::errc{} && result.ptr == last) return value;
    }
    // Anything else: a whole float (1e3), or an error for a non-number, a fraction or a value
    // out of range (negative, or 2^64 and beyond).
    const long double value = whole(entry, path);
    if (value < 0.0L || value >= 18446744073709551616.0L)
      fail(lineOf(entry), "'" + path + "' must be in [0, 18446744073709551615], got " + node.Scalar());
    return static_cast<std::uint64_t>(value);
  }

  /// A string (any scalar).
  std::string textValue(const Entry& entry, const std::string& path) const {
    if (!entry.value.IsScalar()) fail(lineOf(entry), "'" + path + "' must be a string, got " + describe(entry.value));
    return entry.value.Scalar();
  }

  /// One of `choices`; returns its index.
  int choiceIndex(const Entry& entry, const std::string& path, const std::vector<std::string>& choices) const {
    const YAML::Node& node = entry.value;
    if (node.IsScalar()) {
      const auto it = std::find(choices.begin(), choices.end(), node.Scalar());
      if (it != choices.end()) return static_cast<int>(it - choices.begin());
    }
    fail(lineOf(entry), "'" + path + "' must be one of: " + join(choices) + "; got " + describe(node));
  }

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
        case FieldKind::kReal: field.set_number(out, numberValue(*entry, path, field.range)); break;
        case FieldKind::kInteger:
          field.set_number(out, static_cast<double>(integerValue(
                                    *entry, path,
                                    IntRange{static_cast<std::int64_t>(field.range.lo),
                                             static_cast<std::int64_t>(field.range.hi)})));
          break;
        case FieldKind::kUnsigned64: field.set_unsigned(out, unsigned64Value(*entry, path)); break;
        case FieldKind::kText: field.set_text(out, textValue(*entry, path)); break;
        case FieldKind::kChoice:
          field.set_text(out, field.choices[static_cast<std::size_t>(choiceIndex(*entry, path, field.choices))]);
          break;
        case FieldKind::kNested: break;
      }
    }
  }

  /// Fails naming the missing keys of an item that needs them.
  void require(const Section& s, std::initializer_list<const char*> keys, const std::string& what) const {
    for (const char* key : keys)
      if (s.find(key) == nullptr) fail(s.line, "'" + s.path + "' needs '" + key + "' (" + what + ")");
  }

 private:
  static std::string where(const std::string& path) { return path.empty() ? "at the top level" : "in '" + path + "'"; }

  long double whole(const Entry& entry, const std::string& path) const {
    const YAML::Node& node = entry.value;
    bool is_number = false;
    std::optional<long double> value;
    if (node.IsScalar() && isPlainOrNumericTag(node)) value = parseWhole(node.Scalar(), is_number);
    if (!value)
      fail(lineOf(entry), "'" + path + "' must be an integer, got " +
                              (is_number ? "the fraction " + node.Scalar() : describe(node)));
    return *value;
  }

  std::string file_;
};

std::string regionText(const Rect& r) {
  return "[" + compactNumber(r.x_min) + ", " + compactNumber(r.x_max) + "] x [" + compactNumber(r.y_min) + ", " +
         compactNumber(r.y_max) + "]";
}

std::string pointText(Vec2 p) { return "(" + compactNumber(p.x) + ", " + compactNumber(p.y) + ")"; }

/// Number of sensors a grid layout puts in the region, as common/sensor_layout.cpp computes it.
double gridSensorCount(const Rect& region, double spacing) {
  return std::floor(region.width() / spacing + 1e-9) * std::floor(region.height() / spacing + 1e-9);
}

/// Number of cells of side 2 Rs over the region, as common/sensor_layout.cpp computes it: node
/// tiles are unions of these cells, so there can be no more node processes than cells.
double layoutCellCount(const Rect& region, double sensing_range) {
  const double cell = std::max(2.0 * sensing_range, 1e-6);
  const double columns = std::max(1.0, std::ceil(region.width() / cell - 1e-9));
  const double rows = std::max(1.0, std::ceil(region.height() / cell - 1e-9));
  return columns * rows;
}

bool validName(const std::string& name) {
  if (name.empty() || name.size() > kMaxNameLength) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
           c == '.';
  });
}

// ---------------------------------------------------------------------------------------------
// Cross-field rules: each says what must hold between values of different keys, and the line to
// blame when it does not. They run after the keys they involve are read.

/// region: x_min < x_max and y_min < y_max.
void regionIsOrdered(const Reader& r, const Rect& region, int line) {
  if (!(region.x_min < region.x_max))
    r.fail(line, "'region' must have x_min < x_max, got x_min = " + compactNumber(region.x_min) +
                     ", x_max = " + compactNumber(region.x_max));
  if (!(region.y_min < region.y_max))
    r.fail(line, "'region' must have y_min < y_max, got y_min = " + compactNumber(region.y_min) +
                     ", y_max = " + compactNumber(region.y_max));
}

/// sensors: a grid holds 1 to kMaxSensors sensors.
void gridFitsRegion(const Reader& r, const Scenario& s, int line) {
  if (s.sensors.kind != SensorLayoutConfig::Kind::kGrid) return;
  const double n = gridSensorCount(s.region, s.sensors.spacing);
  if (n < 1.0 || n > kMaxSensors)
    r.fail(line, "'sensors.spacing' " + compactNumber(s.sensors.spacing) + " puts " + compactNumber(n) +
                     " sensors on the grid over the region " + regionText(s.region) + "; expected 1 to " +
                     compactNumber(kMaxSensors));
}

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

/// sensor_model.acoustic: a tick is a whole number (at most 100000) of detection steps.
void tickIsWholeDetectionSteps(const Reader& r, const AcousticConfig& ac, int line) {
  const double steps = ac.tick_s / ac.detection_step_s;
  if (std::abs(steps - std::round(steps)) > 1e-6 * steps || std::round(steps) > 100000.0)
    r.fail(line, "'sensor_model.acoustic.tick_s' " + compactNumber(ac.tick_s) +
                     " must be a whole number (at most 100000) of detection steps of " +
                     compactNumber(ac.detection_step_s) + " s");
}

/// A key that only the acoustic model reads, given with another model.
void onlyAcoustic(const Reader& r, const Scenario& s, const std::string& path, int line) {
  if (s.sensor_model.kind != SensorModelConfig::Kind::kAcousticDoppler)
    r.fail(line, "'" + path + "' applies only with 'sensor_model.kind: acoustic_doppler'");
}

/// targets.birth_rate: at most kMaxBirthsPerTick expected births per tick over the region.
void birthsPerTickBounded(const Reader& r, const Scenario& s, int line) {
  const double births = s.targets.birth_rate * s.region.area();
  if (births > kMaxBirthsPerTick)
    r.fail(line, "'targets.birth_rate' " + compactNumber(s.targets.birth_rate) + " gives " + compactNumber(births) +
                     " expected births per tick over the region (area " + compactNumber(s.region.area()) +
                     "); expected at most " + compactNumber(kMaxBirthsPerTick));
}

/// A scripted target: slower than its sound (acoustic), disappearing after it appears, starting
/// inside the region.
void scriptedTargetIsValid(const Reader& r, const Scenario& s, const TargetSpec& spec, const Section& t) {
  const std::string& path = t.path;
  if (s.sensor_model.kind == SensorModelConfig::Kind::kAcousticDoppler) {
    // The retarded emission time is unique only while the target is slower than its sound.
    const auto& ac = s.sensor_model.acoustic;
    const double target_speed = std::hypot(spec.velocity.x, spec.velocity.y) / ac.tick_s;
    if (!(target_speed < ac.sound_speed))
      r.fail(t.line, "'" + path + "' moves at " + compactNumber(target_speed) + " per second, not slower than the " +
                         "sound speed " + compactNumber(ac.sound_speed) + " of 'sensor_model.acoustic'");
  }
  if (spec.disappear_tick != 0 && spec.disappear_tick <= spec.appear_tick)
    r.fail(Reader::lineOf(*t.find("disappear_tick")),
           "'" + path + ".disappear_tick' must be 0 (never) or greater than appear_tick " +
               std::to_string(spec.appear_tick) + ", got " + std::to_string(spec.disappear_tick));
  if (!s.region.contains(spec.position))
    r.fail(t.line, "'" + path + "' starts at " + pointText(spec.position) + ", outside the region " +
                       regionText(s.region));
}

/// Born targets move at up to the speed class's bound on each axis (common/truth.cpp); with
/// acoustic sensors they must stay slower than their sound.
void bornTargetsSlowerThanSound(const Reader& r, const Scenario& s, int line) {
  if (s.sensor_model.kind != SensorModelConfig::Kind::kAcousticDoppler || !(s.targets.birth_rate > 0.0)) return;
  const double per_axis = s.targets.speed_class == SpeedClass::kSlow     ? 1.0
                          : s.targets.speed_class == SpeedClass::kMedium ? 2.0
                                                                         : 5.0;
  const double fastest = per_axis * std::sqrt(2.0) / s.sensor_model.acoustic.tick_s;
  if (!(fastest < s.sensor_model.acoustic.sound_speed))
    r.fail(line, "'targets.speed_class' lets born targets move at up to " + compactNumber(fastest) +
                     " per second, not slower than the sound speed " +
                     compactNumber(s.sensor_model.acoustic.sound_speed) + " of 'sensor_model.acoustic'");
}

/// A supernode inside the region and apart from every earlier one.
void supernodeIsPlaced(const Reader& r, const Scenario& s, Vec2 p, const Section& sec) {
  if (!s.region.contains(p))
    r.fail(sec.line, "'" + sec.path + "' at " + pointText(p) + " is outside the region " + regionText(s.region));
  for (std::size_t j = 0; j < s.supernodes.size(); ++j)
    if (s.supernodes[j] == p)
      r.fail(sec.line, "'" + sec.path + "' at " + pointText(p) + " is at the same place as 'supernodes[" +
                           std::to_string(j) + "]'");
}

/// run.node_processes: at most one tile per cell of side 2 Rs.
void nodeProcessesFitCells(const Reader& r, const Scenario& s, int line) {
  const double cells = layoutCellCount(s.region, s.sensor_model.sensing_range);
  if (static_cast<double>(s.run.node_processes) > cells)
    r.fail(line, "'run.node_processes' " + std::to_string(s.run.node_processes) + " exceeds the " +
                     compactNumber(cells) + " cells of side 2 Rs = " + compactNumber(2.0 * s.sensor_model.sensing_range) +
                     " that node tiles are made of; expected at most " + compactNumber(cells));
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
int lineOr(const Section& s, std::string_view key, int fallback) {
  const Entry* e = s.find(key);
  return e == nullptr ? fallback : Reader::lineOf(*e);
}

/// A params mapping (tracker.params, aggregator.params): any names, numbers only; the owning
/// component's table checks names and ranges (common/param_spec.hpp).
std::map<std::string, EngineParam> readParams(const Reader& r, const Entry& entry, const std::string& path) {
  std::map<std::string, EngineParam> params;
  const Section p = r.section(entry, path, {});
  for (const auto& [name, value] : p.entries)
    params[name] = EngineParam{r.anyNumber(value, p.pathOf(name)), Reader::lineOf(value.key)};
  return params;
}

// ---------------------------------------------------------------------------------------------
// The scenario, section by section. Sections are read in a fixed order (region first) so that
// checks against the region do not depend on the order of keys in the file.

/// sensor_model (Oh eq. 5, or An et al. 2014 eq. 1-4 for acoustic sensors); returns the line
/// to blame for sensing_range (fallback when the file does not give it).
int readSensorModel(const Reader& r, const Section& top, Scenario& s, int fallback_line) {
  int sensing_range_line = fallback_line;
  if (top.find("sensor_model") == nullptr) deriveLeftOut(r, nullptr, schema::sensorModel(), s.sensor_model, s);
  if (const Entry* e = top.find("sensor_model")) {
    const Section sec = r.section(*e, schema::sensorModel());
    r.fields(sec, schema::sensorModel(), s.sensor_model);
    sensing_range_line = lineOr(sec, "sensing_range", sensing_range_line);
    deriveLeftOut(r, &sec, schema::sensorModel(), s.sensor_model, s);
    if (const Entry* a = sec.find("acoustic")) {
      onlyAcoustic(r, s, "sensor_model.acoustic", Reader::lineOf(a->key));
      const Section asec = r.section(*a, schema::acoustic());
      r.fields(asec, schema::acoustic(), s.sensor_model.acoustic);
      tickIsWholeDetectionSteps(r, s.sensor_model.acoustic, asec.line);
    }
    if (const Entry* n = sec.find("environmental_noise")) {
      onlyAcoustic(r, s, "sensor_model.environmental_noise", Reader::lineOf(n->key));
      const Section nsec = r.section(*n, schema::environmentalNoise());
      auto& noise = s.sensor_model.environmental_noise;
      const Entry* components = nsec.find("components");
      if (nsec.find("preset") != nullptr && components != nullptr)
        r.fail(nsec.line, "'sensor_model.environmental_noise' takes either 'preset' or 'components', not both");
      r.fields(nsec, schema::environmentalNoise(), noise);
      noise.components = *noisePreset(noise.preset);
      if (components != nullptr && !components->value.IsNull()) {
        const std::string path = "sensor_model.environmental_noise.components";
        if (!components->value.IsSequence())
          r.fail(Reader::lineOf(*components),
                 "'" + path + "' must be a list of {fraction, duration_s}, got " + describe(components->value));
        noise.preset = "custom";
        double total = 0.0;
        forEachItem(r, *components, path, "{fraction, duration_s}", [&](const YAML::Node& item, int line, auto& p) {
          const Section c = r.item(item, line, p, schema::noiseComponent());
          r.require(c, {"fraction", "duration_s"}, "share of the sensors and seconds each hears the noise");
          NoiseComponent component;
          r.fields(c, schema::noiseComponent(), component);
          total += component.fraction;
          noise.components.push_back(component);
        });
        if (total > 1.0)
          r.fail(Reader::lineOf(*components),
                 "the fractions of '" + path + "' add up to " + compactNumber(total) + "; expected at most 1");
      }
    }
  }

  return sensing_range_line;
}

/// targets: the random births and the scripted list.
void readTargets(const Reader& r, const Section& top, Scenario& s) {
  if (const Entry* e = top.find("targets")) {
    const Section sec = r.section(*e, schema::targets());
    r.fields(sec, schema::targets(), s.targets);
    if (sec.find("birth_rate") != nullptr) birthsPerTickBounded(r, s, Reader::lineOf(*sec.find("birth_rate")));
    if (const Entry* scripted = sec.find("scripted"); scripted != nullptr && !scripted->value.IsNull()) {
      const std::string shape = "{appear_tick, disappear_tick, x, y, vx, vy}";
      if (!scripted->value.IsSequence())
        r.fail(Reader::lineOf(*scripted),
               "'targets.scripted' must be a list of " + shape + ", got " + describe(scripted->value));
      forEachItem(r, *scripted, "targets.scripted", shape, [&](const YAML::Node& item, int line, auto& path) {
        const Section t = r.item(item, line, path, schema::scriptedTarget());
        r.require(t, {"x", "y"}, "initial position, sensor separations");
        r.require(t, {"vx", "vy"}, "velocity, sensor separations per tick");
        TargetSpec spec;
        r.fields(t, schema::scriptedTarget(), spec);
        if (const Entry* range = t.find("sensing_range"))
          onlyAcoustic(r, s, path + ".sensing_range", Reader::lineOf(*range));
        scriptedTargetIsValid(r, s, spec, t);
        s.targets.scripted.push_back(spec);
      });
    }
  }
  if (const Entry* e = top.find("targets")) bornTargetsSlowerThanSound(r, s, Reader::lineOf(*e));

}

/// supernodes: the listed ones, or one at the centre of the region.
void readSupernodes(const Reader& r, const Section& top, Scenario& s) {
  if (const Entry* e = top.find("supernodes"); e != nullptr && !e->value.IsNull()) {
    const int list_line = Reader::lineOf(*e);
    if (!e->value.IsSequence()) r.fail(list_line, "'supernodes' must be a list of {x, y}, got " + describe(e->value));
    if (e->value.size() == 0) r.fail(list_line, "'supernodes' must list at least one supernode");
    if (e->value.size() > kMaxSupernodes)
      r.fail(list_line, "'supernodes' lists " + std::to_string(e->value.size()) + " supernodes; expected at most " +
                            std::to_string(kMaxSupernodes));
    forEachItem(r, *e, "supernodes", "{x, y}", [&](const YAML::Node& item, int line, auto& path) {
      const Section sec = r.item(item, line, path, schema::supernode());
      r.require(sec, {"x", "y"}, "position, sensor separations");
      Vec2 p;
      r.fields(sec, schema::supernode(), p);
      supernodeIsPlaced(r, s, p, sec);
      s.supernodes.push_back(p);
    });
  } else {
    s.supernodes = {{0.5 * (s.region.x_min + s.region.x_max), 0.5 * (s.region.y_min + s.region.y_max)}};
    s.derived["supernodes"] = "one supernode at the centre of the region";
  }

}

/// tracker and aggregator: which components, and their parameters as written (the engine and
/// association registries check them against the chosen component's table).
void readComponentChoices(const Reader& r, const Section& top, Scenario& s) {
  if (const Entry* e = top.find("tracker")) {
    const Section sec = r.section(*e, schema::tracker());
    r.fields(sec, schema::tracker(), s.tracker);
    if (const Entry* engine = sec.find("engine")) {
      s.tracker.engine_line = Reader::lineOf(*engine);
      if (s.tracker.engine.empty()) r.fail(s.tracker.engine_line, "'tracker.engine' must name an engine, got ''");
    }
    if (const Entry* params = sec.find("params")) s.tracker.params = readParams(r, *params, "tracker.params");
  }
  if (const Entry* e = top.find("aggregator")) {
    const Section sec = r.section(*e, schema::aggregator());
    r.fields(sec, schema::aggregator(), s.aggregator);
    if (const Entry* association = sec.find("association")) {
      s.aggregator.association_line = Reader::lineOf(*association);
      if (s.aggregator.association.empty())
        r.fail(s.aggregator.association_line, "'aggregator.association' must name a method, got ''");
    }
    if (const Entry* params = sec.find("params")) s.aggregator.params = readParams(r, *params, "aggregator.params");
  }

}

Scenario readScenario(const YAML::Node& root, const std::string& file) {
  const Reader r(file);
  Scenario s;
  s.source_path = file;
  const Section top = r.section(root, 1, "", schema::sectionNames());

  if (const Entry* e = top.find("name")) {
    r.fields(top, schema::topLevel(), s);
    if (!validName(s.name))
      r.fail(Reader::lineOf(*e), "'name' must be 1 to " + std::to_string(kMaxNameLength) +
                                     " characters from A-Z a-z 0-9 _ - . (it names the run directory), got '" +
                                     s.name + "'");
  }

  int region_line = 1;
  if (const Entry* e = top.find("region")) {
    const Section sec = r.section(*e, schema::region());
    region_line = sec.line;
    r.fields(sec, schema::region(), s.region);
    regionIsOrdered(r, s.region, sec.line);
  }

  int layout_line = region_line;  // where a layout that does not fit the region is reported
  if (const Entry* e = top.find("sensors")) {
    const Section sec = r.section(*e, schema::sensors());
    r.fields(sec, schema::sensors(), s.sensors);
    layout_line = lineOr(sec, "spacing", layout_line);
  }
  gridFitsRegion(r, s, layout_line);

  const int sensing_range_line = readSensorModel(r, top, s, region_line);

  if (const Entry* e = top.find("localisation"))
    r.fields(r.section(*e, schema::localisation()), schema::localisation(), s.localisation);

  readTargets(r, top, s);
  if (const Entry* e = top.find("dynamics"))
    r.fields(r.section(*e, schema::dynamics()), schema::dynamics(), s.dynamics);

  readSupernodes(r, top, s);

  if (const Entry* e = top.find("network")) r.fields(r.section(*e, schema::network()), schema::network(), s.network);

  readComponentChoices(r, top, s);

  if (const Entry* e = top.find("metrics")) r.fields(r.section(*e, schema::metrics()), schema::metrics(), s.metrics);

  int node_processes_line = sensing_range_line;
  if (const Entry* e = top.find("run")) {
    const Section sec = r.section(*e, schema::run());
    r.fields(sec, schema::run(), s.run);
    node_processes_line = lineOr(sec, "node_processes", node_processes_line);
  }
  nodeProcessesFitCells(r, s, node_processes_line);
  return s;
}

// ---------------------------------------------------------------------------------------------
// Writing.

/// A mapping key: plain when it is a simple name, quoted otherwise (and when YAML would read the
/// plain word as null).
std::string keyText(const std::string& name) {
  const bool null_word = name == "null" || name == "Null" || name == "NULL";
  const bool plain = !null_word && !name.empty() &&
                     (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                     std::all_of(name.begin(), name.end(), [](char c) {
                       return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                     });
  return plain ? name : config::yamlQuoted(name);
}

/// `indent key: value` for every value key of `table` (nested keys are written by the caller).
/// A derived value's key gets "# derived: how" after its value.
template <typename C>
void writeFields(std::ostringstream& out, const std::string& indent, const FieldTable<C>& table, const C& config,
                 const std::map<std::string, std::string>& derived = {}) {
  for (const auto& field : table.fields) {
    if (field.kind == FieldKind::kNested) continue;
    out << indent << field.key << ": " << field.yamlValue(config);
    if (const auto it = derived.find(table.section + "." + field.key); it != derived.end())
      out << "  # derived: " << it->second;
    out << "\n";
  }
}

template <typename C>
void writeSection(std::ostringstream& out, const std::string& name, const FieldTable<C>& table, const C& config,
                  const std::map<std::string, std::string>& derived = {}) {
  out << name << ":\n";
  writeFields(out, "  ", table, config, derived);
}

/// "{a: 1, b: 2}": a list item on one line; a key whose zero means "not given" is left out at 0.
template <typename C>
std::string flowMapping(const FieldTable<C>& table, const C& config) {
  std::string text;
  for (const auto& field : table.fields) {
    if (field.kind == FieldKind::kNested || (field.zero_means_unset && field.get_number(config) == 0.0)) continue;
    text += (text.empty() ? "{" : ", ") + field.key + ": " + field.yamlValue(config);
  }
  return text + "}";
}

template <typename C>
void writeList(std::ostringstream& out, const std::string& indent, const std::string& key, const FieldTable<C>& table,
               const std::vector<C>& items, const std::string& derivation = "") {
  if (items.empty()) {
    out << indent << key << ": []\n";
    return;
  }
  out << indent << key << ":" << (derivation.empty() ? "" : "  # derived: " + derivation) << "\n";
  for (const auto& item : items) out << indent << "  - " << flowMapping(table, item) << "\n";
}

void writeParams(std::ostringstream& out, const std::map<std::string, EngineParam>& params) {
  if (params.empty()) {
    out << "  params: {}\n";
    return;
  }
  out << "  params:\n";
  for (const auto& [name, param] : params) out << "    " << keyText(name) << ": " << yamlNumber(param.value) << "\n";
}

// ---------------------------------------------------------------------------------------------
// Reading a document.

/// The one YAML document of a scenario text (null when empty); syntax errors as "name:line: ...".
YAML::Node parseDocument(const std::string& yaml_text, const std::string& name_for_errors) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(yaml_text);
  } catch (const YAML::ParserException& error) {
    const int line = error.mark.is_null() ? 1 : error.mark.line + 1;
    throw ScenarioError(name_for_errors + ":" + std::to_string(line) + ": invalid YAML: " + error.msg);
  } catch (const YAML::Exception& error) {
    throw ScenarioError(name_for_errors + ":1: invalid YAML: " + error.msg);
  }
  for (std::size_t i = 1; i < documents.size(); ++i)
    if (!documents[i].IsNull())
      throw ScenarioError(name_for_errors + ":" + std::to_string(std::max(Reader::lineOf(documents[i]), 1)) +
                          ": a scenario file holds one YAML document; found a second one here");
  return documents.empty() ? YAML::Node() : documents.front();
}

Scenario validateTree(const YAML::Node& root, const std::string& name_for_errors) {
  try {
    return readScenario(root, name_for_errors);
  } catch (const YAML::Exception& error) {  // not expected: every access above is checked
    const int line = error.mark.is_null() ? 1 : error.mark.line + 1;
    throw ScenarioError(name_for_errors + ":" + std::to_string(line) + ": " + error.msg);
  }
}

std::string readScenarioFile(const std::string& path) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw ScenarioError(path + ": cannot open scenario file (" + std::strerror(errno) + ")");
  std::string text;
  char buffer[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, n);
  if (std::ferror(file.get()))
    throw ScenarioError(path + ": cannot read scenario file (" + std::strerror(errno) + ")");
  return text;
}

// ---------------------------------------------------------------------------------------------
// Overrides. They are set in the YAML tree of the file as written, not in the resolved
// scenario, so that what the loader derives from other values (beta from Rs, the default
// supernode from the region, engine defaults from the engine) follows them as after an edit.

/// One step of a key's path: a mapping key, or an item of a list.
struct PathStep {
  std::string key;  ///< empty for a list item
  std::size_t index = 0;
};

/// "supernodes[1].x" -> supernodes, [1], x. Names are anything but '.', '[' and ']'.
std::vector<PathStep> keyPath(const ScenarioOverride& o) {
  const auto bad = [&o]() {
    throw OverrideError(o.text() + ": KEY must be a dotted path of names, list items as name[i] "
                                   "(e.g. network.pte, tracker.params.gate_chi2, supernodes[0].x)");
  };
  std::vector<PathStep> path;
  std::size_t i = 0;
  const std::string& key = o.key;
  while (true) {
    const std::size_t end = key.find_first_of(".[]", i);
    const std::string name = key.substr(i, end == std::string::npos ? std::string::npos : end - i);
    if (name.empty()) bad();
    path.push_back({name, 0});
    i = end;
    while (i != std::string::npos && key[i] == '[') {
      const std::size_t close = key.find(']', i);
      if (close == std::string::npos || close == i + 1) bad();
      std::size_t index = 0;
      const auto result = std::from_chars(key.data() + i + 1, key.data() + close, index);
      if (result.ec != std::errc{} || result.ptr != key.data() + close) bad();
      path.push_back({"", index});
      i = close + 1 < key.size() ? close + 1 : std::string::npos;
    }
    if (i == std::string::npos) break;
    if (key[i] != '.') bad();
    ++i;
  }
  return path;
}

/// The value as one YAML scalar, or null for an empty value.
YAML::Node overrideValue(const ScenarioOverride& o) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(o.value);
  } catch (const YAML::Exception& error) {
    throw OverrideError(o.text() + ": VALUE is not valid YAML (" + error.msg + "); quote it to make it a string");
  }
  if (documents.empty()) return YAML::Node(YAML::NodeType::Null);
  if (documents.size() > 1 || documents.front().IsMap() || documents.front().IsSequence())
    throw OverrideError(o.text() + ": VALUE must be a single value such as 0.4 or gnn, got " +
                        (documents.size() > 1 ? std::string("several YAML documents") : describe(documents.front())) +
                        "; lists and mappings belong in the scenario file");
  return documents.front();
}

/// Sets path[i..] below `container` to `value`; `where` is the dotted path of `container`.
/// Nodes are handles: a copy refers to the same node of the tree, so setting through one
/// changes the tree.
void setPath(YAML::Node container, const std::vector<PathStep>& path, std::size_t i, const YAML::Node& value,
             const std::string& where, const ScenarioOverride& o) {
  const PathStep& step = path[i];
  const bool last = i + 1 == path.size();
  const std::string here =
      step.key.empty() ? where + "[" + std::to_string(step.index) + "]" : (where.empty() ? "" : where + ".") + step.key;
  if (!step.key.empty()) {
    if (!container.IsMap())
      throw OverrideError(o.text() + ": '" + where + "' is " + describe(container) +
                          (container.IsSequence() ? "; address its items as " + where + "[0]" : ", not a mapping"));
    if (last) {
      container[step.key] = value;
      return;
    }
    // A section left out (or left empty) is created, as if the file had it; an unknown name
    // is then rejected by the loader with the list of the names it expects.
    if (!container[step.key].IsMap() && !container[step.key].IsSequence()) {
      if (container[step.key].IsScalar())
        throw OverrideError(o.text() + ": '" + here + "' is " + describe(container[step.key]) + ", not a mapping");
      container[step.key] = YAML::Node(YAML::NodeType::Map);
    }
    setPath(container[step.key], path, i + 1, value, here, o);
    return;
  }
  if (!container.IsSequence())
    throw OverrideError(o.text() + ": '" + where + "' is " + describe(container) + ", not a list");
  if (step.index >= container.size())
    throw OverrideError(o.text() + ": '" + where + "' has " + std::to_string(container.size()) +
                        " items (from [0]); a list can only be changed item by item, not extended");
  if (last) {
    container[step.index] = value;
    return;
  }
  setPath(container[step.index], path, i + 1, value, here, o);
}

void applyOverride(YAML::Node& root, const ScenarioOverride& o) {
  const std::vector<PathStep> path = keyPath(o);
  const YAML::Node value = overrideValue(o);
  if (!root.IsDefined() || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);  // an empty file
  setPath(root, path, 0, value, "", o);
}

/// "name:12: message" -> "message": the line of a validated tree that holds overrides points
/// into no file the user has.
std::string withoutLocation(const std::string& message, const std::string& name) {
  if (message.compare(0, name.size() + 1, name + ":") != 0) return message;
  std::size_t i = name.size() + 1;
  while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i]))) ++i;
  if (i == name.size() + 1 || message.compare(i, 2, ": ") != 0) return message;
  return message.substr(i + 2);
}

Scenario validateTree(const YAML::Node& root, const std::string& name, const ScenarioCheck& check) {
  Scenario s = validateTree(root, name);
  if (check) check(s);
  return s;
}

/// The message a tree fails validation with; nullopt when it is valid.
std::optional<std::string> failureOf(const YAML::Node& root, const std::string& name, const ScenarioCheck& check) {
  try {
    validateTree(root, name, check);
  } catch (const ScenarioError& error) {
    return std::string(error.what());
  }
  return std::nullopt;
}

}  // namespace

Scenario parseScenario(const std::string& yaml_text, const std::string& name_for_errors) {
  return validateTree(parseDocument(yaml_text, name_for_errors), name_for_errors);
}

Scenario loadScenario(const std::string& path) { return parseScenario(readScenarioFile(path), path); }

ScenarioOverride parseOverride(const std::string& key_equals_value) {
  const std::size_t equals = key_equals_value.find('=');
  if (equals == std::string::npos || equals == 0)
    throw OverrideError("--set " + key_equals_value + ": expected KEY=VALUE, e.g. --set network.pte=0.4");
  return {key_equals_value.substr(0, equals), key_equals_value.substr(equals + 1), ""};
}

Scenario applyOverrides(const std::string& yaml_text, const std::string& name_for_errors,
                        const std::vector<ScenarioOverride>& overrides, const ScenarioCheck& check) {
  // Each tree is parsed afresh rather than cloned: a clone loses the marks that give the lines
  // of the file's own problems.
  const auto overridden = [&](const ScenarioOverride* first, const ScenarioOverride* last) {
    YAML::Node tree = parseDocument(yaml_text, name_for_errors);
    if (tree.IsDefined() && !tree.IsNull() && !tree.IsMap()) validateTree(tree, name_for_errors);  // throws
    for (; first != last; ++first) applyOverride(tree, *first);
    return tree;
  };
  const ScenarioOverride* const begin = overrides.data();
  const ScenarioOverride* const end = begin + overrides.size();
  try {
    return validateTree(overridden(begin, end), name_for_errors, check);
  } catch (const OverrideError&) {
    throw;
  } catch (const ScenarioError& error) {
    const std::string message = error.what();
    // The file's own first problem reads the same with and without the overrides, line and all.
    const auto base_failure = failureOf(overridden(begin, begin), name_for_errors, check);
    if (base_failure == message) throw;
    // Otherwise name the overrides that fail the same way on their own, else those that fail
    // some other way on their own, else (only their combination fails) all of them.
    const std::string reason = withoutLocation(message, name_for_errors);
    std::vector<const ScenarioOverride*> same;
    std::vector<const ScenarioOverride*> other;
    for (const ScenarioOverride* o = begin; o != end; ++o) {
      std::optional<std::string> alone;
      try {
        alone = failureOf(overridden(o, o + 1), name_for_errors, check);
      } catch (const OverrideError&) {  // its path needs an earlier override
        continue;
      }
      if (!alone || alone == base_failure) continue;
      (withoutLocation(*alone, name_for_errors) == reason ? same : other).push_back(o);
    }
    std::vector<const ScenarioOverride*> named = !same.empty() ? same : other;
    if (named.empty())
      for (const ScenarioOverride* o = begin; o != end; ++o) named.push_back(o);
    std::string options;
    for (const auto* o : named) options += (options.empty() ? "" : " ") + o->text();
    throw OverrideError(options + ": " + reason);
  }
}

std::optional<std::vector<NoiseComponent>> noisePreset(const std::string& name) {
  // An et al. 2013 §3.3.1.
  if (name == "none") return std::vector<NoiseComponent>{};
  if (name == "noise1") return std::vector<NoiseComponent>{{0.06, 0.1}};
  if (name == "noise2") return std::vector<NoiseComponent>{{0.05, 0.1}, {0.01, 0.5}};
  if (name == "noise3") return std::vector<NoiseComponent>{{0.05, 0.1}, {0.01, 1.0}};
  return std::nullopt;
}

Scenario loadScenario(const std::string& path, const std::vector<ScenarioOverride>& overrides,
                      const ScenarioCheck& check) {
  return applyOverrides(readScenarioFile(path), path, overrides, check);
}

std::string resolvedScenarioYaml(const Scenario& s) {
  std::ostringstream out;
  out << "# wsntrack resolved scenario: every parameter written out with defaults filled in.\n"
      << "# Loading this file gives the same scenario. '# derived:' marks a value the file left out\n"
      << "# and the loader computed from others.\n";
  writeFields(out, "", schema::topLevel(), s);
  writeSection(out, "region", schema::region(), s.region);
  writeSection(out, "sensors", schema::sensors(), s.sensors);
  writeSection(out, "sensor_model", schema::sensorModel(), s.sensor_model, s.derived);
  if (s.sensor_model.kind == SensorModelConfig::Kind::kAcousticDoppler) {
    out << "  acoustic:\n";
    writeFields(out, "    ", schema::acoustic(), s.sensor_model.acoustic);
    const auto& noise = s.sensor_model.environmental_noise;
    out << "  environmental_noise:\n";
    if (noise.preset != "custom") {
      writeFields(out, "    ", schema::environmentalNoise(), noise);
    } else {
      writeList(out, "    ", "components", schema::noiseComponent(), noise.components);
    }
  }
  writeSection(out, "localisation", schema::localisation(), s.localisation);
  writeSection(out, "targets", schema::targets(), s.targets);
  writeList(out, "  ", "scripted", schema::scriptedTarget(), s.targets.scripted);
  writeSection(out, "dynamics", schema::dynamics(), s.dynamics);
  const auto supernodes_derived = s.derived.find("supernodes");
  writeList(out, "", "supernodes", schema::supernode(), s.supernodes,
            supernodes_derived == s.derived.end() ? "" : supernodes_derived->second);
  writeSection(out, "network", schema::network(), s.network);
  writeSection(out, "tracker", schema::tracker(), s.tracker);
  writeParams(out, s.tracker.params);
  writeSection(out, "aggregator", schema::aggregator(), s.aggregator);
  writeParams(out, s.aggregator.params);
  writeSection(out, "metrics", schema::metrics(), s.metrics);
  writeSection(out, "run", schema::run(), s.run);
  return out.str();
}

}  // namespace wsn::common

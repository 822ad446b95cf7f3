// The strict YAML scenario loader (DESIGN principle 6): every key is known, every value has the
// expected type and lies in its range, and every problem is reported as "file:line: message"
// naming the dotted key and what was expected. Also applies command-line overrides (--set) to a
// file's YAML before validating it, and writes a scenario back fully resolved.
#include "common/scenario.hpp"

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

// ---------------------------------------------------------------------------------------------
// Limits that are not paper values but keep a run finite and the numbers meaningful.

constexpr double kMaxCoordinate = 1e6;      ///< |region bounds| (sensor separations)
constexpr double kMaxSensors = 1e7;         ///< sensors a layout may create
constexpr double kMaxBirthsPerTick = 1000;  ///< birth_rate * region area
constexpr std::size_t kMaxSupernodes = 256;
constexpr std::size_t kMaxNameLength = 100;

// ---------------------------------------------------------------------------------------------
// Number formatting.

/// Shortest decimal text that reads back to the same double ("0.3", "9.75", "100", "1e+06").
std::string shortestNumber(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

/// For messages: shortest text with a compact exponent ("1e6" rather than "1e+06").
std::string compactNumber(double value) {
  std::string text = shortestNumber(value);
  const auto e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  const bool negative = !exponent.empty() && exponent.front() == '-';
  std::size_t i = (!exponent.empty() && (exponent.front() == '-' || exponent.front() == '+')) ? 1 : 0;
  while (i + 1 < exponent.size() && exponent[i] == '0') ++i;
  return text.substr(0, e) + "e" + (negative ? "-" : "") + exponent.substr(i);
}

/// For the resolved file: shortest round-trip text that every YAML reader takes for a float
/// (YAML 1.1 readers want a dot in the mantissa of an exponent form: "1.0e+06").
std::string yamlNumber(double value) {
  std::string text = shortestNumber(value);
  const auto e = text.find('e');
  if (e != std::string::npos && text.find('.') == std::string::npos) text.insert(e, ".0");
  return text;
}

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

// ---------------------------------------------------------------------------------------------
// Ranges.

/// A real interval with open or closed ends, printed as in the messages: "(0, 1e6]".
struct Range {
  double lo;
  double hi;
  bool lo_open;
  bool hi_open;
  bool contains(double v) const { return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi); }
  std::string text() const {
    return std::string(lo_open ? "(" : "[") + compactNumber(lo) + ", " + compactNumber(hi) + (hi_open ? ")" : "]");
  }
};

constexpr Range kPositive{0.0, 1e6, true, false};
constexpr Range kNonNegative{0.0, 1e6, false, false};
constexpr Range kProbability{0.0, 1.0, false, false};
constexpr Range kCoordinate{-kMaxCoordinate, kMaxCoordinate, false, false};

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
  Section section(const YAML::Node& node, int line, const std::string& path,
                  std::initializer_list<const char*> allowed) const {
    Section s;
    s.path = path;
    s.line = std::max(line, 1);
    std::vector<std::string> names(allowed.begin(), allowed.end());
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

  Section section(const Entry& entry, const std::string& path, std::initializer_list<const char*> allowed) const {
    return section(entry.value, lineOf(entry), path, allowed);
  }

  /// A real number in `range`; true when the key was given.
  bool number(const Section& s, std::string_view key, double& out, const Range& range) const {
    const Entry* entry = s.find(key);
    if (entry == nullptr) return false;
    out = numberValue(*entry, s.pathOf(key), range);
    return true;
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

  /// A whole number in `range`, stored in an integer type T.
  template <typename T>
  bool integer(const Section& s, std::string_view key, T& out, const IntRange& range) const {
    const Entry* entry = s.find(key);
    if (entry == nullptr) return false;
    const std::string path = s.pathOf(key);
    const long double value = whole(*entry, path);
    if (value < static_cast<long double>(range.lo) || value > static_cast<long double>(range.hi))
      fail(lineOf(*entry), "'" + path + "' must be in " + range.text() + ", got " + entry->value.Scalar());
    out = static_cast<T>(value);
    return true;
  }

  /// A whole number in [0, 2^64 - 1] (seeds), converted exactly.
  bool unsigned64(const Section& s, std::string_view key, std::uint64_t& out) const {
    const Entry* entry = s.find(key);
    if (entry == nullptr) return false;
    const YAML::Node& node = entry->value;
    if (node.IsScalar() && isPlainOrNumericTag(node)) {  // integer text, decimal or hex: exact
      const std::string_view text = withoutPlus(node.Scalar());
      const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
      const char* last = text.data() + text.size();
      std::uint64_t value = 0;
      const auto result = std::from_chars(text.data() + (hex ? 2 : 0), last, value, hex ? 16 : 10);
      if (result.ec == std::errc{} && result.ptr == last) {
        out = value;
        return true;
      }
    }
    // Anything else: a whole float (1e3), or an error for a non-number, a fraction or a value
    // out of range (negative, or 2^64 and beyond).
    const std::string path = s.pathOf(key);
    const long double value = whole(*entry, path);
    if (value < 0.0L || value >= 18446744073709551616.0L)
      fail(lineOf(*entry), "'" + path + "' must be in [0, 18446744073709551615], got " + node.Scalar());
    out = static_cast<std::uint64_t>(value);
    return true;
  }

  /// A string (any scalar).
  bool text(const Section& s, std::string_view key, std::string& out) const {
    const Entry* entry = s.find(key);
    if (entry == nullptr) return false;
    if (!entry->value.IsScalar())
      fail(lineOf(*entry), "'" + s.pathOf(key) + "' must be a string, got " + describe(entry->value));
    out = entry->value.Scalar();
    return true;
  }

  /// One of `choices`; returns its index, or -1 when the key is absent.
  int choice(const Section& s, std::string_view key, std::initializer_list<const char*> choices) const {
    const Entry* entry = s.find(key);
    if (entry == nullptr) return -1;
    std::vector<std::string> names(choices.begin(), choices.end());
    const YAML::Node& node = entry->value;
    if (node.IsScalar()) {
      const auto it = std::find(names.begin(), names.end(), node.Scalar());
      if (it != names.end()) return static_cast<int>(it - names.begin());
    }
    fail(lineOf(*entry), "'" + s.pathOf(key) + "' must be one of: " + join(names) + "; got " + describe(node));
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
// The scenario, section by section. Sections are read in a fixed order (region first) so that
// checks against the region do not depend on the order of keys in the file.

Scenario readScenario(const YAML::Node& root, const std::string& file) {
  const Reader r(file);
  Scenario s;
  s.source_path = file;
  const Section top = r.section(root, 1, "",
                                {"name", "region", "sensors", "sensor_model", "localisation", "targets", "dynamics",
                                 "supernodes", "network", "tracker", "aggregator", "metrics", "run"});

  if (const Entry* e = top.find("name")) {
    r.text(top, "name", s.name);
    if (!validName(s.name))
      r.fail(Reader::lineOf(*e), "'name' must be 1 to " + std::to_string(kMaxNameLength) +
                                     " characters from A-Z a-z 0-9 _ - . (it names the run directory), got '" +
                                     s.name + "'");
  }

  // region
  int region_line = 1;
  if (const Entry* e = top.find("region")) {
    const Section sec = r.section(*e, "region", {"x_min", "y_min", "x_max", "y_max"});
    region_line = sec.line;
    r.number(sec, "x_min", s.region.x_min, kCoordinate);
    r.number(sec, "y_min", s.region.y_min, kCoordinate);
    r.number(sec, "x_max", s.region.x_max, kCoordinate);
    r.number(sec, "y_max", s.region.y_max, kCoordinate);
    if (!(s.region.x_min < s.region.x_max))
      r.fail(sec.line, "'region' must have x_min < x_max, got x_min = " + compactNumber(s.region.x_min) +
                           ", x_max = " + compactNumber(s.region.x_max));
    if (!(s.region.y_min < s.region.y_max))
      r.fail(sec.line, "'region' must have y_min < y_max, got y_min = " + compactNumber(s.region.y_min) +
                           ", y_max = " + compactNumber(s.region.y_max));
  }

  // sensors
  int layout_line = region_line;  // where a layout that does not fit the region is reported
  if (const Entry* e = top.find("sensors")) {
    const Section sec = r.section(*e, "sensors", {"layout", "spacing", "count"});
    const int kind = r.choice(sec, "layout", {"grid", "random"});
    if (kind >= 0) s.sensors.kind = kind == 0 ? SensorLayoutConfig::Kind::kGrid : SensorLayoutConfig::Kind::kRandom;
    if (r.number(sec, "spacing", s.sensors.spacing, kPositive)) layout_line = Reader::lineOf(*sec.find("spacing"));
    r.integer(sec, "count", s.sensors.count, IntRange{1, static_cast<std::int64_t>(kMaxSensors)});
  }
  if (s.sensors.kind == SensorLayoutConfig::Kind::kGrid) {
    const double n = gridSensorCount(s.region, s.sensors.spacing);
    if (n < 1.0 || n > kMaxSensors)
      r.fail(layout_line, "'sensors.spacing' " + compactNumber(s.sensors.spacing) + " puts " + compactNumber(n) +
                              " sensors on the grid over the region " + regionText(s.region) + "; expected 1 to " +
                              compactNumber(kMaxSensors));
  }

  // sensor_model (Oh eq. 5, or An et al. 2014 eq. 1-4 for acoustic sensors)
  int sensing_range_line = region_line;
  if (const Entry* e = top.find("sensor_model")) {
    const Section sec = r.section(*e, "sensor_model",
                                  {"kind", "alpha", "beta", "gamma", "eta", "sensing_range", "noise_sigma", "acoustic",
                                   "environmental_noise"});
    const int kind = r.choice(sec, "kind", {"signal_strength", "acoustic_doppler"});
    if (kind >= 0) s.sensor_model.kind = static_cast<SensorModelConfig::Kind>(kind);
    r.number(sec, "alpha", s.sensor_model.alpha, Range{0.0, 100.0, true, false});
    r.number(sec, "gamma", s.sensor_model.gamma, kNonNegative);
    r.number(sec, "eta", s.sensor_model.eta, Range{0.0, 1e9, true, false});
    if (r.number(sec, "sensing_range", s.sensor_model.sensing_range, kPositive))
      sensing_range_line = Reader::lineOf(*sec.find("sensing_range"));
    r.number(sec, "noise_sigma", s.sensor_model.noise_sigma, kNonNegative);
    if (!r.number(sec, "beta", s.sensor_model.beta, Range{0.0, 1e12, true, false})) {
      // Oh §VII: beta = 3 (1 + gamma Rs^alpha), a signal three times the one at the edge of the range.
      const auto& m = s.sensor_model;
      s.sensor_model.beta = 3.0 * (1.0 + m.gamma * std::pow(m.sensing_range, m.alpha));
      if (!(s.sensor_model.beta <= 1e12))
        r.fail(sec.line, "'sensor_model.beta' left out is 3 (1 + gamma Rs^alpha) = " +
                             compactNumber(s.sensor_model.beta) + ", outside (0, 1e12]; give beta explicitly");
    }
    const bool acoustic = s.sensor_model.kind == SensorModelConfig::Kind::kAcousticDoppler;
    if (const Entry* a = sec.find("acoustic")) {
      if (!acoustic)
        r.fail(Reader::lineOf(a->key), "'sensor_model.acoustic' applies only with 'sensor_model.kind: acoustic_doppler'");
      const Section asec = r.section(*a, "sensor_model.acoustic",
                                     {"threshold", "sound_speed", "detection_step_s", "tick_s", "power_fluctuation"});
      auto& ac = s.sensor_model.acoustic;
      r.number(asec, "threshold", ac.threshold, Range{0.0, 1e12, true, false});
      r.number(asec, "sound_speed", ac.sound_speed, kPositive);
      r.number(asec, "detection_step_s", ac.detection_step_s, Range{0.0, 10.0, true, false});
      r.number(asec, "tick_s", ac.tick_s, Range{0.0, 1e3, true, false});
      r.number(asec, "power_fluctuation", ac.power_fluctuation, Range{0.0, 1.0, false, true});
      const double steps = ac.tick_s / ac.detection_step_s;
      if (std::abs(steps - std::round(steps)) > 1e-6 * steps || std::round(steps) > 100000.0)
        r.fail(asec.line, "'sensor_model.acoustic.tick_s' " + compactNumber(ac.tick_s) +
                              " must be a whole number (at most 100000) of detection steps of " +
                              compactNumber(ac.detection_step_s) + " s");
    }
    if (const Entry* n = sec.find("environmental_noise")) {
      if (!acoustic)
        r.fail(Reader::lineOf(n->key),
               "'sensor_model.environmental_noise' applies only with 'sensor_model.kind: acoustic_doppler'");
      const Section nsec = r.section(*n, "sensor_model.environmental_noise", {"preset", "components"});
      auto& noise = s.sensor_model.environmental_noise;
      const Entry* preset = nsec.find("preset");
      const Entry* components = nsec.find("components");
      if (preset != nullptr && components != nullptr)
        r.fail(nsec.line, "'sensor_model.environmental_noise' takes either 'preset' or 'components', not both");
      if (preset != nullptr) {
        const int which = r.choice(nsec, "preset", {"none", "noise1", "noise2", "noise3"});
        noise.preset = std::array{"none", "noise1", "noise2", "noise3"}[static_cast<std::size_t>(which)];
        noise.components = *noisePreset(noise.preset);
      }
      if (components != nullptr && !components->value.IsNull()) {
        if (!components->value.IsSequence())
          r.fail(Reader::lineOf(*components),
                 "'sensor_model.environmental_noise.components' must be a list of {fraction, duration_s}, got " +
                     describe(components->value));
        noise.preset = "custom";
        double total = 0.0;
        std::size_t i = 0;
        for (const auto& item : components->value) {
          const std::string path = "sensor_model.environmental_noise.components[" + std::to_string(i++) + "]";
          const int item_line = Reader::lineOf(item) > 0 ? Reader::lineOf(item) : Reader::lineOf(*components);
          if (!item.IsMap()) r.fail(item_line, "'" + path + "' must be a mapping {fraction, duration_s}, got " + describe(item));
          const Section c = r.section(item, item_line, path, {"fraction", "duration_s"});
          r.require(c, {"fraction", "duration_s"}, "share of the sensors and seconds each hears the noise");
          NoiseComponent component;
          r.number(c, "fraction", component.fraction, kProbability);
          r.number(c, "duration_s", component.duration_s, Range{0.0, 1e6, true, false});
          total += component.fraction;
          noise.components.push_back(component);
        }
        if (total > 1.0)
          r.fail(Reader::lineOf(*components), "the fractions of 'sensor_model.environmental_noise.components' add up to " +
                                                  compactNumber(total) + "; expected at most 1");
      }
    }
  }

  if (const Entry* e = top.find("localisation")) {
    const Section sec = r.section(*e, "localisation", {"sigma"});
    r.number(sec, "sigma", s.localisation.sigma, Range{0.0, 1e3, false, false});
  }

  // targets
  if (const Entry* e = top.find("targets")) {
    const Section sec = r.section(*e, "targets", {"scripted", "birth_rate", "death_probability", "speed_class"});
    if (r.number(sec, "birth_rate", s.targets.birth_rate, kNonNegative)) {
      const double births = s.targets.birth_rate * s.region.area();
      if (births > kMaxBirthsPerTick)
        r.fail(Reader::lineOf(*sec.find("birth_rate")),
               "'targets.birth_rate' " + compactNumber(s.targets.birth_rate) + " gives " + compactNumber(births) +
                   " expected births per tick over the region (area " + compactNumber(s.region.area()) +
                   "); expected at most " + compactNumber(kMaxBirthsPerTick));
    }
    r.number(sec, "death_probability", s.targets.death_probability, kProbability);
    const int speed = r.choice(sec, "speed_class", {"slow", "medium", "fast"});
    if (speed >= 0) s.targets.speed_class = static_cast<SpeedClass>(speed);

    if (const Entry* scripted = sec.find("scripted"); scripted != nullptr && !scripted->value.IsNull()) {
      if (!scripted->value.IsSequence())
        r.fail(Reader::lineOf(*scripted),
               "'targets.scripted' must be a list of {appear_tick, disappear_tick, x, y, vx, vy}, got " +
                   describe(scripted->value));
      std::size_t i = 0;
      for (const auto& item : scripted->value) {
        const std::string path = "targets.scripted[" + std::to_string(i++) + "]";
        const int item_line = Reader::lineOf(item) > 0 ? Reader::lineOf(item) : Reader::lineOf(*scripted);
        if (!item.IsMap())
          r.fail(item_line, "'" + path + "' must be a mapping {appear_tick, disappear_tick, x, y, vx, vy}, got " +
                                describe(item));
        const Section t =
            r.section(item, item_line, path, {"appear_tick", "disappear_tick", "x", "y", "vx", "vy", "sensing_range"});
        r.require(t, {"x", "y"}, "initial position, sensor separations");
        r.require(t, {"vx", "vy"}, "velocity, sensor separations per tick");
        TargetSpec spec;
        r.integer(t, "appear_tick", spec.appear_tick, IntRange{1, 1000000});
        r.integer(t, "disappear_tick", spec.disappear_tick, IntRange{0, 1000000});
        r.number(t, "x", spec.position.x, kCoordinate);
        r.number(t, "y", spec.position.y, kCoordinate);
        r.number(t, "vx", spec.velocity.x, kCoordinate);
        r.number(t, "vy", spec.velocity.y, kCoordinate);
        if (r.number(t, "sensing_range", spec.sensing_range, kPositive) &&
            s.sensor_model.kind != SensorModelConfig::Kind::kAcousticDoppler)
          r.fail(Reader::lineOf(*t.find("sensing_range")),
                 "'" + path + ".sensing_range' applies only with 'sensor_model.kind: acoustic_doppler'");
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
        s.targets.scripted.push_back(spec);
      }
    }
  }

  if (s.sensor_model.kind == SensorModelConfig::Kind::kAcousticDoppler && s.targets.birth_rate > 0.0) {
    // Born targets move at up to the speed class's bound on each axis (common/truth.cpp); the
    // retarded emission time is unique only while they are slower than their sound.
    const double per_axis = s.targets.speed_class == SpeedClass::kSlow ? 1.0
                            : s.targets.speed_class == SpeedClass::kMedium ? 2.0 : 5.0;
    const double fastest = per_axis * std::sqrt(2.0) / s.sensor_model.acoustic.tick_s;
    if (!(fastest < s.sensor_model.acoustic.sound_speed))
      r.fail(Reader::lineOf(*top.find("targets")), "'targets.speed_class' lets born targets move at up to " +
                                                      compactNumber(fastest) + " per second, not slower than the sound speed " +
                                                      compactNumber(s.sensor_model.acoustic.sound_speed) +
                                                      " of 'sensor_model.acoustic'");
  }

  // dynamics (Oh eq. 8)
  if (const Entry* e = top.find("dynamics")) {
    const Section sec = r.section(*e, "dynamics", {"delta", "process_noise_sigma"});
    r.number(sec, "delta", s.dynamics.delta, Range{0.0, 1e3, true, false});
    r.number(sec, "process_noise_sigma", s.dynamics.process_noise_sigma, Range{0.0, 1e3, false, false});
  }

  // supernodes: default one at the centre of the region
  if (const Entry* e = top.find("supernodes"); e != nullptr && !e->value.IsNull()) {
    const int list_line = Reader::lineOf(*e);
    if (!e->value.IsSequence())
      r.fail(list_line, "'supernodes' must be a list of {x, y}, got " + describe(e->value));
    if (e->value.size() == 0) r.fail(list_line, "'supernodes' must list at least one supernode");
    if (e->value.size() > kMaxSupernodes)
      r.fail(list_line, "'supernodes' lists " + std::to_string(e->value.size()) + " supernodes; expected at most " +
                            std::to_string(kMaxSupernodes));
    std::size_t i = 0;
    for (const auto& item : e->value) {
      const std::string path = "supernodes[" + std::to_string(i++) + "]";
      const int item_line = Reader::lineOf(item) > 0 ? Reader::lineOf(item) : list_line;
      if (!item.IsMap()) r.fail(item_line, "'" + path + "' must be a mapping {x, y}, got " + describe(item));
      const Section sec = r.section(item, item_line, path, {"x", "y"});
      r.require(sec, {"x", "y"}, "position, sensor separations");
      Vec2 p;
      r.number(sec, "x", p.x, kCoordinate);
      r.number(sec, "y", p.y, kCoordinate);
      if (!s.region.contains(p))
        r.fail(sec.line, "'" + path + "' at " + pointText(p) + " is outside the region " + regionText(s.region));
      for (std::size_t j = 0; j < s.supernodes.size(); ++j)
        if (s.supernodes[j] == p)
          r.fail(sec.line, "'" + path + "' at " + pointText(p) + " is at the same place as 'supernodes[" +
                               std::to_string(j) + "]'");
      s.supernodes.push_back(p);
    }
  } else {
    s.supernodes = {{0.5 * (s.region.x_min + s.region.x_max), 0.5 * (s.region.y_min + s.region.y_max)}};
  }

  // network (Oh §V)
  if (const Entry* e = top.find("network")) {
    const Section sec = r.section(*e, "network", {"communication_range", "pte", "pde"});
    r.number(sec, "communication_range", s.network.communication_range, kPositive);
    r.number(sec, "pte", s.network.pte, kProbability);
    r.number(sec, "pde", s.network.pde, kProbability);
  }

  // tracker: parameters are only recorded here; the engine registry checks them.
  if (const Entry* e = top.find("tracker")) {
    const Section sec = r.section(*e, "tracker", {"engine", "window_size", "params"});
    if (r.text(sec, "engine", s.tracker.engine)) {
      s.tracker.engine_line = Reader::lineOf(*sec.find("engine"));
      if (s.tracker.engine.empty()) r.fail(s.tracker.engine_line, "'tracker.engine' must name an engine, got ''");
    }
    r.integer(sec, "window_size", s.tracker.window_size, IntRange{1, 1000});
    if (const Entry* params = sec.find("params")) {
      const Section p = r.section(*params, "tracker.params", {});
      for (const auto& [name, entry] : p.entries)
        s.tracker.params[name] = EngineParam{r.anyNumber(entry, p.pathOf(name)), Reader::lineOf(entry.key)};
    }
  }

  // aggregator: like tracker, parameters are only recorded here; the association registry checks them.
  if (const Entry* e = top.find("aggregator")) {
    const Section sec = r.section(*e, "aggregator", {"association", "params"});
    if (r.text(sec, "association", s.aggregator.association)) {
      s.aggregator.association_line = Reader::lineOf(*sec.find("association"));
      if (s.aggregator.association.empty())
        r.fail(s.aggregator.association_line, "'aggregator.association' must name a method, got ''");
    }
    if (const Entry* params = sec.find("params")) {
      const Section p = r.section(*params, "aggregator.params", {});
      for (const auto& [name, entry] : p.entries)
        s.aggregator.params[name] = EngineParam{r.anyNumber(entry, p.pathOf(name)), Reader::lineOf(entry.key)};
    }
  }

  if (const Entry* e = top.find("metrics")) {
    const Section sec =
        r.section(*e, "metrics", {"ospa_c", "ospa_p", "gospa_c", "gospa_p", "mot_threshold", "quality_gate",
                                    "boundary_band"});
    const Range order{1.0, 100.0, false, false};
    r.number(sec, "ospa_c", s.metrics.ospa_c, kPositive);
    r.number(sec, "ospa_p", s.metrics.ospa_p, order);
    r.number(sec, "gospa_c", s.metrics.gospa_c, kPositive);
    r.number(sec, "gospa_p", s.metrics.gospa_p, order);
    r.number(sec, "mot_threshold", s.metrics.mot_threshold, kPositive);
    r.number(sec, "quality_gate", s.metrics.quality_gate, kPositive);
    r.number(sec, "boundary_band", s.metrics.boundary_band, kNonNegative);
  }

  // run
  int node_processes_line = sensing_range_line;
  if (const Entry* e = top.find("run")) {
    const Section sec = r.section(*e, "run", {"ticks", "seed", "node_processes", "max_ticks_in_flight"});
    r.integer(sec, "ticks", s.run.ticks, IntRange{1, 1000000});
    r.unsigned64(sec, "seed", s.run.seed);
    if (r.integer(sec, "node_processes", s.run.node_processes, IntRange{1, 64}))
      node_processes_line = Reader::lineOf(*sec.find("node_processes"));
    r.integer(sec, "max_ticks_in_flight", s.run.max_ticks_in_flight, IntRange{1, 64});
  }
  const double cells = layoutCellCount(s.region, s.sensor_model.sensing_range);
  if (static_cast<double>(s.run.node_processes) > cells)
    r.fail(node_processes_line, "'run.node_processes' " + std::to_string(s.run.node_processes) +
                                    " exceeds the " + compactNumber(cells) + " cells of side 2 Rs = " +
                                    compactNumber(2.0 * s.sensor_model.sensing_range) +
                                    " that node tiles are made of; expected at most " + compactNumber(cells));
  return s;
}

// ---------------------------------------------------------------------------------------------
// Writing.

/// A double-quoted YAML string (escapes quote, backslash and control characters).
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte == 0x7f) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\x%02x", byte);
      out += buffer;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

/// A mapping key: plain when it is a simple name, quoted otherwise (and when YAML would read the
/// plain word as null).
std::string keyText(const std::string& name) {
  const bool null_word = name == "null" || name == "Null" || name == "NULL";
  const bool plain = !null_word && !name.empty() &&
                     (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                     std::all_of(name.begin(), name.end(), [](char c) {
                       return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                     });
  return plain ? name : quoted(name);
}

const char* speedClassName(SpeedClass c) {
  switch (c) {
    case SpeedClass::kSlow: return "slow";
    case SpeedClass::kMedium: return "medium";
    case SpeedClass::kFast: return "fast";
  }
  return "medium";
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
  return {key_equals_value.substr(0, equals), key_equals_value.substr(equals + 1)};
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
  const auto num = [](double v) { return yamlNumber(v); };
  out << "# wsntrack resolved scenario: every parameter written out with defaults filled in.\n"
      << "# Loading this file gives the same scenario.\n";
  out << "name: " << quoted(s.name) << "\n";
  out << "region:\n"
      << "  x_min: " << num(s.region.x_min) << "\n"
      << "  y_min: " << num(s.region.y_min) << "\n"
      << "  x_max: " << num(s.region.x_max) << "\n"
      << "  y_max: " << num(s.region.y_max) << "\n";
  out << "sensors:\n"
      << "  layout: " << (s.sensors.kind == SensorLayoutConfig::Kind::kGrid ? "grid" : "random") << "\n"
      << "  spacing: " << num(s.sensors.spacing) << "\n"
      << "  count: " << s.sensors.count << "\n";
  out << "sensor_model:\n"
      << "  kind: "
      << (s.sensor_model.kind == SensorModelConfig::Kind::kAcousticDoppler ? "acoustic_doppler" : "signal_strength")
      << "\n"
      << "  alpha: " << num(s.sensor_model.alpha) << "\n"
      << "  beta: " << num(s.sensor_model.beta) << "\n"
      << "  gamma: " << num(s.sensor_model.gamma) << "\n"
      << "  eta: " << num(s.sensor_model.eta) << "\n"
      << "  sensing_range: " << num(s.sensor_model.sensing_range) << "\n"
      << "  noise_sigma: " << num(s.sensor_model.noise_sigma) << "\n";
  if (s.sensor_model.kind == SensorModelConfig::Kind::kAcousticDoppler) {
    const auto& ac = s.sensor_model.acoustic;
    out << "  acoustic:\n"
        << "    threshold: " << num(ac.threshold) << "\n"
        << "    sound_speed: " << num(ac.sound_speed) << "\n"
        << "    detection_step_s: " << num(ac.detection_step_s) << "\n"
        << "    tick_s: " << num(ac.tick_s) << "\n"
        << "    power_fluctuation: " << num(ac.power_fluctuation) << "\n";
    const auto& noise = s.sensor_model.environmental_noise;
    out << "  environmental_noise:\n";
    if (noise.preset != "custom") {
      out << "    preset: " << noise.preset << "\n";
    } else {
      out << "    components:\n";
      for (const auto& c : noise.components)
        out << "      - {fraction: " << num(c.fraction) << ", duration_s: " << num(c.duration_s) << "}\n";
    }
  }
  out << "localisation:\n"
      << "  sigma: " << num(s.localisation.sigma) << "\n";
  out << "targets:\n"
      << "  birth_rate: " << num(s.targets.birth_rate) << "\n"
      << "  death_probability: " << num(s.targets.death_probability) << "\n"
      << "  speed_class: " << speedClassName(s.targets.speed_class) << "\n";
  if (s.targets.scripted.empty()) {
    out << "  scripted: []\n";
  } else {
    out << "  scripted:\n";
    for (const auto& t : s.targets.scripted)
      out << "    - {appear_tick: " << t.appear_tick << ", disappear_tick: " << t.disappear_tick
          << ", x: " << num(t.position.x) << ", y: " << num(t.position.y) << ", vx: " << num(t.velocity.x)
          << ", vy: " << num(t.velocity.y)
          << (t.sensing_range > 0.0 ? ", sensing_range: " + num(t.sensing_range) : std::string()) << "}\n";
  }
  out << "dynamics:\n"
      << "  delta: " << num(s.dynamics.delta) << "\n"
      << "  process_noise_sigma: " << num(s.dynamics.process_noise_sigma) << "\n";
  if (s.supernodes.empty()) {
    out << "supernodes: []\n";
  } else {
    out << "supernodes:\n";
    for (const auto& p : s.supernodes) out << "  - {x: " << num(p.x) << ", y: " << num(p.y) << "}\n";
  }
  out << "network:\n"
      << "  communication_range: " << num(s.network.communication_range) << "\n"
      << "  pte: " << num(s.network.pte) << "\n"
      << "  pde: " << num(s.network.pde) << "\n";
  out << "tracker:\n"
      << "  engine: " << quoted(s.tracker.engine) << "\n"
      << "  window_size: " << s.tracker.window_size << "\n";
  if (s.tracker.params.empty()) {
    out << "  params: {}\n";
  } else {
    out << "  params:\n";
    for (const auto& [name, param] : s.tracker.params)
      out << "    " << keyText(name) << ": " << num(param.value) << "\n";
  }
  out << "aggregator:\n"
      << "  association: " << quoted(s.aggregator.association) << "\n";
  if (s.aggregator.params.empty()) {
    out << "  params: {}\n";
  } else {
    out << "  params:\n";
    for (const auto& [name, param] : s.aggregator.params)
      out << "    " << keyText(name) << ": " << num(param.value) << "\n";
  }
  out << "metrics:\n"
      << "  ospa_c: " << num(s.metrics.ospa_c) << "\n"
      << "  ospa_p: " << num(s.metrics.ospa_p) << "\n"
      << "  gospa_c: " << num(s.metrics.gospa_c) << "\n"
      << "  gospa_p: " << num(s.metrics.gospa_p) << "\n"
      << "  mot_threshold: " << num(s.metrics.mot_threshold) << "\n"
      << "  quality_gate: " << num(s.metrics.quality_gate) << "\n"
      << "  boundary_band: " << num(s.metrics.boundary_band) << "\n";
  out << "run:\n"
      << "  ticks: " << s.run.ticks << "\n"
      << "  seed: " << s.run.seed << "\n"
      << "  node_processes: " << s.run.node_processes << "\n"
      << "  max_ticks_in_flight: " << s.run.max_ticks_in_flight << "\n";
  return out.str();
}

}  // namespace wsn::common

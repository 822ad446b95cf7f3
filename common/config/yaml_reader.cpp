#include "common/config/yaml_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

namespace wsn::common::config {
namespace {

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
  if (result.ec != std::errc{} || result.ptr != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
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

/// A plain scalar, or one explicitly tagged as a number (!!int, !!float); quoted or otherwise
/// tagged scalars are strings.
bool isPlainOrNumericTag(const YAML::Node& node) {
  const std::string& tag = node.Tag();
  return tag == "?" || tag == "tag:yaml.org,2002:int" || tag == "tag:yaml.org,2002:float";
}

/// "at the top level" or "in 'path'", for messages about keys.
std::string where(const std::string& path) { return path.empty() ? "at the top level" : "in '" + path + "'"; }

}  // namespace

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
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

void Reader::fail(int line, const std::string& message) const {
  throw ScenarioError(file_ + ":" + std::to_string(std::max(line, 1)) + ": " + message);
}

int Reader::lineOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? 0 : mark.line + 1;
}

int Reader::lineOf(const Entry& entry) {
  if (entry.value.IsNull() || lineOf(entry.value) == 0) return lineOf(entry.key);
  return lineOf(entry.value);
}

Section Reader::section(const YAML::Node& node, int line, const std::string& path,
                        std::vector<std::string> names) const {
  Section s;
  s.path = path;
  s.line = std::max(line, 1);
  std::sort(names.begin(), names.end());
  if (!node.IsDefined() || node.IsNull()) return s;
  if (!node.IsMap()) {
    if (path.empty())
      fail(s.line, "a scenario must be a mapping of sections (" + join(names) + "), got " + describe(node));
    fail(s.line,
         "'" + path + "' must be a mapping" + (names.empty() ? "" : " of " + join(names)) + ", got " + describe(node));
  }
  for (auto it = node.begin(); it != node.end(); ++it) {
    const YAML::Node key = it->first;
    const int key_line = lineOf(key) > 0 ? lineOf(key) : s.line;
    if (!key.IsScalar()) fail(key_line, "keys " + where(path) + " must be plain names, got " + describe(key));
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

double Reader::numberValue(const Entry& entry, const std::string& path, const Range& range) const {
  const double value = anyNumber(entry, path);
  if (!range.contains(value))
    fail(lineOf(entry), "'" + path + "' must be in " + range.text() + ", got " + entry.value.Scalar());
  return value;
}

double Reader::anyNumber(const Entry& entry, const std::string& path) const {
  const YAML::Node& node = entry.value;
  std::optional<double> value;
  if (node.IsScalar() && isPlainOrNumericTag(node)) value = parseDouble(node.Scalar());
  if (!value) fail(lineOf(entry), "'" + path + "' must be a number, got " + describe(node));
  return *value;
}

std::int64_t Reader::integerValue(const Entry& entry, const std::string& path, const IntRange& range) const {
  const long double value = whole(entry, path);
  if (value < static_cast<long double>(range.lo) || value > static_cast<long double>(range.hi))
    fail(lineOf(entry), "'" + path + "' must be in " + range.text() + ", got " + entry.value.Scalar());
  return static_cast<std::int64_t>(value);
}

std::uint64_t Reader::unsigned64Value(const Entry& entry, const std::string& path) const {
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

std::string Reader::textValue(const Entry& entry, const std::string& path) const {
  if (!entry.value.IsScalar()) fail(lineOf(entry), "'" + path + "' must be a string, got " + describe(entry.value));
  return entry.value.Scalar();
}

int Reader::choiceIndex(const Entry& entry, const std::string& path, const std::vector<std::string>& choices) const {
  const YAML::Node& node = entry.value;
  if (node.IsScalar()) {
    const auto it = std::find(choices.begin(), choices.end(), node.Scalar());
    if (it != choices.end()) return static_cast<int>(it - choices.begin());
  }
  fail(lineOf(entry), "'" + path + "' must be one of: " + join(choices) + "; got " + describe(node));
}

void Reader::require(const Section& s, std::initializer_list<const char*> keys, const std::string& what) const {
  for (const char* key : keys)
    if (s.find(key) == nullptr) fail(s.line, "'" + s.path + "' needs '" + key + "' (" + what + ")");
}

long double Reader::whole(const Entry& entry, const std::string& path) const {
  const YAML::Node& node = entry.value;
  bool is_number = false;
  std::optional<long double> value;
  if (node.IsScalar() && isPlainOrNumericTag(node)) value = parseWhole(node.Scalar(), is_number);
  if (!value)
    fail(lineOf(entry),
         "'" + path + "' must be an integer, got " + (is_number ? "the fraction " + node.Scalar() : describe(node)));
  return *value;
}

}  // namespace wsn::common::config

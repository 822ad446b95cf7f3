// The one description of a configuration section: for each key its member, kind, unit, range,
// default and meaning. Readers (the YAML scenario loader, the engine parameter check), the
// resolved-scenario writer, `wsntrack components` and the key tables of scenarios/README.md
// are all driven by these tables, so a key is described once. No YAML and no I/O here.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace wsn::common {
struct Scenario;  // a derived default may depend on any section read before (common/scenario_config.hpp)
}  // namespace wsn::common

namespace wsn::common::config {

/// Shortest decimal text that reads back to the same double ("0.3", "9.75", "100", "1e+06").
std::string shortestNumber(double value);
/// For messages and docs: shortest text with a compact exponent ("1e6" rather than "1e+06").
std::string compactNumber(double value);
/// For YAML files: shortest round-trip text that every YAML reader takes for a float (YAML 1.1
/// readers want a dot in the mantissa of an exponent form: "1.0e+06").
std::string yamlNumber(double value);
/// A double-quoted YAML string (escapes quote, backslash and control characters).
std::string yamlQuoted(const std::string& text);

/// A real interval with open or closed ends, printed as in messages: "(0, 1e6]".
struct Range {
  double lo = 0.0;
  double hi = 0.0;
  bool lo_open = false;
  bool hi_open = false;
  bool contains(double v) const { return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi); }
  std::string text() const {
    return std::string(lo_open ? "(" : "[") + compactNumber(lo) + ", " + compactNumber(hi) + (hi_open ? ")" : "]");
  }
};

constexpr Range closed(double lo, double hi) { return {lo, hi, false, false}; }
constexpr Range openClosed(double lo, double hi) { return {lo, hi, true, false}; }
constexpr Range closedOpen(double lo, double hi) { return {lo, hi, false, true}; }

// The ranges most keys share: lengths, rates and probabilities.
inline constexpr Range kPositive = openClosed(0.0, 1e6);
inline constexpr Range kNonNegative = closed(0.0, 1e6);
inline constexpr Range kProbability = closed(0.0, 1.0);

/// What kind of value a key holds (and so how it is read and written).
enum class FieldKind {
  kReal,        ///< a finite real number in `range`
  kInteger,     ///< a whole number in the closed `range`
  kUnsigned64,  ///< a whole number in [0, 2^64 - 1] (seeds), held exactly
  kText,        ///< any string, written quoted
  kChoice,      ///< one of `choices`, written plain
  kNested,      ///< a mapping or list read by its own code (a sub-section, a list of items)
};

/// One key of a section of configuration type C.
template <typename C>
struct Field {
  std::string key;
  FieldKind kind = FieldKind::kReal;
  std::string unit;  ///< "" when the value has no unit
  std::string doc;   ///< what the value means, with the paper's symbol and section
  Range range;       ///< kReal, kInteger
  std::vector<std::string> choices;  ///< kChoice
  /// Docs only: a range column richer than `range` ("inside the region"); "" to print `range`.
  std::string range_note;
  /// Docs only: the default column when it is not C{}'s value (e.g. a value the loader derives).
  std::string default_note;
  /// A number whose 0, or a choice whose first name, means "not given" (a target's own sensing
  /// range, its class): list items leave it out.
  bool zero_means_unset = false;
  /// A default derived from other values when the key is left out (kReal, kInteger): how, in
  /// words for the resolved file and the docs, and the function. The loader runs it after the
  /// section (and every section before it) is read; the resolved scenario.yaml records the value
  /// with "# derived: <derivation>".
  std::string derivation;
  std::function<double(const C& section, const Scenario& scenario)> derive;

  // Accessors: exactly the pair of the field's kind is set.
  std::function<double(const C&)> get_number;  ///< kReal, kInteger
  std::function<void(C&, double)> set_number;
  std::function<std::uint64_t(const C&)> get_unsigned;  ///< kUnsigned64
  std::function<void(C&, std::uint64_t)> set_unsigned;
  std::function<std::string(const C&)> get_text;  ///< kText, kChoice (the choice's name)
  std::function<void(C&, const std::string&)> set_text;

  bool isNumber() const { return kind == FieldKind::kReal || kind == FieldKind::kInteger; }

  /// Whether a list item leaves this key out: a nested key (written by its own code) or a value
  /// that means "not given".
  bool leftOutOfItem(const C& config) const {
    if (kind == FieldKind::kNested) return true;
    if (!zero_means_unset) return false;
    if (isNumber()) return get_number(config) == 0.0;
    return kind == FieldKind::kChoice && get_text(config) == choices.front();
  }

  /// The value as written in a resolved YAML file.
  std::string yamlValue(const C& config) const {
    switch (kind) {
      case FieldKind::kReal: return yamlNumber(get_number(config));
      case FieldKind::kInteger: return std::to_string(std::llround(get_number(config)));
      case FieldKind::kUnsigned64: return std::to_string(get_unsigned(config));
      case FieldKind::kText: return yamlQuoted(get_text(config));
      case FieldKind::kChoice: return get_text(config);
      case FieldKind::kNested: break;
    }
    return {};
  }

  /// The range column of the docs.
  std::string rangeText() const {
    if (!range_note.empty()) return range_note;
    switch (kind) {
      case FieldKind::kReal: return range.text();
      case FieldKind::kInteger: return "[" + compactNumber(range.lo) + ", " + compactNumber(range.hi) + "]";
      case FieldKind::kUnsigned64: return "[0, 2^64 − 1]";
      case FieldKind::kText: return "any text";
      case FieldKind::kChoice: {
        std::string out;
        for (const auto& c : choices) out += (out.empty() ? "`" : ", `") + c + "`";
        return out;
      }
      case FieldKind::kNested: break;
    }
    return {};
  }

  /// The default column of the docs: C{}'s value unless default_note says otherwise.
  std::string defaultText() const {
    if (!default_note.empty()) return default_note;
    if (!derivation.empty()) return derivation;
    const C defaults{};
    switch (kind) {
      case FieldKind::kReal:
      case FieldKind::kInteger: return compactNumber(get_number(defaults));
      case FieldKind::kUnsigned64: return std::to_string(get_unsigned(defaults));
      case FieldKind::kText:
      case FieldKind::kChoice: return "`" + get_text(defaults) + "`";
      case FieldKind::kNested: break;
    }
    return {};
  }
};

/// The fields of one section, in the order the resolved file writes them.
template <typename C>
struct FieldTable {
  std::string section;  ///< dotted path of the section ("network", "tracker.params")
  std::vector<Field<C>> fields;

  const Field<C>* find(const std::string& key) const {
    for (const auto& f : fields)
      if (f.key == key) return &f;
    return nullptr;
  }
  /// "a, b, c": the keys in table order.
  std::string keys() const {
    std::string out;
    for (const auto& f : fields) out += (out.empty() ? "" : ", ") + f.key;
    return out;
  }
  /// The keys sorted by name, as messages about an unknown key list them.
  std::vector<std::string> sortedKeys() const;
};

template <typename C>
std::vector<std::string> FieldTable<C>::sortedKeys() const {
  std::vector<std::string> out;
  for (const auto& f : fields) out.push_back(f.key);
  std::sort(out.begin(), out.end());
  return out;
}

// ---------------------------------------------------------------------------------------------
// Building fields. `ref` is a member pointer (double C::*) or a callable C& -> T& reaching a
// nested member (position.x).

namespace detail {
template <typename C, typename Ref>
decltype(auto) access(const Ref& ref, C& config) {
  if constexpr (std::is_member_object_pointer_v<Ref>)
    return (config.*ref);
  else
    return ref(config);
}
}  // namespace detail

/// A real number in `range`.
template <typename C, typename Ref>
Field<C> real(std::string key, Ref ref, Range range, std::string unit, std::string doc) {
  Field<C> f;
  f.key = std::move(key);
  f.kind = FieldKind::kReal;
  f.range = range;
  f.unit = std::move(unit);
  f.doc = std::move(doc);
  f.get_number = [ref](const C& c) { return static_cast<double>(detail::access(ref, const_cast<C&>(c))); };
  f.set_number = [ref](C& c, double v) { detail::access(ref, c) = v; };
  return f;
}

/// A whole number in [lo, hi], held in an integer (or, for engine parameters, double) member.
template <typename C, typename Ref>
Field<C> integer(std::string key, Ref ref, double lo, double hi, std::string unit, std::string doc) {
  Field<C> f;
  f.key = std::move(key);
  f.kind = FieldKind::kInteger;
  f.range = closed(lo, hi);
  f.unit = std::move(unit);
  f.doc = std::move(doc);
  f.get_number = [ref](const C& c) { return static_cast<double>(detail::access(ref, const_cast<C&>(c))); };
  f.set_number = [ref](C& c, double v) {
    auto& member = detail::access(ref, c);
    member = static_cast<std::remove_reference_t<decltype(member)>>(v);
  };
  return f;
}

/// A whole number in [0, 2^64 - 1], held exactly.
template <typename C, typename Ref>
Field<C> unsigned64(std::string key, Ref ref, std::string unit, std::string doc) {
  Field<C> f;
  f.key = std::move(key);
  f.kind = FieldKind::kUnsigned64;
  f.unit = std::move(unit);
  f.doc = std::move(doc);
  f.get_unsigned = [ref](const C& c) { return detail::access(ref, const_cast<C&>(c)); };
  f.set_unsigned = [ref](C& c, std::uint64_t v) { detail::access(ref, c) = v; };
  return f;
}

/// Any string.
template <typename C, typename Ref>
Field<C> text(std::string key, Ref ref, std::string doc) {
  Field<C> f;
  f.key = std::move(key);
  f.kind = FieldKind::kText;
  f.doc = std::move(doc);
  f.get_text = [ref](const C& c) { return detail::access(ref, const_cast<C&>(c)); };
  f.set_text = [ref](C& c, const std::string& v) { detail::access(ref, c) = v; };
  return f;
}

/// One of `names`; names[i] stands for the enumerator with value i (enums are declared in the
/// same order), or, for a string member, for itself.
template <typename C, typename Ref>
Field<C> choice(std::string key, Ref ref, std::vector<std::string> names, std::string doc) {
  Field<C> f;
  f.key = std::move(key);
  f.kind = FieldKind::kChoice;
  f.choices = names;
  f.doc = std::move(doc);
  using Member = std::remove_cvref_t<decltype(detail::access(ref, std::declval<C&>()))>;
  if constexpr (std::is_enum_v<Member>) {
    f.get_text = [ref, names](const C& c) {
      const auto index = static_cast<std::size_t>(detail::access(ref, const_cast<C&>(c)));
      return index < names.size() ? names[index] : std::string("?");
    };
    f.set_text = [ref, names](C& c, const std::string& v) {
      for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == v) {
          detail::access(ref, c) = static_cast<Member>(i);
          return;
        }
      throw std::invalid_argument("'" + v + "' is not a choice");
    };
  } else {
    f.get_text = [ref](const C& c) { return detail::access(ref, const_cast<C&>(c)); };
    f.set_text = [ref](C& c, const std::string& v) { detail::access(ref, c) = v; };
  }
  return f;
}

/// A key holding a mapping or a list that its section reads with its own code; in the table so
/// that the key is allowed and documented in its place. `unit` describes its shape.
template <typename C>
Field<C> nested(std::string key, std::string shape, std::string default_note, std::string range_note,
                std::string doc) {
  Field<C> f;
  f.key = std::move(key);
  f.kind = FieldKind::kNested;
  f.unit = std::move(shape);
  f.default_note = std::move(default_note);
  f.range_note = std::move(range_note);
  f.doc = std::move(doc);
  return f;
}

/// The fields of `table` as fields of a struct Outer that holds an Inner at `ref` (a component
/// whose parameters are another component's plus its own).
template <typename Outer, typename Inner, typename Ref>
std::vector<Field<Outer>> lift(const FieldTable<Inner>& table, Ref ref) {
  std::vector<Field<Outer>> out;
  for (const auto& f : table.fields) {
    Field<Outer> g;
    g.key = f.key;
    g.kind = f.kind;
    g.unit = f.unit;
    g.doc = f.doc;
    g.range = f.range;
    g.choices = f.choices;
    g.range_note = f.range_note;
    g.default_note = f.default_note;
    g.zero_means_unset = f.zero_means_unset;
    const auto inner = [ref](const Outer& o) -> Inner& { return detail::access(ref, const_cast<Outer&>(o)); };
    if (f.get_number) g.get_number = [inner, get = f.get_number](const Outer& o) { return get(inner(o)); };
    if (f.set_number) g.set_number = [inner, set = f.set_number](Outer& o, double v) { set(inner(o), v); };
    if (f.get_unsigned) g.get_unsigned = [inner, get = f.get_unsigned](const Outer& o) { return get(inner(o)); };
    if (f.set_unsigned) g.set_unsigned = [inner, set = f.set_unsigned](Outer& o, std::uint64_t v) { set(inner(o), v); };
    if (f.get_text) g.get_text = [inner, get = f.get_text](const Outer& o) { return get(inner(o)); };
    if (f.set_text) g.set_text = [inner, set = f.set_text](Outer& o, const std::string& v) { set(inner(o), v); };
    out.push_back(std::move(g));
  }
  return out;
}

/// Gives a number field a default derived from the scenario when the key is left out.
template <typename C, typename F>
Field<C> derivedDefault(Field<C> f, std::string derivation, F derive) {
  f.derivation = std::move(derivation);
  f.derive = std::move(derive);
  return f;
}

/// Sets documentation-only columns on a field built above.
template <typename C>
Field<C> withNotes(Field<C> f, std::string range_note, std::string default_note = "") {
  f.range_note = std::move(range_note);
  f.default_note = std::move(default_note);
  return f;
}

/// One field as the docs show it: the Markdown key tables and `wsntrack components` read the same rows.
struct FieldDoc {
  std::string key;
  std::string unit;  ///< "" when the value has no unit
  std::string default_text;
  std::string range_text;
  std::string doc;
};

/// A table's rows for the docs: `marker` names it in scenarios/README.md, `section` is the
/// dotted path of its keys in a scenario ("sensor_model.acoustic").
struct KeyTable {
  std::string marker;
  std::string section;
  std::vector<FieldDoc> fields;
};

template <typename C>
KeyTable keyTable(std::string marker, std::string section, const FieldTable<C>& table) {
  KeyTable out{std::move(marker), std::move(section), {}};
  for (const auto& f : table.fields) out.fields.push_back({f.key, f.unit, f.defaultText(), f.rangeText(), f.doc});
  return out;
}

/// Rows as Markdown: | key | unit | default | range | meaning |.
inline std::string markdownTable(const std::vector<FieldDoc>& rows) {
  std::string out = "| key | unit | default | range | meaning |\n|-----|------|---------|-------|---------|\n";
  for (const auto& f : rows)
    out += "| `" + f.key + "` | " + (f.unit.empty() ? "—" : f.unit) + " | " + f.default_text + " | " + f.range_text +
           " | " + f.doc + " |\n";
  return out;
}

/// The table as Markdown.
template <typename C>
std::string markdownTable(const FieldTable<C>& table) {
  return markdownTable(keyTable("", "", table).fields);
}

}  // namespace wsn::common::config

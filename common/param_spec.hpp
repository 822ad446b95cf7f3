// Numeric parameters of a pluggable component chosen by name in the scenario (a supernode tracking
// engine, the aggregator's track association): each component describes its typed parameter
// struct once, as a field table (common/config/field_table.hpp); from it come the listing, the
// strict check that fills in defaults, and the typed struct the component runs with.
#pragma once

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <map>
#include <string>
#include <vector>

#include "common/config/field_table.hpp"
#include "common/observation_statistics.hpp"
#include "common/scenario_config.hpp"
#include "common/scenario_error.hpp"

namespace wsn::common {

/// How a parameter with a physical meaning follows the scenario when the file leaves it out (or
/// writes `auto`): a summary for the docs, and the derivation from the scenario's statistics and
/// the parameters resolved before it (every fixed one, and the derived ones listed earlier).
/// The statistics a derivation reads, measured on first use (the measurement simulates the
/// sensor field, so a scenario whose derivations do not need them never pays for it).
using StatisticsSource = std::function<const ObservationStatistics&()>;

struct ParamDerivation {
  std::string summary;
  std::function<Derived(const StatisticsSource& statistics, const std::map<std::string, EngineParam>& resolved)>
      derive;
};

/// No statistics: every derived parameter takes its table default. For code that fixes the model
/// on purpose (unit tests of an algorithm at given parameters, benchmarks); a run never uses it.
inline const StatisticsSource kNoStatistics{};

/// A numeric parameter with its default (fixed, or derived from the scenario) and admissible range.
struct ParamSpec {
  std::string name;
  double default_value = 0.0;
  double min = 0.0;
  double max = 0.0;
  std::string description;
  bool integer = false;  ///< the value must be a whole number (a count)
  std::string unit;      ///< "" when it has none
  /// Set when the default is derived from the scenario; default_value is then only the fallback
  /// of a scenario resolved without statistics (none is, outside unit tests of other things).
  ParamDerivation derivation;
  bool derived() const { return static_cast<bool>(derivation.derive); }
};

/// The parameters of a field table over P, as listed and checked; defaults are P{}'s except
/// for the keys of `derivations`, which follow the scenario. A derivation for a key the table
/// does not have is a programming error (std::logic_error).
template <typename P>
std::vector<ParamSpec> paramSpecs(const config::FieldTable<P>& table,
                                  const std::map<std::string, ParamDerivation>& derivations = {}) {
  std::vector<ParamSpec> specs;
  const P defaults{};
  for (const auto& f : table.fields) {
    ParamSpec spec{f.key, f.get_number(defaults), f.range.lo, f.range.hi, f.doc,
                   f.kind == config::FieldKind::kInteger, f.unit, {}};
    if (const auto it = derivations.find(f.key); it != derivations.end()) spec.derivation = it->second;
    specs.push_back(std::move(spec));
  }
  // Not a structured binding: clang before 16 cannot capture one in a lambda (the fuzzers' build).
  for (const auto& derivation : derivations) {
    const std::string& key = derivation.first;
    if (std::none_of(specs.begin(), specs.end(), [&](const ParamSpec& p) { return p.name == key; }))
      throw std::logic_error("derivation for '" + key + "', which '" + table.section + "' does not have");
  }
  return specs;
}

/// The typed parameters from resolved params (resolveParams filled in every default): each key
/// of the table is read from its own entry. A key missing from `params` is a programming error
/// (the params were not resolved against this table), never a silent default.
template <typename P>
P decodeParams(const config::FieldTable<P>& table, const std::map<std::string, EngineParam>& params, P base = P{}) {
  for (const auto& f : table.fields) {
    const auto it = params.find(f.key);
    if (it == params.end())
      throw std::logic_error("parameter '" + f.key + "' of '" + table.section + "' was not resolved");
    f.set_number(base, it->second.value);
  }
  return base;
}

/// Checks `params`, read from the scenario's `section` (e.g. "tracker.params"), against the
/// `specs` of `owner` (e.g. "engine 'mcmcda'") and adds every missing parameter: a derived one
/// from `statistics` (clamped to its range, a count rounded up; how it was derived goes to
/// derived["section.name"]), any other with its default. Throws ScenarioError
/// "source_path:line: ..." for an unknown name, a value out of range or a fraction where a count
/// is expected; names are checked in sorted order, so the first error reported does not depend on
/// the order of keys in the file.
void resolveParams(const std::string& source_path, const std::string& section, const std::string& owner,
                   const std::vector<ParamSpec>& specs, std::map<std::string, EngineParam>& params,
                   const StatisticsSource& statistics = {}, std::map<std::string, std::string>* derived = nullptr);

}  // namespace wsn::common

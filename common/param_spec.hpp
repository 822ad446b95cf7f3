// Numeric parameters of a pluggable component chosen by name in the scenario (a supernode tracking
// engine, the aggregator's track association): each component describes its typed parameter
// struct once, as a field table (common/config/field_table.hpp); from it come the listing, the
// strict check that fills in defaults, and the typed struct the component runs with.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/config/field_table.hpp"
#include "common/scenario.hpp"

namespace wsn::common {

/// A numeric parameter with its paper default and admissible range.
struct ParamSpec {
  std::string name;
  double default_value = 0.0;
  double min = 0.0;
  double max = 0.0;
  std::string description;
  bool integer = false;  ///< the value must be a whole number (a count)
  std::string unit;      ///< "" when it has none
};

/// The parameters of a field table over P, as listed and checked; defaults are P{}'s unless
/// `defaults` says otherwise.
template <typename P>
std::vector<ParamSpec> paramSpecs(const config::FieldTable<P>& table, const P& defaults = P{}) {
  std::vector<ParamSpec> specs;
  for (const auto& f : table.fields)
    specs.push_back({f.key, f.get_number(defaults), f.range.lo, f.range.hi, f.doc,
                     f.kind == config::FieldKind::kInteger, f.unit});
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
/// `specs` of `owner` (e.g. "engine 'mcmcda'") and adds every missing parameter with its default.
/// Throws ScenarioError "source_path:line: ..." for an unknown name, a value out of range or a
/// fraction where a count is expected; names are checked in sorted order, so the first error
/// reported does not depend on the order of keys in the file.
void resolveParams(const std::string& source_path, const std::string& section, const std::string& owner,
                   const std::vector<ParamSpec>& specs, std::map<std::string, EngineParam>& params);

}  // namespace wsn::common

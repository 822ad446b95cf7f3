#include "common/param_spec.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wsn::common {

void resolveParams(const std::string& source_path, const std::string& section, const std::string& owner,
                   const std::vector<ParamSpec>& specs, std::map<std::string, EngineParam>& params,
                   const StatisticsSource& statistics, std::map<std::string, std::string>* derived) {
  const auto where = [&](int line) { return source_path + ":" + std::to_string(line) + ": "; };
  for (const auto& [name, param] : params) {
    // An init-capture: clang before 16 cannot capture a structured binding (the fuzzers' build).
    const auto it = std::find_if(specs.begin(), specs.end(), [&wanted = name](const ParamSpec& p) { return p.name == wanted; });
    if (it == specs.end()) {
      std::string names;
      for (const auto& p : specs) names += (names.empty() ? "" : ", ") + p.name;
      throw ScenarioError(where(param.line) + "unknown parameter '" + name + "' for " + owner +
                          "; expected one of: " + (names.empty() ? "(none)" : names));
    }
    if (param.automatic) continue;  // a known name asking for its default: nothing to range-check
    const double v = param.value;
    if (!(v >= it->min && v <= it->max))  // also rejects NaN
      throw ScenarioError(where(param.line) + "'" + section + "." + name + "' must be in [" + config::compactNumber(it->min) +
                          ", " + config::compactNumber(it->max) + "], got " + config::compactNumber(v));
    if (it->integer && v != std::floor(v))
      throw ScenarioError(where(param.line) + "'" + section + "." + name + "' must be a whole number, got " +
                          config::compactNumber(v));
  }
  std::erase_if(params, [](const auto& entry) { return entry.second.automatic; });
  // Fixed defaults first, so that a derivation can read any of them; then the derived ones in
  // table order, each seeing those before it.
  std::vector<const ParamSpec*> to_derive;
  for (const auto& p : specs) {
    if (params.contains(p.name)) continue;
    if (p.derived() && statistics)
      to_derive.push_back(&p);
    else
      params[p.name] = EngineParam{p.default_value, 0};
  }
  for (const ParamSpec* p : to_derive) {
    Derived d;
    try {
      d = p->derivation.derive(statistics, params);
    } catch (const std::out_of_range&) {  // it read a derived parameter listed after it
      throw std::logic_error("the derivation of '" + section + "." + p->name + "' of " + owner +
                             " reads a parameter that is derived after it: list it later in the table");
    }
    double value = std::isfinite(d.value) ? d.value : p->default_value;
    if (p->integer) value = std::ceil(value - 1e-9);
    const double clamped = std::clamp(value, p->min, p->max);
    params[p->name] = EngineParam{clamped, 0};
    if (derived != nullptr)
      (*derived)[section + "." + p->name] =
          d.how + (clamped != value ? " = " + config::compactNumber(value) + ", kept in range" : "");
  }
}

}  // namespace wsn::common

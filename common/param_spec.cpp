#include "common/param_spec.hpp"

#include <algorithm>
#include <cmath>

namespace wsn::common {

void resolveParams(const std::string& source_path, const std::string& section, const std::string& owner,
                   const std::vector<ParamSpec>& specs, std::map<std::string, EngineParam>& params) {
  const auto where = [&](int line) { return source_path + ":" + std::to_string(line) + ": "; };
  for (const auto& [name, param] : params) {
    const auto it = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& p) { return p.name == name; });
    if (it == specs.end()) {
      std::string names;
      for (const auto& p : specs) names += (names.empty() ? "" : ", ") + p.name;
      throw ScenarioError(where(param.line) + "unknown parameter '" + name + "' for " + owner +
                          "; expected one of: " + (names.empty() ? "(none)" : names));
    }
    const double v = param.value;
    if (!(v >= it->min && v <= it->max))  // also rejects NaN
      throw ScenarioError(where(param.line) + "'" + section + "." + name + "' must be in [" + config::compactNumber(it->min) +
                          ", " + config::compactNumber(it->max) + "], got " + config::compactNumber(v));
    if (it->integer && v != std::floor(v))
      throw ScenarioError(where(param.line) + "'" + section + "." + name + "' must be a whole number, got " +
                          config::compactNumber(v));
  }
  for (const auto& p : specs)
    if (!params.contains(p.name)) params[p.name] = EngineParam{p.default_value, 0};
}

}  // namespace wsn::common

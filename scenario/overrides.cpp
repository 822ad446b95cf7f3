// Command-line overrides (--set KEY=VALUE). They are set in the YAML tree of the file as written,
// not in the resolved scenario, so that what the loader derives from other values (beta from Rs,
// the default supernode from the region, engine defaults from the engine) follows them as after
// an edit; a problem they cause is blamed on the overrides that reproduce it.
#include "scenario/overrides.hpp"

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <charconv>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "common/config/yaml_documents.hpp"
#include "common/config/yaml_reader.hpp"
#include "scenario/document.hpp"

namespace wsn::scenario {
namespace {

using common::Scenario;
using common::ScenarioError;
using common::config::describe;

/// One step of a key's path: a mapping key, or an item of a list.
struct PathStep {
  std::string key;  ///< empty for a list item
  std::size_t index = 0;
};

/// "supernodes[1].x" -> supernodes, [1], x. Names are anything but '.', '[' and ']'.
std::vector<PathStep> keyPath(const ScenarioOverride& o) {
  const auto bad = [&o]() {
    throw OverrideError(o.text() +
                        ": KEY must be a dotted path of names, list items as name[i] "
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
  common::config::YamlDocuments documents;
  try {
    documents = common::config::readYamlDocuments(o.value);
  } catch (const YAML::Exception& error) {
    throw OverrideError(o.text() + ": VALUE is not valid YAML (" + error.msg + "); quote it to make it a string");
  }
  if (documents.count == 0) return YAML::Node(YAML::NodeType::Null);
  if (documents.count > 1 || documents.first.IsMap() || documents.first.IsSequence())
    throw OverrideError(o.text() + ": VALUE must be a single value such as 0.4 or gnn, got " +
                        (documents.count > 1 ? std::string("several YAML documents") : describe(documents.first)) +
                        "; lists and mappings belong in the scenario file");
  return documents.first;
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

/// Sets one override in the tree of a file (an empty file becomes an empty mapping first).
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

/// The scenario of a tree, with the checks of other modules run on it.
Scenario validateTree(const YAML::Node& root, const std::string& name, const ScenarioCheck& check) {
  Scenario s = scenarioFromDocument(root, name);
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
    YAML::Node tree = parseScenarioDocument(yaml_text, name_for_errors);
    if (tree.IsDefined() && !tree.IsNull() && !tree.IsMap()) scenarioFromDocument(tree, name_for_errors);  // throws
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

Scenario loadScenario(const std::string& path, const std::vector<ScenarioOverride>& overrides,
                      const ScenarioCheck& check) {
  return applyOverrides(readScenarioFile(path), path, overrides, check);
}

}  // namespace wsn::scenario

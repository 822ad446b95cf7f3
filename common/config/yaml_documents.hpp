// The documents of a YAML text, read without yaml-cpp 0.7's YAML::LoadAll, which loops without end
// (allocating as it goes) on some malformed input such as `"a", b` (yaml-cpp PR #1319, not in
// Debian 12's 0.7): the scenario fuzzer found it, and a scenario file or --set value must give an
// error, never hang.
#pragma once

#include <cstddef>
#include <string>

#include <yaml-cpp/yaml.h>

namespace wsn::common::config {

/// The first document of `text` (null for an empty text), as YAML::LoadAll's first would be, and
/// what follows it.
struct YamlDocuments {
  YAML::Node first;
  std::size_t count = 0;        ///< documents, empty ones included (LoadAll's size)
  int later_content_line = 0;   ///< 1-based line of the first later document that is not null; 0 if none
};

/// Parses every document of `text`. Throws YAML::ParserException (with the mark of the trouble) for
/// invalid YAML, including a text on which the parser stops making progress.
YamlDocuments readYamlDocuments(const std::string& text);

}  // namespace wsn::common::config

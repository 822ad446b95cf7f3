#include "common/config/yaml_writer.hpp"

#include <algorithm>
#include <cctype>

namespace wsn::common::config {

std::string keyText(const std::string& name) {
  const bool null_word = name == "null" || name == "Null" || name == "NULL";
  const bool plain = !null_word && !name.empty() &&
                     (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                     std::all_of(name.begin(), name.end(),
                                 [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
  return plain ? name : yamlQuoted(name);
}

}  // namespace wsn::common::config

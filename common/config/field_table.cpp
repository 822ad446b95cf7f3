#include "common/config/field_table.hpp"

#include <charconv>
#include <cstdio>

namespace wsn::common::config {

std::string shortestNumber(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

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

std::string yamlNumber(double value) {
  std::string text = shortestNumber(value);
  const auto e = text.find('e');
  if (e != std::string::npos && text.find('.') == std::string::npos) text.insert(e, ".0");
  return text;
}

std::string yamlQuoted(const std::string& text) {
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

}  // namespace wsn::common::config

#include "common/output.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace wsn::common {

// std::to_chars with a precision writes what printf("%.*f") and ("%.*g") write in the C locale,
// correctly rounded from the exact binary value, at a fraction of glibc printf's cost: a city-scale
// run writes millions of these a minute (tracks.csv, observations.csv). Non-finite values keep
// printf's spelling.

std::string significant9(double value) {
  char buffer[64];
  if (!std::isfinite(value)) {
    std::snprintf(buffer, sizeof buffer, "%.9g", value);
    return buffer;
  }
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value == 0.0 ? 0.0 : value,  // no "-0"
                                 std::chars_format::general, 9).ptr;
  return std::string(buffer, end);
}

std::string fixed6(double value) {
  char buffer[400];  // 1e308 in fixed notation has 309 digits before the point
  if (!std::isfinite(value)) {
    std::snprintf(buffer, sizeof buffer, "%.6f", value);
    return buffer;
  }
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value == 0.0 ? 0.0 : value,
                                 std::chars_format::fixed, 6).ptr;
  std::string text(buffer, end);
  if (text == "-0.000000") text = "0.000000";  // a tiny negative rounds to it
  return text;
}

CsvFile::CsvFile(const std::string& path, const std::string& header) : path_(path), file_(std::fopen(path.c_str(), "w")) {
  if (file_ == nullptr) throw std::runtime_error(path + ": cannot write (" + std::strerror(errno) + ")");
  row(header);
}

CsvFile::~CsvFile() {
  if (file_ != nullptr) std::fclose(file_);
}

void CsvFile::row(const std::string& line) {
  if (file_ == nullptr) throw std::runtime_error(path_ + ": write after close");
  if (std::fputs(line.c_str(), file_) < 0 || std::fputc('\n', file_) == EOF)
    throw std::runtime_error(path_ + ": write failed (" + std::strerror(errno) + ")");
}

void CsvFile::close() {
  if (file_ == nullptr) return;
  const int rc = std::fclose(file_);
  file_ = nullptr;
  if (rc != 0) throw std::runtime_error(path_ + ": close failed (" + std::strerror(errno) + ")");
}

void writeTextFile(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp";
  std::FILE* file = std::fopen(temporary.c_str(), "w");
  if (file == nullptr) throw std::runtime_error(temporary + ": cannot write (" + std::strerror(errno) + ")");
  const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  if (std::fclose(file) != 0 || !written) throw std::runtime_error(temporary + ": write failed");
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
    throw std::runtime_error(path + ": rename failed (" + std::strerror(errno) + ")");
}

std::vector<std::string> splitCsvLine(const std::string& line) {
  std::vector<std::string> fields;
  std::string::size_type start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

}  // namespace wsn::common

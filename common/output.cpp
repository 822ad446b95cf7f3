#include "common/output.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace wsn::common {

std::string significant9(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.9g", value == 0.0 ? 0.0 : value);  // no "-0"
  return buffer;
}

std::string fixed6(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", value == 0.0 ? 0.0 : value);  // no "-0.000000"
  std::string text = buffer;
  if (text == "-0.000000") text = "0.000000";
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

}  // namespace wsn::common

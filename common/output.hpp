// Run-directory writers: CSV files with a fixed header and number format, and whole text
// files written atomically, so that equal runs give byte-identical files.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace wsn::common {

/// Formats a double with 6 decimals ("%.6f"): the fixed format of every CSV number.
std::string fixed6(double value);
/// value with 9 significant digits ("%.9g"): for quantities, such as covariances, whose scale
/// varies too much for a fixed number of decimals.
std::string significant9(double value);

/// A CSV file written row by row; throws std::runtime_error naming the path on I/O failure.
class CsvFile {
 public:
  CsvFile(const std::string& path, const std::string& header);
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;
  ~CsvFile();
  void row(const std::string& line);
  /// Flushes and closes, reporting errors (the destructor closes silently).
  void close();

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
};

/// The fields of one line of the run's CSV files (a header or a row: no quoting, no commas in a
/// field, as CsvFile writes them); an empty line is one empty field.
std::vector<std::string> splitCsvLine(const std::string& line);

/// Writes `text` to `path` via a temporary file and rename, so readers never see half a file.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace wsn::common

#include "launcher/rejections.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/dds/role_runtime.hpp"
#include "common/output.hpp"

namespace wsn::launcher {

std::uint64_t gatherRejections(const std::string& run_dir) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(run_dir) / dds::kRejectionsDirectory;
  std::vector<fs::path> files;
  std::error_code error;
  if (fs::is_directory(dir, error))
    for (const auto& entry : fs::directory_iterator(dir, error))
      if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());

  nlohmann::json processes = nlohmann::json::array();
  std::uint64_t total = 0;
  for (const auto& file : files) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    const auto parsed = nlohmann::json::parse(text.str(), nullptr, false);
    if (parsed.is_discarded() || !parsed.contains("rejected") || !parsed["rejected"].is_array()) {
      processes.push_back({{"file", file.filename().string()}, {"error", "not a role's record of rejections"}});
      ++total;
      continue;
    }
    for (const auto& item : parsed["rejected"])
      if (item.contains("count") && item["count"].is_number_unsigned()) total += item["count"].get<std::uint64_t>();
    processes.push_back(parsed);
  }
  const nlohmann::json record = {{"total", total}, {"processes", processes}};
  common::writeTextFile(run_dir + "/rejected.json", record.dump(2) + "\n");
  fs::remove_all(dir, error);
  return total;
}

}  // namespace wsn::launcher

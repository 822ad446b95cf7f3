#include "launcher/run_description.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "common/dds/cyclone_config.hpp"
#include "common/output.hpp"

namespace wsn::launcher {
namespace {

using Json = nlohmann::ordered_json;

/// A value on one line; an array's items separated by ", " as the sed of scripts expects
/// (`"viewer_participant_indices": [5, 8]`).
std::string oneLine(const Json& value) {
  if (!value.is_array()) return value.dump(-1, ' ', false, Json::error_handler_t::replace);
  std::string text = "[";
  for (const auto& item : value) text += (text.size() > 1 ? ", " : "") + oneLine(item);
  return text + "]";
}

std::string hex(std::uint64_t value) {
  std::ostringstream out;
  out << std::hex << value;
  return out.str();
}

/// run.json's values by key, each checked for its type; every error names the file and the key.
class Fields {
 public:
  Fields(const std::string& json, std::string path) : path_(std::move(path)) {
    json_ = Json::parse(json, nullptr, false);
    if (json_.is_discarded() || !json_.is_object()) throw std::runtime_error(path_ + ": not a JSON object");
  }

  const Json& at(const std::string& key, bool (Json::*is_kind)() const noexcept) const {
    const auto found = json_.find(key);
    if (found == json_.end() || !((*found).*is_kind)()) throw std::runtime_error(path_ + ": no valid \"" + key + "\"");
    return *found;
  }
  long long integer(const std::string& key) const { return at(key, &Json::is_number_integer).get<long long>(); }
  std::string text(const std::string& key) const { return at(key, &Json::is_string).get<std::string>(); }
  double number(const std::string& key) const { return at(key, &Json::is_number).get<double>(); }
  bool boolean(const std::string& key) const { return at(key, &Json::is_boolean).get<bool>(); }
  /// The value of an optional key written back as one line ("" when it is absent).
  std::string line(const std::string& key) const { return json_.contains(key) ? oneLine(json_.at(key)) : ""; }
  [[noreturn]] void invalid(const std::string& key) const { throw std::runtime_error(path_ + ": no valid \"" + key + "\""); }

 private:
  Json json_;
  std::string path_;
};

}  // namespace

std::string runDescriptionJson(const RunDescription& run) {
  Json json;
  json["run_id"] = hex(run.identity.run_id);
  json["domain"] = run.identity.domain;
  json["participants"] = run.participants;
  json["viewer_participant_indices"] = {run.first_viewer_index, run.first_viewer_index + run.viewer_slots - 1};
  json["scenario"] = run.scenario;
  json["ticks"] = run.ticks;
  json["processes"] = run.processes;
  json["tick_interval_s"] = run.tick_interval_s;
  json["in_process"] = run.in_process;
  json["launcher_pid"] = run.launcher_pid;
  if (!run.status.empty()) json["status"] = run.status;
  if (!run.reason.empty()) json["reason"] = run.reason;
  if (!run.provenance_json.empty()) json["provenance"] = Json::parse(run.provenance_json);
  std::string text = "{\n";
  for (auto item = json.begin(); item != json.end(); ++item)
    text += "  " + Json(item.key()).dump() + ": " + oneLine(item.value()) + (std::next(item) == json.end() ? "\n" : ",\n");
  return text + "}\n";
}

RunDescription parseRunDescription(const std::string& json, const std::string& path) {
  const Fields fields(json, path);
  RunDescription run;
  const std::string run_id = fields.text("run_id");
  if (run_id.empty() || run_id.size() > 16 || run_id.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
    fields.invalid("run_id");
  run.identity.run_id = std::stoull(run_id, nullptr, 16);
  run.identity.domain = static_cast<int>(fields.integer("domain"));
  run.participants = static_cast<int>(fields.integer("participants"));
  const auto& viewers = fields.at("viewer_participant_indices", &Json::is_array);
  if (viewers.size() != 2 || !viewers[0].is_number_unsigned() || !viewers[1].is_number_unsigned())
    fields.invalid("viewer_participant_indices");
  run.first_viewer_index = viewers[0].get<int>();
  run.viewer_slots = viewers[1].get<int>() - run.first_viewer_index + 1;
  run.scenario = fields.text("scenario");
  run.ticks = static_cast<std::int32_t>(fields.integer("ticks"));
  run.processes = static_cast<std::int32_t>(fields.integer("processes"));
  run.tick_interval_s = fields.number("tick_interval_s");
  run.in_process = fields.boolean("in_process");
  run.launcher_pid = fields.integer("launcher_pid");
  run.provenance_json = fields.line("provenance");
  // Optional: a run.json written before the status existed has none (status stays empty).
  if (!fields.line("status").empty()) run.status = fields.text("status");
  if (!fields.line("reason").empty()) run.reason = fields.text("reason");
  if (!run.status.empty() && run.status != kRunRunning && run.status != kRunComplete && run.status != kRunFailed)
    fields.invalid("status");
  if (run.identity.domain < 0 || run.identity.domain > dds::kMaxDomainId || run.viewer_slots < 1 || run.ticks < 1)
    throw std::runtime_error(path + ": values out of range");
  return run;
}

void writeRunDescription(const std::string& run_dir, const RunDescription& run) {
  // Written whole and renamed into place: a viewer never reads half a file.
  const std::string path = run_dir + "/run.json";
  common::writeTextFile(path + ".tmp", runDescriptionJson(run));
  std::error_code error;
  std::filesystem::rename(path + ".tmp", path, error);
  if (error) throw std::runtime_error(path + ": cannot write (" + error.message() + ")");
}

RunDescription readRunDescription(const std::string& run_dir) {
  const std::string path = run_dir + "/run.json";
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parseRunDescription(buffer.str(), path);
}

void markRun(const std::string& run_dir, const std::string& status, const std::string& reason) {
  RunDescription run = readRunDescription(run_dir);
  run.status = status;
  run.reason = reason.substr(0, reason.find('\n'));
  // A failure headline that introduces a log tail ends in ':'; on its own line it reads better without.
  while (!run.reason.empty() && (run.reason.back() == ':' || run.reason.back() == ' ')) run.reason.pop_back();
  writeRunDescription(run_dir, run);
}

}  // namespace wsn::launcher

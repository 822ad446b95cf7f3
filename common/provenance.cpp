#include "common/provenance.hpp"

#include <openssl/evp.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/version.hpp"

namespace wsn::common {
namespace {

std::string utcNow() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::array<char, 32> text{};
  std::strftime(text.data(), text.size(), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text.data();
}

std::string hostName() {
  std::array<char, 256> name{};
  if (gethostname(name.data(), name.size() - 1) != 0) return "unknown";
  return name.data();
}

}  // namespace

std::string sha256Hex(const std::string& bytes) {
  // OpenSSL's EVP interface: a maintained, audited digest rather than a hand-written one.
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest.data(), &length, EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("sha256: OpenSSL EVP_Digest failed");
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) {
    hex += kHex[digest[i] >> 4];
    hex += kHex[digest[i] & 0xf];
  }
  return hex;
}

std::string sha256OfFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read the scenario file to record its sha256");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error(path + ": read error while recording its sha256");
  return sha256Hex(bytes);
}

Provenance captureProvenance(const std::vector<std::string>& command_line, const std::string& scenario_file) {
  Provenance p;
  p.version = std::string(version::projectVersion());
  p.commit = version::commitWithState();
  p.cyclone_dds = std::string(version::cycloneDdsVersion());
  p.command_line = command_line;
  std::error_code error;
  p.cwd = std::filesystem::current_path(error).string();
  p.started_utc = utcNow();
  p.host = hostName();
  p.scenario_file = scenario_file;
  p.scenario_sha256 = sha256OfFile(scenario_file);
  return p;
}

std::string provenanceJson(const Provenance& p) {
  // Keys in this order (nlohmann's ordered_json keeps insertion order) so the line reads naturally.
  nlohmann::ordered_json json;
  json["version"] = p.version;
  json["commit"] = p.commit;
  json["cyclone_dds"] = p.cyclone_dds;
  json["command_line"] = p.command_line;
  json["cwd"] = p.cwd;
  json["started_utc"] = p.started_utc;
  json["host"] = p.host;
  json["scenario_file"] = p.scenario_file;
  json["scenario_sha256"] = p.scenario_sha256;
  // Replace, not throw, on invalid UTF-8 in an argument: provenance must never stop a run.
  return json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

Provenance parseProvenanceJson(const std::string& text) {
  const auto json = nlohmann::json::parse(text, nullptr, false);
  if (json.is_discarded() || !json.is_object()) throw std::runtime_error("provenance: not a JSON object");
  auto string = [&](const char* key) {
    if (!json.contains(key) || !json[key].is_string()) throw std::runtime_error(std::string("provenance: no string \"") + key + "\"");
    return json[key].get<std::string>();
  };
  Provenance p;
  p.version = string("version");
  p.commit = string("commit");
  p.cyclone_dds = string("cyclone_dds");
  if (!json.contains("command_line") || !json["command_line"].is_array())
    throw std::runtime_error("provenance: no array \"command_line\"");
  for (const auto& arg : json["command_line"]) {
    if (!arg.is_string()) throw std::runtime_error("provenance: \"command_line\" holds a non-string");
    p.command_line.push_back(arg.get<std::string>());
  }
  p.cwd = string("cwd");
  p.started_utc = string("started_utc");
  p.host = string("host");
  p.scenario_file = string("scenario_file");
  p.scenario_sha256 = string("scenario_sha256");
  return p;
}

std::string readRunProvenance(const std::string& run_json_path) {
  std::ifstream in(run_json_path);
  if (!in) return "";
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto json = nlohmann::json::parse(text, nullptr, false);
  if (json.is_discarded() || !json.is_object()) throw std::runtime_error(run_json_path + ": not a JSON object");
  if (!json.contains("provenance")) return "";
  try {
    return provenanceJson(parseProvenanceJson(json["provenance"].dump()));
  } catch (const std::exception& error) {
    throw std::runtime_error(run_json_path + ": " + error.what());
  }
}

}  // namespace wsn::common

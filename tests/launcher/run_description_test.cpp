// run.json (launcher/run_description.cpp): what the launcher writes reads back the same, stays
// one key per line for the sed of shell scripts, and a damaged file is named with what is wrong.
#include "launcher/run_description.hpp"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace wsn::launcher {
namespace {

RunDescription described() {
  RunDescription run;
  run.identity.run_id = 0x00ab'cdef'0123'4567ULL;
  run.identity.domain = 42;
  run.participants = 9;
  run.first_viewer_index = 9;
  run.viewer_slots = 4;
  run.scenario = "oh \"quadrants\"";  // a quote in a name must not break the file
  run.ticks = 100;
  run.processes = 8;
  run.tick_interval_s = 0.1;
  run.in_process = false;
  run.launcher_pid = 31337;
  run.status = kRunFailed;
  run.reason = "supernode 2 killed by SIGKILL; log d/logs/supernode-2.log";
  run.provenance_json = R"({"version":"0.1.0","command_line":["wsntrack","run"],"host":"h"})";
  return run;
}

std::string errorOf(const std::string& json) {
  try {
    parseRunDescription(json, "d/run.json");
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

TEST_CASE("run.json reads back to the description it was written from", "[launcher][run_json]") {
  const auto run = described();
  CHECK(parseRunDescription(runDescriptionJson(run), "run.json") == run);
  // Without provenance (a description made by hand) the key is left out, and still reads back.
  auto bare = run;
  bare.provenance_json.clear();
  const auto text = runDescriptionJson(bare);
  CHECK(text.find("provenance") == std::string::npos);
  CHECK(parseRunDescription(text, "run.json") == bare);
  // The largest run id keeps its 16 hex digits.
  bare.identity.run_id = ~0ULL;
  CHECK(parseRunDescription(runDescriptionJson(bare), "run.json").identity.run_id == ~0ULL);
}

TEST_CASE("run.json has one key per line in the layout scripts read with sed", "[launcher][run_json]") {
  const std::string text = runDescriptionJson(described());
  // The sed of examples/README.md and watch_test.sh: '"domain": N,', '"run_id": "HEX",' and the
  // viewer indices as '[first, last]' with first + slots - 1 = 9 + 4 - 1 = 12.
  CHECK(text.find("\n  \"run_id\": \"abcdef01234567\",\n") != std::string::npos);
  CHECK(text.find("\n  \"domain\": 42,\n") != std::string::npos);
  CHECK(text.find("\n  \"viewer_participant_indices\": [9, 12],\n") != std::string::npos);
  CHECK(text.find("\n  \"tick_interval_s\": 0.1,\n") != std::string::npos);
  CHECK(text.find("\n  \"in_process\": false,\n") != std::string::npos);
  CHECK(text.find("\n  \"status\": \"failed\",\n") != std::string::npos);
  // The provenance is the last line, on one line, as provenanceJson wrote it.
  CHECK(text.find("\n  \"provenance\": " + described().provenance_json + "\n}\n") != std::string::npos);
  // Thirteen keys, thirteen lines between the braces.
  CHECK(std::count(text.begin(), text.end(), '\n') == 15);
  CHECK(nlohmann::json::parse(text).at("scenario") == "oh \"quadrants\"");
}

TEST_CASE("a damaged run.json is named with the key that is wrong", "[launcher][run_json]") {
  auto json = nlohmann::json::parse(runDescriptionJson(described()));
  const auto without = [&](const std::string& key) {
    auto copy = json;
    copy.erase(key);
    return errorOf(copy.dump());
  };
  const auto with = [&](const std::string& key, const nlohmann::json& value) {
    auto copy = json;
    copy[key] = value;
    return errorOf(copy.dump());
  };
  CHECK(errorOf("not json") == "d/run.json: not a JSON object");
  CHECK(errorOf("[1, 2]") == "d/run.json: not a JSON object");
  CHECK(without("domain") == "d/run.json: no valid \"domain\"");
  CHECK(with("domain", "42") == "d/run.json: no valid \"domain\"");
  CHECK(with("ticks", 2.5) == "d/run.json: no valid \"ticks\"");
  CHECK(with("run_id", "xyz") == "d/run.json: no valid \"run_id\"");
  CHECK(with("run_id", "12345678901234567") == "d/run.json: no valid \"run_id\"");  // 17 digits: beyond 64 bits
  CHECK(with("viewer_participant_indices", nlohmann::json::array({1})) ==
        "d/run.json: no valid \"viewer_participant_indices\"");
  CHECK(with("viewer_participant_indices", nlohmann::json::array({-1, 3})) ==
        "d/run.json: no valid \"viewer_participant_indices\"");
  CHECK(with("in_process", 0) == "d/run.json: no valid \"in_process\"");
  // Well-formed but impossible: a domain beyond Cyclone's, no viewer slot, no tick.
  CHECK(with("domain", 999) == "d/run.json: values out of range");
  CHECK(with("viewer_participant_indices", nlohmann::json::array({9, 8})) == "d/run.json: values out of range");
  CHECK(with("ticks", 0) == "d/run.json: values out of range");
  CHECK(with("status", "done") == "d/run.json: no valid \"status\"");
  CHECK(with("status", 1) == "d/run.json: no valid \"status\"");
  // Keys it does not know are left alone (a newer launcher may add some).
  CHECK(with("future", 1).empty());
  // A run.json from before the status existed reads with an empty one.
  CHECK(without("status").empty());
  CHECK(without("reason").empty());
}

TEST_CASE("markRun rewrites the status and the reason's first line, provenance still last", "[launcher][run_json]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("wsn-run-json-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto run = described();
  run.status = kRunRunning;
  run.reason.clear();
  writeRunDescription(dir.string(), run);
  CHECK(readRunDescription(dir.string()).status == "running");
  markRun(dir.string(), kRunFailed, "node 0 killed by SIGKILL; log d/logs/node-0.log:\n    last line of the log\n");
  const auto failed = readRunDescription(dir.string());
  CHECK(failed.status == "failed");
  CHECK(failed.reason == "node 0 killed by SIGKILL; log d/logs/node-0.log");
  run.status = failed.status;
  run.reason = failed.reason;
  CHECK(failed == run);  // everything else as it was
  std::ifstream in(dir / "run.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text.find("\n  \"provenance\": " + run.provenance_json + "\n}\n") != std::string::npos);
  markRun(dir.string(), kRunComplete);
  CHECK(readRunDescription(dir.string()).status == "complete");
  CHECK(readRunDescription(dir.string()).reason.empty());
  CHECK_FALSE(fs::exists(dir / "run.json.tmp"));
  fs::remove_all(dir);
  // A directory without run.json: the error names the file.
  CHECK_THROWS_WITH(markRun((dir / "none").string(), kRunComplete), Catch::Contains("run.json: cannot read"));
}

}  // namespace
}  // namespace wsn::launcher

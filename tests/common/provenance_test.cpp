// The provenance block of a run: SHA-256 against the FIPS 180-2 test vectors, capture from a real
// file, and the JSON round trip through run.json that the aggregator relies on.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "common/provenance.hpp"
#include "common/version.hpp"

namespace wsn::common {
namespace {

/// A file in a directory of this process's own, so that two suites running at once do not share it.
std::string tempFile(const std::string& name, const std::string& content) {
  static const auto dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("wsn_provenance_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

TEST_CASE("sha256 matches the FIPS 180-2 test vectors", "[provenance]") {
  // FIPS 180-2 appendix B.1 and B.2, and the empty message.
  CHECK(sha256Hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(sha256Hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256OfFile(tempFile("abc", "abc")) == sha256Hex("abc"));
  CHECK_THROWS_WITH(sha256OfFile("/nonexistent/scenario.yaml"), Catch::Contains("/nonexistent/scenario.yaml"));
}

TEST_CASE("captured provenance names the build, the command line, the time and the file", "[provenance]") {
  const std::string scenario = tempFile("scenario.yaml", "run: {ticks: 5}\n");
  const Provenance p = captureProvenance({"wsntrack", "run", scenario, "--seed", "3"}, scenario);
  CHECK(p.version == version::projectVersion());
  CHECK(p.commit.rfind(std::string(version::gitCommit()), 0) == 0);
  CHECK(p.cyclone_dds == version::cycloneDdsVersion());
  CHECK(p.command_line.size() == 5);
  CHECK(p.cwd == std::filesystem::current_path().string());
  CHECK(p.scenario_file == scenario);
  CHECK(p.scenario_sha256 == sha256Hex("run: {ticks: 5}\n"));
  CHECK(!p.host.empty());
  // 2026-11-25T12:01:02Z: 20 characters, 'T' and 'Z' in place.
  REQUIRE(p.started_utc.size() == 20);
  CHECK(p.started_utc[10] == 'T');
  CHECK(p.started_utc.back() == 'Z');
}

TEST_CASE("provenance is one JSON line and reads back equal, also from run.json", "[provenance]") {
  Provenance p;
  p.version = "0.1.0";
  p.commit = "0123abcd+dirty";
  p.cyclone_dds = "0.10.2";
  p.command_line = {"wsntrack", "run", "a \"quoted\" path\\x.yaml"};
  p.cwd = "/home/someone";
  p.started_utc = "2026-11-25T12:01:02Z";
  p.host = "h";
  p.scenario_file = "a \"quoted\" path\\x.yaml";
  p.scenario_sha256 = std::string(64, 'a');
  const std::string json = provenanceJson(p);
  CHECK(json.find('\n') == std::string::npos);
  CHECK(json.rfind("{\"version\":\"0.1.0\",\"commit\":", 0) == 0);
  CHECK(parseProvenanceJson(json) == p);

  const std::string run_json = tempFile("run.json", "{\n  \"run_id\": \"1f\",\n  \"provenance\": " + json + "\n}\n");
  CHECK(readRunProvenance(run_json) == json);
  CHECK(readRunProvenance(tempFile("plain_run.json", "{\"run_id\": \"1f\"}")).empty());
  CHECK(readRunProvenance("/nonexistent/run.json").empty());
  CHECK_THROWS_WITH(readRunProvenance(tempFile("bad_run.json", "{\"provenance\": {\"version\": 1}}")),
                    Catch::Contains("no string \"version\""));
  CHECK_THROWS_WITH(readRunProvenance(tempFile("broken_run.json", "{\"provenance\": ")),
                    Catch::Contains("not a JSON object"));
}

}  // namespace
}  // namespace wsn::common

// Gathering the roles' records of refused samples into rejected.json (launcher/rejections.hpp):
// totals summed over processes, the role files removed, and a file no role wrote counted rather
// than skipped.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "common/edge_checks.hpp"
#include "launcher/rejections.hpp"

namespace wsn::launcher {
namespace {

namespace fs = std::filesystem;

struct TempRun {
  TempRun() : path(fs::temp_directory_path() / ("wsn-rejections-" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path / "rejected");
  }
  ~TempRun() { fs::remove_all(path); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(path / "rejected" / name) << text; }
  nlohmann::json record() const {
    std::ifstream in(path / "rejected.json");
    return nlohmann::json::parse(in);
  }
  fs::path path;
};

TEST_CASE("the roles' rejections are summed into rejected.json and their files removed", "[rejections]") {
  TempRun run;
  common::RejectionLog network;
  network.add("wsn_report_batch", common::RejectReason::kNotFinite, 3);
  network.add("wsn_report_batch", common::RejectReason::kDuplicate);
  run.write("network-0.json", network.json("network", 0));
  common::RejectionLog supernode;
  supernode.add("wsn_delivery_batch", common::RejectReason::kForeignRun, 2);
  run.write("supernode-1.json", supernode.json("supernode", 1));
  CHECK(gatherRejections(run.path.string()) == 6);
  const auto record = run.record();
  CHECK(record["total"] == 6);
  REQUIRE(record["processes"].size() == 2);
  CHECK(record["processes"][0]["role"] == "network");
  CHECK(record["processes"][1]["rejected"][0]["reason"] == "foreign_run");
  CHECK_FALSE(fs::exists(run.path / "rejected"));
}

TEST_CASE("a run that refused nothing still records a total of zero", "[rejections]") {
  TempRun run;
  fs::remove_all(run.path / "rejected");
  CHECK(gatherRejections(run.path.string()) == 0);
  CHECK(run.record()["total"] == 0);
  CHECK(run.record()["processes"].empty());
}

TEST_CASE("a file no role wrote counts as one more problem", "[rejections]") {
  TempRun run;
  run.write("node-0.json", "not json");
  CHECK(gatherRejections(run.path.string()) == 1);
  CHECK(run.record()["processes"][0]["error"] == "not a role's record of rejections");
}

}  // namespace
}  // namespace wsn::launcher

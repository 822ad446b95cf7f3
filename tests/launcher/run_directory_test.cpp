// The run directory's lock (launcher/run_directory.cpp): a directory whose run is live is refused,
// --overwrite or not, naming the live launcher's pid; one whose run has ended is cleared and reused.
#include "launcher/run_directory.hpp"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

namespace wsn::launcher {
namespace {

namespace fs = std::filesystem;

std::string errorOf(const std::string& dir, bool overwrite) {
  try {
    createRunDirectory(dir, overwrite);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

void touch(const fs::path& path) { std::ofstream(path) << "x\n"; }

/// A run directory as an ended run left it: its inputs and its (unheld) lock file.
void endedRun(const fs::path& dir) {
  fs::create_directories(dir / "logs");
  touch(dir / "scenario.yaml");
  touch(dir / "cyclonedds.xml");
  touch(dir / "metrics.json");
  touch(dir / kRunLockFile);
}

TEST_CASE("a live run's directory is refused with its launcher's pid, overwrite or not", "[launcher][run_dir]") {
  const fs::path root = fs::temp_directory_path() / ("wsn-run-dir-" + std::to_string(::getpid()));
  fs::remove_all(root);
  const std::string live = (root / "live").string();
  CHECK(errorOf(live, false).empty());  // created and locked by this process, as a launcher does
  CHECK(fs::exists(root / "live" / kRunLockFile));
  CHECK(fs::is_directory(root / "live" / "logs"));
  RunDescription run;
  run.launcher_pid = 4242;
  run.ticks = 1;
  run.viewer_slots = 1;
  writeRunDescription(live, run);
  touch(root / "live" / "scenario.yaml");
  touch(root / "live" / "cyclonedds.xml");
  const std::string expected = live + ": a run is still live there (wsntrack launcher pid 4242)";
  CHECK(errorOf(live, true).rfind(expected, 0) == 0);
  CHECK(errorOf(live, false).rfind(expected, 0) == 0);
  CHECK(fs::exists(root / "live" / "run.json"));  // nothing was deleted

  // Locked before its run.json exists: still refused, the pid unknown.
  fs::remove(root / "live" / "run.json");
  CHECK(errorOf(live, true).find("pid unknown: its run.json is not written yet") != std::string::npos);
  fs::remove_all(root);
}

TEST_CASE("an ended run's directory is refused without overwrite and cleared with it", "[launcher][run_dir]") {
  const fs::path root = fs::temp_directory_path() / ("wsn-run-dir-ended-" + std::to_string(::getpid()));
  fs::remove_all(root);
  endedRun(root / "ended");
  const std::string ended = (root / "ended").string();
  CHECK(errorOf(ended, false) == ended + ": run directory exists and is not empty (use --overwrite)");
  CHECK(fs::exists(root / "ended" / "metrics.json"));
  CHECK(errorOf(ended, true).empty());
  CHECK_FALSE(fs::exists(root / "ended" / "metrics.json"));
  CHECK_FALSE(fs::exists(root / "ended" / "scenario.yaml"));
  CHECK(fs::exists(root / "ended" / kRunLockFile));  // now held by this process

  // A launcher stopped before it wrote its inputs left its lock file and logs/: cleared with overwrite.
  fs::create_directories(root / "stopped" / "logs");
  touch(root / "stopped" / kRunLockFile);
  touch(root / "stopped" / "logs" / "launcher.log");
  const std::string stopped = (root / "stopped").string();
  CHECK(errorOf(stopped, false) == stopped + ": run directory exists and is not empty (use --overwrite)");
  CHECK(errorOf(stopped, true).empty());
  CHECK_FALSE(fs::exists(root / "stopped" / "logs" / "launcher.log"));

  // A directory of the user's own is never cleared, and gets no lock file.
  fs::create_directories(root / "mine");
  touch(root / "mine" / "notes.txt");
  const std::string mine = (root / "mine").string();
  CHECK(errorOf(mine, true).find("not a wsntrack run directory") != std::string::npos);
  CHECK(fs::exists(root / "mine" / "notes.txt"));
  CHECK_FALSE(fs::exists(root / "mine" / kRunLockFile));
  fs::remove_all(root);
}

}  // namespace
}  // namespace wsn::launcher

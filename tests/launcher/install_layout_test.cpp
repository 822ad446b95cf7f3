// Tests of launcher/install_layout: which layout a wsntrack directory is taken for, the paths it gives,
// and the message when the role executables are nowhere, on trees made in a temporary directory.
#include "launcher/install_layout.hpp"

#include <unistd.h>

#include <catch2/catch.hpp>

#include <fstream>
#include <string>

namespace wsn::launcher {
namespace {

namespace fs = std::filesystem;

/// A fresh directory, removed with everything in it at the end of the test.
class TempTree {
 public:
  TempTree() {
    static int counter = 0;
    root_ = fs::temp_directory_path() /
            ("wsn_install_layout_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  TempTree(const TempTree&) = delete;
  TempTree& operator=(const TempTree&) = delete;
  ~TempTree() {
    std::error_code ignored;
    fs::remove_all(root_, ignored);
  }
  const fs::path& root() const { return root_; }

  /// Creates the file (and its directory), executable or not.
  fs::path file(const fs::path& relative, bool executable) const {
    const fs::path path = root_ / relative;
    fs::create_directories(path.parent_path());
    std::ofstream(path) << "#!/bin/sh\n";
    fs::permissions(path, executable ? fs::perms::owner_all : fs::perms::owner_read | fs::perms::owner_write);
    return path;
  }
  void roles(const fs::path& dir) const {
    for (const auto& name : roleExecutables()) file(dir / name, true);
  }

 private:
  fs::path root_;
};

/// The default GNUInstallDirs layout, as cmake/WsnInstallDirs.cmake computes it.
InstallPaths defaultPaths(const fs::path& source_dir) {
  return {source_dir, "../libexec/wsntrack", "../share/wsntrack/tools", "../share/wsntrack/scenarios"};
}

TEST_CASE("a build tree is everything next to wsntrack, with tools and scenarios from the sources", "[launcher]") {
  TempTree tree;
  tree.file("build/bin/wsntrack", true);
  tree.roles("build/bin");
  tree.file("build/bin/plot_run.py", true);
  const auto layout = locateInstall(tree.root() / "build/bin", defaultPaths(tree.root() / "src"));
  CHECK(layout.build_tree);
  CHECK(layout.missing.empty());
  CHECK(layout.role_dir == (tree.root() / "build/bin").string());
  CHECK(layout.requireRoleDir() == layout.role_dir);
  CHECK(layout.plot_script == (tree.root() / "build/bin/plot_run.py").string());
  CHECK(layout.tools_dir == (tree.root() / "src/tools").string());
  CHECK(layout.scenario_dir == (tree.root() / "src/scenarios").string());
}

TEST_CASE("an installed tree is found relative to bin with no dot-dot left in the paths", "[launcher]") {
  TempTree tree;
  tree.file("prefix/bin/wsntrack", true);
  tree.roles("prefix/libexec/wsntrack");
  tree.file("prefix/share/wsntrack/tools/plot_run.py", true);
  // The trailing separator is what /proc/self/exe never gives but a caller might.
  const auto layout = locateInstall(tree.root() / "prefix/bin/", defaultPaths(tree.root() / "src"));
  CHECK_FALSE(layout.build_tree);
  CHECK(layout.missing.empty());
  CHECK(layout.role_dir == (tree.root() / "prefix/libexec/wsntrack").string());
  CHECK(layout.plot_script == (tree.root() / "prefix/share/wsntrack/tools/plot_run.py").string());
  CHECK(layout.tools_dir == (tree.root() / "prefix/share/wsntrack/tools").string());
  CHECK(layout.scenario_dir == (tree.root() / "prefix/share/wsntrack/scenarios").string());
  CHECK(layout.role_dir.find("..") == std::string::npos);
}

TEST_CASE("a custom layout with the roles in bin and data elsewhere is taken for installed", "[launcher]") {
  TempTree tree;
  tree.file("opt/w/games/wsntrack", true);
  tree.roles("opt/w/games");
  tree.file("opt/w/data/tools/plot_run.py", true);
  // -DCMAKE_INSTALL_BINDIR=games -DCMAKE_INSTALL_LIBEXECDIR=games -DCMAKE_INSTALL_DATADIR=data, roughly.
  const InstallPaths paths{"", ".", "../data/tools", "../data/scenarios"};
  const auto layout = locateInstall(tree.root() / "opt/w/games", paths);
  CHECK_FALSE(layout.build_tree);
  CHECK(layout.missing.empty());
  CHECK(layout.role_dir == (tree.root() / "opt/w/games").string());
  CHECK(layout.plot_script == (tree.root() / "opt/w/data/tools/plot_run.py").string());
}

TEST_CASE("an absolute installed directory is used as it is", "[launcher]") {
  TempTree tree;
  tree.file("usr/bin/wsntrack", true);
  tree.roles("elsewhere/roles");
  const InstallPaths paths{"", tree.root() / "elsewhere/roles", "../share/wsntrack/tools", "../share/wsntrack/scenarios"};
  const auto layout = locateInstall(tree.root() / "usr/bin", paths);
  CHECK(layout.missing.empty());
  CHECK(layout.role_dir == (tree.root() / "elsewhere/roles").string());
}

TEST_CASE("the build tree wins when both layouts are complete", "[launcher]") {
  TempTree tree;
  tree.file("p/bin/wsntrack", true);
  tree.roles("p/bin");
  tree.file("p/bin/plot_run.py", true);
  tree.roles("p/libexec/wsntrack");
  const auto layout = locateInstall(tree.root() / "p/bin", defaultPaths(""));
  CHECK(layout.build_tree);
  CHECK(layout.role_dir == (tree.root() / "p/bin").string());
  // A build tree without its sources still has the copied plot script as its tools.
  CHECK(layout.tools_dir == (tree.root() / "p/bin").string());
}

TEST_CASE("an installed tree without the plot script still runs and names where the script belongs", "[launcher]") {
  TempTree tree;
  tree.file("prefix/bin/wsntrack", true);
  tree.roles("prefix/libexec/wsntrack");
  const auto layout = locateInstall(tree.root() / "prefix/bin", defaultPaths(""));
  CHECK(layout.missing.empty());
  CHECK(layout.plot_script == (tree.root() / "prefix/share/wsntrack/tools/plot_run.py").string());
  CHECK_FALSE(fs::exists(layout.plot_script));
}

TEST_CASE("missing role executables name both places looked in and requireRoleDir throws", "[launcher]") {
  TempTree tree;
  tree.file("prefix/bin/wsntrack", true);
  tree.file("prefix/share/wsntrack/tools/plot_run.py", true);
  const auto layout = locateInstall(tree.root() / "prefix/bin", defaultPaths(""));
  REQUIRE_FALSE(layout.missing.empty());
  CHECK_THAT(layout.missing, Catch::Contains((tree.root() / "prefix/bin").string()));
  CHECK_THAT(layout.missing, Catch::Contains((tree.root() / "prefix/libexec/wsntrack").string()));
  CHECK_THAT(layout.missing, Catch::Contains("wsntrack-supernode"));
  CHECK_THROWS_WITH(layout.requireRoleDir(), layout.missing);
  // Replay and plots need no roles: the plot script is still where the installed layout puts it.
  CHECK(layout.plot_script == (tree.root() / "prefix/share/wsntrack/tools/plot_run.py").string());
}

TEST_CASE("a build tree missing one role keeps its plot script and reports the missing roles", "[launcher]") {
  TempTree tree;
  tree.file("build/bin/wsntrack", true);
  tree.roles("build/bin");
  tree.file("build/bin/plot_run.py", true);
  fs::remove(tree.root() / "build/bin/wsntrack-aggregator");
  const auto layout = locateInstall(tree.root() / "build/bin", defaultPaths(""));
  CHECK_FALSE(layout.missing.empty());
  CHECK(layout.build_tree);
  CHECK(layout.plot_script == (tree.root() / "build/bin/plot_run.py").string());
}

TEST_CASE("a role file that is not executable does not count", "[launcher]") {
  TempTree tree;
  tree.file("prefix/bin/wsntrack", true);
  tree.roles("prefix/libexec/wsntrack");
  tree.file("prefix/libexec/wsntrack/wsntrack-network", false);
  const auto layout = locateInstall(tree.root() / "prefix/bin", defaultPaths(""));
  // No x bit at all: refused by access() even for root, who may run anything with one.
  CHECK_FALSE(layout.missing.empty());
}

TEST_CASE("this build finds a tree installed with its own configured paths", "[launcher]") {
  const auto paths = thisBuildPaths();
  CHECK(fs::exists(paths.source_dir / "tools/plot_run.py"));
  // An absolute directory (a custom configuration) cannot be laid out under a temporary prefix.
  if (paths.role_dir.is_absolute() || paths.tools_dir.is_absolute()) return;
  TempTree tree;
  const fs::path bin = tree.root() / "prefix/bin";
  tree.file(bin / "wsntrack", true);
  tree.roles(bin / paths.role_dir);
  tree.file(bin / paths.tools_dir / "plot_run.py", true);
  const auto layout = locateInstall(bin);
  CHECK_FALSE(layout.build_tree);
  CHECK(layout.missing.empty());
  CHECK(fs::equivalent(layout.role_dir, bin / paths.role_dir));
  CHECK(fs::exists(layout.plot_script));
}

}  // namespace
}  // namespace wsn::launcher

// Finding wsntrack's companions relative to its own executable, so that a build tree and an installed
// tree (any prefix, any GNUInstallDirs layout) both work from any working directory.
#include "launcher/install_layout.hpp"

#include <unistd.h>

#include <system_error>

// CMake defines these for this file only (launcher/CMakeLists.txt); the fallbacks are the default
// GNUInstallDirs layout, so that the file also compiles on its own.
#ifndef WSN_SOURCE_DIR
#define WSN_SOURCE_DIR ""
#endif
#ifndef WSN_INSTALL_ROLE_DIR
#define WSN_INSTALL_ROLE_DIR "../libexec/wsntrack"
#endif
#ifndef WSN_INSTALL_TOOLS_DIR
#define WSN_INSTALL_TOOLS_DIR "../share/wsntrack/tools"
#endif
#ifndef WSN_INSTALL_SCENARIO_DIR
#define WSN_INSTALL_SCENARIO_DIR "../share/wsntrack/scenarios"
#endif

namespace wsn::launcher {
namespace fs = std::filesystem;

InstallPaths thisBuildPaths() {
  return {WSN_SOURCE_DIR, WSN_INSTALL_ROLE_DIR, WSN_INSTALL_TOOLS_DIR, WSN_INSTALL_SCENARIO_DIR};
}

const std::vector<std::string>& roleExecutables() {
  static const std::vector<std::string> names{"wsntrack-node", "wsntrack-network", "wsntrack-supernode",
                                              "wsntrack-aggregator"};
  return names;
}

namespace {

constexpr const char* kPlotScript = "plot_run.py";

bool isExecutableFile(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error) && ::access(path.c_str(), X_OK) == 0;
}

bool hasEveryRole(const fs::path& dir) {
  for (const auto& name : roleExecutables())
    if (!isExecutableFile(dir / name)) return false;
  return true;
}

/// Absolute and without "." or "..", but symbolic links kept: the path a user would recognise.
fs::path tidy(const fs::path& path) {
  fs::path normal = fs::absolute(path).lexically_normal();
  // lexically_normal leaves a trailing separator on "a/b/..": drop it so that strings compare.
  if (!normal.has_filename() && normal.has_parent_path() && normal != normal.root_path()) normal = normal.parent_path();
  return normal;
}

InstallLayout buildTreeLayout(const fs::path& here, const InstallPaths& paths) {
  InstallLayout layout;
  layout.build_tree = true;
  layout.role_dir = here.string();
  layout.plot_script = (here / kPlotScript).string();
  // A build tree belongs to its sources; without them (the fallback) the tools are the copied script.
  const fs::path source = paths.source_dir.empty() ? fs::path() : tidy(paths.source_dir);
  layout.tools_dir = source.empty() ? here.string() : (source / "tools").string();
  layout.scenario_dir = source.empty() ? std::string() : (source / "scenarios").string();
  return layout;
}

InstallLayout installedLayout(const fs::path& here, const InstallPaths& paths) {
  InstallLayout layout;
  layout.role_dir = tidy(here / paths.role_dir).string();
  layout.tools_dir = tidy(here / paths.tools_dir).string();
  layout.plot_script = (fs::path(layout.tools_dir) / kPlotScript).string();
  layout.scenario_dir = tidy(here / paths.scenario_dir).string();
  return layout;
}

}  // namespace

InstallLayout locateInstall(const fs::path& executable_dir, const InstallPaths& paths) {
  const fs::path here = tidy(executable_dir);
  // The build tree first. The build copies plot_run.py next to wsntrack and an installed bin/ never
  // has it, so a layout that installs the roles into bin/ itself is still taken for an installed one.
  const bool plot_here = fs::exists(here / kPlotScript);
  if (plot_here && hasEveryRole(here)) return buildTreeLayout(here, paths);
  InstallLayout installed = installedLayout(here, paths);
  if (hasEveryRole(installed.role_dir)) return installed;
  // Neither: keep the layout this most looks like, so that the plot script is still found.
  InstallLayout layout = plot_here ? buildTreeLayout(here, paths) : installed;
  std::string names;
  for (const auto& name : roleExecutables()) names += (names.empty() ? "" : ", ") + name;
  layout.missing = "cannot find the role executables of " + (here / "wsntrack").string() + " (" + names +
                   "): looked next to it (a build tree, with " + kPlotScript + ") and in " + installed.role_dir +
                   " (an installed tree)";
  return layout;
}

const std::string& InstallLayout::requireRoleDir() const {
  if (!missing.empty()) throw std::runtime_error(missing);
  return role_dir;
}

InstallLayout locateInstall(const fs::path& executable_dir) { return locateInstall(executable_dir, thisBuildPaths()); }

}  // namespace wsn::launcher

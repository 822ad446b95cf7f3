// Where wsntrack finds its role executables, plot script, tools and scenarios, from the directory of
// its own executable: in a build tree (everything next to it) or in an installed tree (GNUInstallDirs).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace wsn::launcher {

/// The python that runs plot_run.py (plots, replay): Debian's, which has python3-matplotlib; the
/// python3 first on PATH may be a pyenv or venv build without it.
inline constexpr const char* kPlotPython = "/usr/bin/python3";

/// How a build lays itself out. The installed directories are relative to the directory wsntrack is
/// installed in (CMAKE_INSTALL_BINDIR), so that an installed tree works wherever its prefix is.
struct InstallPaths {
  std::filesystem::path source_dir;         ///< build tree: tools/ and scenarios/ are the sources'
  std::filesystem::path role_dir;           ///< installed: the wsntrack-<role> executables
  std::filesystem::path tools_dir;          ///< installed: plot_run.py, sweep.py, wsntrack_run.py
  std::filesystem::path scenario_dir;       ///< installed: the shipped scenarios
};

/// This build's paths, as CMake computed them when it was configured.
InstallPaths thisBuildPaths();

/// What wsntrack uses, all absolute and free of "..".
struct InstallLayout {
  bool build_tree = false;  ///< true: found next to wsntrack, as the build leaves it
  std::string role_dir;
  std::string plot_script;  ///< where plot_run.py belongs in this layout; it may be missing (plots are optional)
  std::string tools_dir;
  std::string scenario_dir;
  /// Empty, or why the role executables were not found, naming every place looked in.
  std::string missing;

  /// role_dir, or std::runtime_error(missing) when the role executables were not found.
  const std::string& requireRoleDir() const;
};

/// The executables `wsntrack run` starts, without their directory.
const std::vector<std::string>& roleExecutables();

/// The build tree when every role executable and plot_run.py are next to wsntrack, else the installed
/// tree, `paths` from it. Missing role executables do not throw here (replay and plots need none):
/// `missing` says so and requireRoleDir() throws.
InstallLayout locateInstall(const std::filesystem::path& executable_dir, const InstallPaths& paths);

/// locateInstall with this build's paths.
InstallLayout locateInstall(const std::filesystem::path& executable_dir);

}  // namespace wsn::launcher

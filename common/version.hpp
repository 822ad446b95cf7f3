// What build this is: the project version, the git commit it was built from and the Cyclone DDS
// version it was built against, for `--version` and the provenance block of every run directory.
#pragma once

#include <string>
#include <string_view>

namespace wsn::version {

/// The project's version (CMake's project(VERSION)), e.g. "0.1.0".
std::string_view projectVersion();
/// The full git commit hash the build was made from; "unknown" outside a git checkout.
std::string_view gitCommit();
/// Whether tracked files differed from that commit when the build was made.
bool gitDirty();
/// The Cyclone DDS version the build was configured against, e.g. "0.10.2".
std::string_view cycloneDdsVersion();

/// One line for `--version`: "wsntrack 0.1.0 (commit 1a2b3c4d5e6f+dirty, Cyclone DDS 0.10.2)".
inline std::string describe(std::string_view program = "wsntrack") {
  std::string commit(gitCommit());
  if (commit.size() > 12) commit.resize(12);
  return std::string(program) + " " + std::string(projectVersion()) + " (commit " + commit + (gitDirty() ? "+dirty" : "") +
         ", Cyclone DDS " + std::string(cycloneDdsVersion()) + ")";
}

/// The commit as provenance records it: the full hash, with "+dirty" when the tree was modified.
inline std::string commitWithState() { return std::string(gitCommit()) + (gitDirty() ? "+dirty" : ""); }

}  // namespace wsn::version

// A secured run's credentials on disk (docs/SECURITY.md): RUN_DIR/credentials, a 0700 directory of
// 0600 files holding the run's CA certificate, the signed governance and permissions documents and
// every identity's certificate and private key. The CA's own key never leaves the launcher's memory.
#pragma once

#include <cstdint>
#include <string>
#include <utility>

#include "common/scenario_config.hpp"

namespace wsn::launcher {

/// The directory's name inside the run directory.
inline constexpr const char* kCredentialsDirectory = "credentials";

/// How long a run's certificates and permissions stay valid: a run of a week at most, by design
/// (wsntrack's longest benchmark runs take minutes), so a key that outlives its run by mistake
/// (--keep-credentials) admits nothing for long.
inline constexpr int kCredentialValidityHours = 7 * 24;

/// Makes the run's CA, issues every identity of dds::runIdentities() and writes them with the
/// documents for `domain` into RUN_DIR/credentials; returns that directory's absolute path.
/// Throws std::runtime_error when the directory cannot be made private or a file written.
std::string writeRunCredentials(const std::string& run_dir, std::uint64_t run_id, int domain,
                                common::MessageProtection protection);

/// Removes RUN_DIR/credentials and everything in it; no error when it is not there.
void removeRunCredentials(const std::string& run_dir);

/// Removes a run's credentials when the command ends, however it returns, once arm() said the run
/// directory is this run's (never those of a directory the launcher refused to take); a path that
/// ends the process at once (std::_Exit) calls remove() first. Keeps them with `keep`
/// (--keep-credentials).
class CredentialsRemoval {
 public:
  explicit CredentialsRemoval(bool keep) : keep_(keep) {}
  ~CredentialsRemoval() { remove(); }
  CredentialsRemoval(const CredentialsRemoval&) = delete;
  CredentialsRemoval& operator=(const CredentialsRemoval&) = delete;
  /// From now on `run_dir` is this run's, and its credentials go at the end.
  void arm(std::string run_dir) { run_dir_ = std::move(run_dir); }
  /// Removes them now (once); a failure is a warning on stderr, never an exception.
  void remove() noexcept;

 private:
  bool keep_;
  std::string run_dir_;
  bool done_ = false;
};

}  // namespace wsn::launcher

#include "launcher/run_credentials.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <stdexcept>

#include "common/dds/security.hpp"
#include "launcher/credentials.hpp"

namespace wsn::launcher {
namespace {

namespace fs = std::filesystem;

/// Writes `text` to a new file readable and writable by its owner only. O_EXCL: the directory was
/// just made empty, so an existing file there means someone else put it there.
void writePrivateFile(const fs::path& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) throw std::runtime_error(path.string() + ": cannot create (" + std::strerror(errno) + ")");
  std::size_t written = 0;
  while (written < text.size()) {
    const auto n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      throw std::runtime_error(path.string() + ": cannot write (" + why + ")");
    }
    written += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) throw std::runtime_error(path.string() + ": cannot write (" + std::strerror(errno) + ")");
}

/// A UTC time as the permissions document's validity wants it.
std::string permissionsTime(std::chrono::system_clock::time_point t) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
  std::tm utc{};
  ::gmtime_r(&seconds, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  return text;
}

}  // namespace

std::string writeRunCredentials(const std::string& run_dir, std::uint64_t run_id, int domain,
                                common::MessageProtection protection) {
  const fs::path dir = fs::absolute(fs::path(run_dir) / kCredentialsDirectory);
  removeRunCredentials(run_dir);
  if (::mkdir(dir.c_str(), 0700) != 0 || ::chmod(dir.c_str(), 0700) != 0)
    throw std::runtime_error(dir.string() + ": cannot create a private directory (" + std::strerror(errno) + ")");

  const std::string organization = dds::runOrganization(run_id);
  const RunAuthority authority(organization, std::chrono::hours(kCredentialValidityHours));
  writePrivateFile(dir / "ca.pem", authority.certificatePem());
  writePrivateFile(dir / "governance.p7s", authority.sign(dds::governanceDocument(domain, protection)));
  // The same hour of slack before now as the certificates (RunAuthority): other hosts' clocks.
  const auto now = std::chrono::system_clock::now();
  writePrivateFile(dir / "permissions.p7s",
                   authority.sign(dds::permissionsDocument(domain, organization,
                                                           permissionsTime(now - std::chrono::hours(1)),
                                                           permissionsTime(now - std::chrono::hours(1) + std::chrono::hours(kCredentialValidityHours)))));
  for (const auto& identity : dds::runIdentities()) {
    const IssuedIdentity issued = authority.issue(identity.name);
    if (issued.subject_name != dds::subjectName(identity.name, organization))
      throw std::logic_error("certificate subject '" + issued.subject_name + "' is not the permissions' '" +
                             dds::subjectName(identity.name, organization) + "'");
    writePrivateFile(dir / (identity.name + ".cert.pem"), issued.certificate_pem);
    writePrivateFile(dir / (identity.name + ".key.pem"), issued.private_key_pem);
  }
  return dir.string();
}

void removeRunCredentials(const std::string& run_dir) {
  std::error_code error;
  fs::remove_all(fs::path(run_dir) / kCredentialsDirectory, error);
  if (error)
    throw std::runtime_error((fs::path(run_dir) / kCredentialsDirectory).string() + ": cannot remove (" +
                             error.message() + ")");
}

void CredentialsRemoval::remove() noexcept {
  if (done_ || keep_ || run_dir_.empty()) return;
  done_ = true;
  try {
    removeRunCredentials(run_dir_);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "wsntrack run: warning: %s\n", error.what());
  }
}

}  // namespace wsn::launcher

// A secured run's credentials as Cyclone DDS takes them: the files the launcher writes (private,
// complete), and a participant configured with them that may write its role's topics and is
// refused the others by its permissions, which checks the signatures, the subject names and the
// plugins' paths all at once.
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "common/dds/cyclone_config.hpp"
#include "common/dds/entity.hpp"
#include "common/dds/role_runtime.hpp"
#include "common/dds/security.hpp"
#include "launcher/run_credentials.hpp"
#include "launcher/run_directory.hpp"

namespace wsn::launcher {
namespace {

namespace fs = std::filesystem;

/// A fresh directory under the system's temporary directory, removed at the end.
struct TempRunDir {
  TempRunDir() : path(fs::temp_directory_path() / ("wsn-credentials-" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempRunDir() { fs::remove_all(path); }
  fs::path path;
};

unsigned mode(const fs::path& path) {
  struct stat st{};
  REQUIRE(::stat(path.c_str(), &st) == 0);
  return st.st_mode & 07777;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST_CASE("the credentials directory is private and holds every identity's files", "[credentials]") {
  TempRunDir run;
  const std::string dir = writeRunCredentials(run.path.string(), 0x1234, 7, common::MessageProtection::kSign);
  CHECK(fs::path(dir) == fs::absolute(run.path / kCredentialsDirectory));
  CHECK(mode(dir) == 0700);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    CHECK(mode(entry.path()) == 0600);
    ++files;
  }
  CHECK(files == 3 + 2 * dds::runIdentities().size());
  for (const auto& identity : dds::runIdentities()) {
    CHECK(slurp(fs::path(dir) / (identity.name + ".cert.pem")).find("BEGIN CERTIFICATE") != std::string::npos);
    CHECK(slurp(fs::path(dir) / (identity.name + ".key.pem")).find("BEGIN PRIVATE KEY") != std::string::npos);
  }
  // Signed as S/MIME, the document inside: the domain and the protection the run asked for.
  const std::string governance = slurp(fs::path(dir) / "governance.p7s");
  CHECK(governance.find("pkcs7-signature") != std::string::npos);
  CHECK(governance.find("<rtps_protection_kind>SIGN</rtps_protection_kind>") != std::string::npos);
  CHECK(governance.find("<min>7</min>") != std::string::npos);
  CHECK(slurp(fs::path(dir) / "permissions.p7s").find("CN=viewer,O=" + dds::runOrganization(0x1234)) != std::string::npos);

  removeRunCredentials(run.path.string());
  CHECK_FALSE(fs::exists(dir));
  removeRunCredentials(run.path.string());  // gone already: no error
}

TEST_CASE("writing the credentials again replaces the old ones", "[credentials]") {
  TempRunDir run;
  const std::string dir = writeRunCredentials(run.path.string(), 1, 3, common::MessageProtection::kSign);
  const std::string first_ca = slurp(fs::path(dir) / "ca.pem");
  writeRunCredentials(run.path.string(), 1, 3, common::MessageProtection::kEncrypt);
  CHECK(slurp(fs::path(dir) / "ca.pem") != first_ca);
  CHECK(slurp(fs::path(dir) / "governance.p7s").find("<rtps_protection_kind>ENCRYPT</rtps_protection_kind>") !=
        std::string::npos);
}

TEST_CASE("removal waits until the run directory is the run's own and can be kept", "[credentials]") {
  TempRunDir run;
  const fs::path dir = writeRunCredentials(run.path.string(), 1, 3, common::MessageProtection::kSign);
  { CredentialsRemoval unarmed(false); }
  CHECK(fs::exists(dir));
  {
    CredentialsRemoval kept(true);
    kept.arm(run.path.string());
  }
  CHECK(fs::exists(dir));
  {
    CredentialsRemoval removal(false);
    removal.arm(run.path.string());
  }
  CHECK_FALSE(fs::exists(dir));
}

TEST_CASE("a secured participant may write its role's topics and no other", "[credentials]") {
  if (dds::securityPluginDirectory().empty()) FAIL("this build found no Cyclone DDS security plugins");
  TempRunDir run;
  const std::uint64_t run_id = newRunId();
  const int domain_id = pickFreeDomain(run_id, 1);
  const std::string dir = writeRunCredentials(run.path.string(), run_id, domain_id, common::MessageProtection::kSign);
  const std::string config = dds::cycloneConfigFor(
      dds::cycloneConfigTemplate(run_id, 1, {}, dds::CycloneSecurity{dir}), 0, dds::roleIdentity("node"));
  dds::Domain domain(static_cast<dds_domainid_t>(domain_id), config);
  dds::Participant participant(domain.id());
  const dds::RunTopics topics(participant);
  // The node's own topics.
  CHECK_NOTHROW(dds::Writer<wsn_msg_ReportBatch>(participant, topics.report_batch, dds::Qos::reliableKeepAll()));
  CHECK_NOTHROW(dds::Writer<wsn_msg_ProcessStatus>(participant, topics.process_status,
                                                   dds::Qos::lastValueTransientLocal()));
  // Another role's: a node that writes deliveries or global tracks is refused.
  CHECK_THROWS_WITH(dds::Writer<wsn_msg_DeliveryBatch>(participant, topics.delivery_batch, dds::Qos::reliableKeepAll()),
                    Catch::Matchers::Contains("Not Allowed By Security", Catch::CaseSensitive::No));
  CHECK_THROWS(dds::Writer<wsn_msg_GlobalTrackBatch>(participant, topics.global_track_batch, dds::Qos::reliableKeepAll()));
  // It may read every topic of the run.
  CHECK_NOTHROW(dds::Reader<wsn_msg_TrackBatch>(participant, topics.track_batch, dds::Qos::reliableKeepAll()));
}

}  // namespace
}  // namespace wsn::launcher

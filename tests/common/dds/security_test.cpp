// The documents of a secured run (common/dds/security.hpp) and the configuration that names them:
// who may publish what, that nothing else is granted, and that each process presents its own
// identity while a viewer reading the stored file presents the viewer's.
#include <algorithm>
#include <string>

#include <catch2/catch.hpp>

#include "common/dds/cyclone_config.hpp"
#include "common/dds/role_runtime.hpp"
#include "common/dds/security.hpp"

namespace wsn::dds {
namespace {

const RunIdentity& identityNamed(const std::string& name) {
  const auto& all = runIdentities();
  const auto it = std::find_if(all.begin(), all.end(), [&](const RunIdentity& i) { return i.name == name; });
  REQUIRE(it != all.end());
  return *it;
}

bool grants(const std::vector<std::string>& topics, const char* topic) {
  return std::find(topics.begin(), topics.end(), topic) != topics.end();
}

/// The text of the grant of `name` in a permissions document.
std::string grantOf(const std::string& document, const std::string& name) {
  const auto start = document.find("<grant name=\"" + name + "\">");
  REQUIRE(start != std::string::npos);
  return document.substr(start, document.find("</grant>", start) - start);
}

TEST_CASE("each role may publish its own topics only", "[security]") {
  using namespace topic_names;
  CHECK(identityNamed("node").publish == std::vector<std::string>{kReportBatch, kSensorBoundary, kProcessStatus});
  CHECK(identityNamed("network").publish == std::vector<std::string>{kDeliveryBatch, kProcessStatus});
  CHECK(identityNamed("supernode").publish == std::vector<std::string>{kTrackBatch, kHandoffBatch, kProcessStatus});
  CHECK(grants(identityNamed("aggregator").publish, kGlobalTrackBatch));
  CHECK_FALSE(grants(identityNamed("aggregator").publish, kReportBatch));
  CHECK(identityNamed(kLauncherIdentity).publish == std::vector<std::string>{kProcessStatus});
}

TEST_CASE("the viewer reads the live topics and writes nothing", "[security]") {
  const auto& viewer = identityNamed(kViewerIdentity);
  CHECK(viewer.publish.empty());
  CHECK(viewer.subscribe == std::vector<std::string>{topic_names::kGlobalTrackBatch, topic_names::kTickMetrics,
                                                     topic_names::kProcessStatus, topic_names::kDeliveryBatch});
  const std::string document = permissionsDocument(5, "wsntrack run 1", "2026-01-01T00:00:00", "2026-01-08T00:00:00");
  const std::string grant = grantOf(document, kViewerIdentity);
  CHECK(grant.find("<publish>") == std::string::npos);
  CHECK(grant.find("<subject_name>CN=viewer,O=wsntrack run 1</subject_name>") != std::string::npos);
  CHECK(grant.find("<default>DENY</default>") != std::string::npos);
}

TEST_CASE("a grant of every topic is one pattern that matches each, keeping the document small", "[security]") {
  const std::string document = permissionsDocument(5, "wsntrack run 0123456789abcdef", "2026-01-01T00:00:00",
                                                   "2026-01-08T00:00:00");
  // The roles subscribe every topic: one pattern, which each topic's name matches.
  const std::string node = grantOf(document, "node");
  CHECK(node.find("<subscribe><topics><topic>wsn_*</topic></topics>") != std::string::npos);
  for (const char* topic : {topic_names::kSensorBoundary, topic_names::kReportBatch, topic_names::kDeliveryBatch,
                            topic_names::kHandoffBatch, topic_names::kTrackBatch, topic_names::kRehomeBatch,
                            topic_names::kGlobalTrackBatch, topic_names::kTickMetrics, topic_names::kTickDone,
                            topic_names::kProcessStatus})
    CHECK(std::string(topic).rfind("wsn_", 0) == 0);
  // A node's publish rule names its topics one by one.
  CHECK(node.find("<publish><topics><topic>wsn_report_batch</topic>") != std::string::npos);
  // The signed document goes in every handshake; 8.5 kB of it lost handshakes under the sanitizers.
  CHECK(document.size() < 5000);
}

TEST_CASE("the permissions grant every identity on the run's domain alone", "[security]") {
  const std::string document = permissionsDocument(42, "org", "2026-01-01T00:00:00", "2026-01-08T00:00:00");
  for (const auto& identity : runIdentities()) {
    const std::string grant = grantOf(document, identity.name);
    CHECK(grant.find("<min>42</min><max>42</max>") != std::string::npos);
    CHECK(grant.find("<not_before>2026-01-01T00:00:00</not_before><not_after>2026-01-08T00:00:00</not_after>") !=
          std::string::npos);
  }
}

TEST_CASE("the governance admits no unauthenticated participant and protects every message", "[security]") {
  const std::string sign = governanceDocument(3, MessageProtection::kSign);
  CHECK(sign.find("<allow_unauthenticated_participants>false</allow_unauthenticated_participants>") != std::string::npos);
  CHECK(sign.find("<enable_join_access_control>true</enable_join_access_control>") != std::string::npos);
  CHECK(sign.find("<rtps_protection_kind>SIGN</rtps_protection_kind>") != std::string::npos);
  CHECK(sign.find("<enable_write_access_control>true</enable_write_access_control>") != std::string::npos);
  CHECK(governanceDocument(3, MessageProtection::kEncrypt).find("<rtps_protection_kind>ENCRYPT</rtps_protection_kind>") !=
        std::string::npos);
}

TEST_CASE("only the four roles have role identities", "[security]") {
  for (const char* role : {"node", "network", "supernode", "aggregator"}) CHECK(roleIdentity(role) == role);
  CHECK_THROWS_AS(roleIdentity("viewer"), std::invalid_argument);
  CHECK_THROWS_AS(roleIdentity("test"), std::invalid_argument);
}

TEST_CASE("a secured configuration names the run's credentials and each process's own identity", "[security]") {
  if (securityPluginDirectory().empty()) FAIL("this build found no Cyclone DDS security plugins");
  const std::string stored = cycloneConfigTemplate(1, 5, {}, CycloneSecurity{"/runs/r/credentials"});
  CHECK(stored.find("<IdentityCA>file:/runs/r/credentials/ca.pem</IdentityCA>") != std::string::npos);
  CHECK(stored.find("<Governance>file:/runs/r/credentials/governance.p7s</Governance>") != std::string::npos);
  CHECK(stored.find(securityPluginDirectory() + "/libdds_security_auth.so") != std::string::npos);
  // The stored file, as a viewer reads it through CYCLONEDDS_URI: Cyclone expands the default.
  CHECK(stored.find("file:/runs/r/credentials/${WSN_IDENTITY:-viewer}.cert.pem") != std::string::npos);
  const std::string supernode = cycloneConfigFor(stored, 2, "supernode");
  CHECK(supernode.find("file:/runs/r/credentials/supernode.cert.pem") != std::string::npos);
  CHECK(supernode.find("file:/runs/r/credentials/supernode.key.pem") != std::string::npos);
  CHECK(supernode.find("WSN_IDENTITY") == std::string::npos);
  // Security off: no section, and an identity changes nothing.
  const std::string open = cycloneConfigTemplate(1, 5);
  CHECK(open.find("<Security>") == std::string::npos);
  CHECK(cycloneConfigFor(open, 2, "supernode") == cycloneConfigFor(open, 2));
}

}  // namespace
}  // namespace wsn::dds

#include "common/dds/security.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "common/dds/role_runtime.hpp"

namespace wsn::dds {
namespace {

using namespace topic_names;

/// Every topic of a run: what dds::RunTopics creates.
std::vector<std::string> everyTopic() {
  return {kSensorBoundary, kReportBatch,  kDeliveryBatch, kHandoffBatch, kTrackBatch,
          kRehomeBatch,    kGlobalTrackBatch, kTickMetrics,   kTickDone,     kProcessStatus};
}

/// Every topic of a run as a permissions pattern (fnmatch): their names all start so.
constexpr const char* kEveryTopicPattern = "wsn_*";

std::vector<RunIdentity> makeIdentities() {
  return {
      {"node", {kReportBatch, kSensorBoundary, kProcessStatus}, everyTopic()},
      {"network", {kDeliveryBatch, kProcessStatus}, everyTopic()},
      {"supernode", {kTrackBatch, kHandoffBatch, kProcessStatus}, everyTopic()},
      {"aggregator", {kGlobalTrackBatch, kTickMetrics, kTickDone, kRehomeBatch, kProcessStatus}, everyTopic()},
      {kInProcessIdentity, everyTopic(), everyTopic()},
      // The launcher announces processes lost outside the scenario's faults (FAULTED at tick 0).
      {kLauncherIdentity, {kProcessStatus}, {kProcessStatus}},
      // The viewer reads; the deliveries are for the browser map's reports (wsntrack watch --http).
      {kViewerIdentity, {}, {kGlobalTrackBatch, kTickMetrics, kProcessStatus, kDeliveryBatch}},
  };
}

void domainRange(std::ostringstream& xml, int domain, const char* indent) {
  xml << indent << "<domains><id_range><min>" << domain << "</min><max>" << domain << "</max></id_range></domains>\n";
}

/// A publish or subscribe rule for `topics` in any partition: the roles address deliveries and
/// handoffs through partitions (topic_names::supernodePartition), and a rule that names none
/// covers only the default partition. Every topic of the run is written as one pattern: the signed
/// document travels in each authentication handshake, and Cyclone 0.10.2 lost handshakes of a
/// document 33 bytes longer than 8.5 kB under the sanitizers (roles never matched: CI at 80082df),
/// which the pattern keeps well below (about 6.7 kB).
void topicList(std::ostringstream& xml, const char* element, const std::vector<std::string>& topics) {
  if (topics.empty()) return;
  xml << "        <" << element << "><topics>";
  if (topics == everyTopic()) {
    xml << "<topic>" << kEveryTopicPattern << "</topic>";
    xml << "</topics><partitions><partition>*</partition></partitions></" << element << ">\n";
    return;
  }
  for (const auto& topic : topics) xml << "<topic>" << topic << "</topic>";
  xml << "</topics><partitions><partition>*</partition></partitions></" << element << ">\n";
}

}  // namespace

const std::vector<RunIdentity>& runIdentities() {
  static const std::vector<RunIdentity> identities = makeIdentities();
  return identities;
}

const std::string& roleIdentity(const std::string& role) {
  static const std::vector<std::string> roles = {"node", "network", "supernode", "aggregator"};
  const auto it = std::find(roles.begin(), roles.end(), role);
  if (it == roles.end()) throw std::invalid_argument("no security identity for role '" + role + "'");
  return *it;
}

std::string subjectName(const std::string& identity, const std::string& organization) {
  return "CN=" + identity + ",O=" + organization;
}

std::string runOrganization(std::uint64_t run_id) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(run_id));
  return std::string("wsntrack run ") + hex;
}

std::string governanceDocument(int domain, MessageProtection protection) {
  const std::string kind = protection == MessageProtection::kSign ? "SIGN" : "ENCRYPT";
  std::ostringstream xml;
  // The RTPS protection covers every message after the handshake, discovery and liveliness
  // included, so the per-topic protections stay NONE (they would protect the same bytes twice).
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
         "xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-Security/20170801/omg_shared_ca_governance.xsd\">\n"
      << "  <domain_access_rules>\n"
      << "    <domain_rule>\n";
  domainRange(xml, domain, "      ");
  xml << "      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>\n"
      << "      <enable_join_access_control>true</enable_join_access_control>\n"
      << "      <discovery_protection_kind>NONE</discovery_protection_kind>\n"
      << "      <liveliness_protection_kind>NONE</liveliness_protection_kind>\n"
      << "      <rtps_protection_kind>" << kind << "</rtps_protection_kind>\n"
      << "      <topic_access_rules>\n"
      << "        <topic_rule>\n"
      << "          <topic_expression>*</topic_expression>\n"
      << "          <enable_discovery_protection>false</enable_discovery_protection>\n"
      << "          <enable_liveliness_protection>false</enable_liveliness_protection>\n"
      << "          <enable_read_access_control>true</enable_read_access_control>\n"
      << "          <enable_write_access_control>true</enable_write_access_control>\n"
      << "          <metadata_protection_kind>NONE</metadata_protection_kind>\n"
      << "          <data_protection_kind>NONE</data_protection_kind>\n"
      << "        </topic_rule>\n"
      << "      </topic_access_rules>\n"
      << "    </domain_rule>\n"
      << "  </domain_access_rules>\n"
      << "</dds>\n";
  return xml.str();
}

std::string permissionsDocument(int domain, const std::string& organization, const std::string& not_before,
                                const std::string& not_after) {
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
         "xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-Security/20170801/omg_shared_ca_permissions.xsd\">\n"
      << "  <permissions>\n";
  for (const auto& identity : runIdentities()) {
    xml << "    <grant name=\"" << identity.name << "\">\n"
        << "      <subject_name>" << subjectName(identity.name, organization) << "</subject_name>\n"
        << "      <validity><not_before>" << not_before << "</not_before><not_after>" << not_after
        << "</not_after></validity>\n"
        << "      <allow_rule>\n";
    domainRange(xml, domain, "        ");
    topicList(xml, "publish", identity.publish);
    topicList(xml, "subscribe", identity.subscribe);
    xml << "      </allow_rule>\n"
        << "      <default>DENY</default>\n"
        << "    </grant>\n";
  }
  xml << "  </permissions>\n"
      << "</dds>\n";
  return xml.str();
}

}  // namespace wsn::dds

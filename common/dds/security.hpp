// Who may take part in a run under DDS Security, and what each may do: the run's identities
// (one per role, the launcher, a read-only viewer), the governance document (only authenticated
// participants; every RTPS message signed or encrypted) and the permissions document that grants
// each identity its topics (docs/SECURITY.md). The documents are plain XML here; the launcher
// signs them with the run's own certificate authority.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/scenario_config.hpp"

namespace wsn::dds {

/// How a secured run protects each RTPS message (OMG DDS Security 1.1, 9.4.1.2.3): sign (a MAC
/// per message: nothing unauthenticated gets in, a reader on the wire still sees the data) or
/// encrypt (AES-GCM: neither).
using common::MessageProtection;

/// One identity of a run: the stem of its credential files and its certificate's common name,
/// and the topics it may publish and subscribe to.
struct RunIdentity {
  std::string name;
  std::vector<std::string> publish;
  std::vector<std::string> subscribe;
};

/// Every identity of a secured run: node, network, supernode, aggregator (each role's processes
/// share their role's), in-process (every role's rights, for a run whose roles are threads of
/// the launcher), launcher (its status observer: process status only) and viewer (wsntrack
/// watch, examples/: reads the global tracks, the tick metrics and process status, writes
/// nothing). A role's participant creates every topic of the run (dds::RunTopics), which DDS
/// Security allows only for topics it may read or write: the roles may read every topic, and
/// publish only their own.
const std::vector<RunIdentity>& runIdentities();

/// The identity of role processes named `role` ("node", "network", "supernode", "aggregator");
/// throws std::invalid_argument for another name.
const std::string& roleIdentity(const std::string& role);

/// The identity names of the launcher's observer and of live viewers.
inline constexpr const char* kLauncherIdentity = "launcher";
inline constexpr const char* kInProcessIdentity = "in-process";
inline constexpr const char* kViewerIdentity = "viewer";

/// The subject name of `identity`'s certificate in a run whose certificates carry
/// `organization` (the launcher's RunAuthority makes them so).
std::string subjectName(const std::string& identity, const std::string& organization);

/// The organization of every certificate of run `run_id`.
std::string runOrganization(std::uint64_t run_id);

/// The governance document of a secured run on `domain`: unauthenticated participants are
/// refused, joining and every topic's readers and writers are checked against the permissions,
/// and every RTPS message is protected as `protection` says.
std::string governanceDocument(int domain, MessageProtection protection);

/// The permissions document granting each of runIdentities() its topics on `domain`, by subject
/// name, valid from `not_before` to `not_after` (UTC, "YYYY-MM-DDTHH:MM:SS"); anything not
/// granted is denied.
std::string permissionsDocument(int domain, const std::string& organization, const std::string& not_before,
                                const std::string& not_after);

}  // namespace wsn::dds

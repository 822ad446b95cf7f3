// Per-run credentials for Cyclone DDS's DDS Security plugins: a certificate authority made in memory
// for one run, the roles' identity certificates, and the S/MIME signature of governance and permissions.
#pragma once

#include <chrono>
#include <memory>
#include <string>

namespace wsn::launcher {

/// A PEM certificate and its private key, and the subject name as DDS Security permissions
/// documents quote it.
struct IssuedIdentity {
  std::string certificate_pem;
  std::string private_key_pem;  ///< unencrypted PKCS#8 PEM ("-----BEGIN PRIVATE KEY-----")
  /// "CN=<common name>,O=<organization>", e.g. "CN=supernode-3,O=wsntrack run 1a2b3c". Cyclone's
  /// access control splits it and the certificate's subject into name=value pairs at ',', '/' and
  /// '|' and compares the pairs, so it goes into <subject_name> verbatim (no spaces after commas).
  std::string subject_name;
};

/// The certificate authority of one run: an EC prime256v1 key and a self-signed CA certificate,
/// made in memory (the key never touches disk). It issues the roles' identity certificates and
/// signs the governance and permissions documents (identity CA and permissions CA are the same).
class RunAuthority {
 public:
  /// `organization`: the O= of every subject (the launcher passes "wsntrack run <run id hex>");
  /// [A-Za-z0-9._-] words separated by single spaces, else std::invalid_argument (anything else
  /// would be escaped or split differently by Cyclone's subject comparison). Every certificate is
  /// valid from an hour before now (slack for other hosts' clocks) for `validity`, which must
  /// exceed that hour and be at most 100 years (std::invalid_argument). The CA's subject is
  /// "CN=wsntrack run authority,O=organization": the spaces keep it from ever equalling an
  /// identity's subject. A moved-from authority may only be destroyed or assigned to.
  RunAuthority(const std::string& organization, std::chrono::hours validity);
  ~RunAuthority();
  RunAuthority(RunAuthority&&) noexcept;
  RunAuthority& operator=(RunAuthority&&) noexcept;
  RunAuthority(const RunAuthority&) = delete;
  RunAuthority& operator=(const RunAuthority&) = delete;

  /// The CA certificate (PEM): Cyclone's identity_ca and permissions_ca.
  const std::string& certificatePem() const;

  /// A new EC prime256v1 key and an identity certificate with subject CN=common_name,O=organization,
  /// signed by the authority (SHA-256), valid as long as the CA. Throws std::invalid_argument for an
  /// empty common name or one with characters other than [A-Za-z0-9._-].
  IssuedIdentity issue(const std::string& common_name) const;

  /// `document` signed as S/MIME multipart/signed (detached signature, text mode, signer
  /// certificate included), as `openssl smime -sign -text -in doc -signer ca.pem -inkey ca.key`
  /// makes it (same layout, digest and attributes; the boundary, signing time and ECDSA signature
  /// differ from run to run). Text mode signs the document with CRLF line ends behind a
  /// "Content-Type: text/plain" header, and verifying it with PKCS7_TEXT (as Cyclone does) gives
  /// the document back with its "\n" turned into "\r\n", which XML parsers read alike.
  std::string sign(const std::string& document) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace wsn::launcher

// The run's DDS Security credentials (launcher/credentials.cpp), checked the way Cyclone DDS 0.10's
// plugins check them: X509_verify_cert against a store holding only the CA (auth_utils.c,
// verify_certificate), SMIME_read_PKCS7 + PKCS7_verify(PKCS7_TEXT) (access_control_utils.c,
// ac_PKCS7_document_check), and its name=value subject comparison (ac_check_subjects_are_equal).
#include "launcher/credentials.hpp"
#include "launcher/openssl_handles.hpp"

#include <openssl/bio.h>
#include <openssl/bn.h>
#include <openssl/evp.h>
#include <openssl/objects.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>
#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace wsn::launcher {
namespace {

using namespace openssl;

constexpr const char* kOrganization = "wsntrack run 1a2b3c";
constexpr std::chrono::hours kValidity{48};
constexpr const char* kOpenssl = "/usr/bin/openssl";

constexpr const char* kPermissions =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\">\n"
    "  <permissions>\n"
    "    <grant name=\"supernode-3\">\n"
    "      <subject_name>CN=supernode-3,O=wsntrack run 1a2b3c</subject_name>\n"
    "    </grant>\n"
    "  </permissions>\n"
    "</dds>\n";

X509Ptr certificateOf(const std::string& pem) {
  const BioPtr bio(BIO_new_mem_buf(pem.data(), static_cast<int>(pem.size())));
  X509Ptr certificate(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
  REQUIRE(certificate);
  return certificate;
}

PkeyPtr privateKeyOf(const std::string& pem) {
  const BioPtr bio(BIO_new_mem_buf(pem.data(), static_cast<int>(pem.size())));
  PkeyPtr key(PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, const_cast<char*>("")));
  REQUIRE(key);
  return key;
}

/// Cyclone's verify_certificate without a CRL: a store with the CA alone, default parameters.
bool verifiesAgainst(X509* certificate, X509* ca) {
  const StorePtr store(X509_STORE_new());
  REQUIRE(X509_STORE_add_cert(store.get(), ca) == 1);
  const StoreContextPtr context(X509_STORE_CTX_new());
  REQUIRE(X509_STORE_CTX_init(context.get(), store.get(), certificate, nullptr) == 1);
  return X509_verify_cert(context.get()) == 1;
}

std::string printed(const X509_NAME* name, unsigned long flags) {
  const BioPtr bio(BIO_new(BIO_s_mem()));
  X509_NAME_print_ex(bio.get(), name, 0, flags);
  char* data = nullptr;
  const long size = BIO_get_mem_data(bio.get(), &data);
  return std::string(data, static_cast<std::size_t>(size));
}

/// Cyclone's ac_check_subjects_are_equal: every name=value of the identity's subject (split at
/// ',', '/', '|' and the first '=') is in the permissions' subject with the same value.
bool cycloneSubjectsEqual(const std::string& permissions_sn, const std::string& identity_sn) {
  // Each token between separators as (name, value after the first '='), value absent without '='.
  const auto pairs = [](std::string subject) {
    for (char& c : subject)
      if (c == '/' || c == '|') c = ',';
    std::vector<std::pair<std::string, std::optional<std::string>>> out;
    std::istringstream in(subject);
    for (std::string token; std::getline(in, token, ',');) {
      const auto eq = token.find('=');
      if (eq == std::string::npos)
        out.emplace_back(token, std::nullopt);
      else
        out.emplace_back(token.substr(0, eq), token.substr(eq + 1));
    }
    return out;
  };
  std::map<std::string, std::string> permitted;  // the first value of a name counts, as in Cyclone
  for (const auto& [name, value] : pairs(permissions_sn)) {
    if (name.empty() && !value) continue;  // string_to_properties skips empty tokens
    if (!value) return false;
    permitted.emplace(name, *value);
  }
  for (const auto& [name, value] : pairs(identity_sn)) {
    const auto found = permitted.find(name);
    if (!value || found == permitted.end() || found->second != *value) return false;
  }
  return true;
}

/// Cyclone's ac_PKCS7_document_check: the verified document, or nothing when it does not verify.
std::optional<std::string> cycloneVerified(const std::string& smime, X509* ca) {
  const BioPtr in(BIO_new_mem_buf(smime.data(), static_cast<int>(smime.size())));
  BIO* content_raw = nullptr;
  const Pkcs7Ptr pkcs7(SMIME_read_PKCS7(in.get(), &content_raw));
  const BioPtr content(content_raw);
  if (!pkcs7) return std::nullopt;
  const StorePtr store(X509_STORE_new());
  REQUIRE(X509_STORE_add_cert(store.get(), ca) == 1);
  const BioPtr out(BIO_new(BIO_s_mem()));
  if (PKCS7_verify(pkcs7.get(), nullptr, store.get(), content.get(), out.get(), PKCS7_TEXT) != 1) return std::nullopt;
  char* data = nullptr;
  const long size = BIO_get_mem_data(out.get(), &data);
  return std::string(data, static_cast<std::size_t>(size));
}

/// The document as S/MIME text mode signs it and PKCS7_verify(PKCS7_TEXT) returns it: "\n" as "\r\n".
std::string withCrlf(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '\n') out += '\r';
    out += c;
  }
  return out;
}

/// A directory of this test's own under the system's temporary directory, removed at the end.
struct TempDirectory {
  std::filesystem::path path;
  TempDirectory() {
    static std::atomic<int> counter{0};
    path = std::filesystem::temp_directory_path() /
           ("wsn_credentials_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(path);
  }
  ~TempDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  TempDirectory(const TempDirectory&) = delete;
  TempDirectory& operator=(const TempDirectory&) = delete;
  std::string write(const std::string& name, const std::string& content) const {
    std::ofstream(path / name, std::ios::binary) << content;
    return (path / name).string();
  }
  std::string read(const std::string& name) const {
    std::ifstream in(path / name, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
};

bool haveOpenssl() { return ::access(kOpenssl, X_OK) == 0; }

/// Runs the openssl command with `arguments` (paths inside `dir`), quiet; true when it exits 0.
bool runOpenssl(const TempDirectory& dir, const std::string& arguments) {
  const std::string command =
      "cd '" + dir.path.string() + "' && " + kOpenssl + " " + arguments + " >/dev/null 2>&1";
  return std::system(command.c_str()) == 0;
}

TEST_CASE("the authority's certificate is a self-signed CA that is valid now", "[launcher][credentials]") {
  const RunAuthority authority(kOrganization, kValidity);
  const X509Ptr ca = certificateOf(authority.certificatePem());

  CHECK(X509_check_issued(ca.get(), ca.get()) == X509_V_OK);
  const PkeyPtr key(X509_get_pubkey(ca.get()));
  CHECK(X509_verify(ca.get(), key.get()) == 1);
  // Cyclone's check_key_type_and_size accepts EC keys of exactly 256 bits (or RSA 2048).
  CHECK(EVP_PKEY_get_id(key.get()) == EVP_PKEY_EC);
  CHECK(EVP_PKEY_get_bits(key.get()) == 256);
  CHECK(X509_get_signature_nid(ca.get()) == NID_ecdsa_with_SHA256);
  CHECK(X509_get_version(ca.get()) == X509_VERSION_3);

  // X509_check_ca is 1 for basicConstraints CA:TRUE; the extension is marked critical.
  CHECK(X509_check_ca(ca.get()) == 1);
  const int constraints = X509_get_ext_by_NID(ca.get(), NID_basic_constraints, -1);
  REQUIRE(constraints >= 0);
  CHECK(X509_EXTENSION_get_critical(X509_get_ext(ca.get(), constraints)) == 1);
  CHECK(X509_get_key_usage(ca.get()) == (KU_KEY_CERT_SIGN | KU_CRL_SIGN | KU_DIGITAL_SIGNATURE));

  // Valid now: notBefore in the past (-1), notAfter in the future (1); the window is an hour
  // before construction plus 48 h, i.e. exactly 2 days from notBefore to notAfter.
  CHECK(X509_cmp_current_time(X509_get0_notBefore(ca.get())) == -1);
  CHECK(X509_cmp_current_time(X509_get0_notAfter(ca.get())) == 1);
  int days = -1;
  int seconds = -1;
  REQUIRE(ASN1_TIME_diff(&days, &seconds, X509_get0_notBefore(ca.get()), X509_get0_notAfter(ca.get())) == 1);
  CHECK(days == 2);
  CHECK(seconds == 0);
  // And notBefore is an hour ago: between 3600 s and 3600 s + a minute of slow test before now.
  REQUIRE(ASN1_TIME_diff(&days, &seconds, X509_get0_notBefore(ca.get()), nullptr) == 1);
  CHECK(days == 0);
  CHECK(seconds >= 3600);
  CHECK(seconds <= 3660);
}

TEST_CASE("an issued certificate verifies against its authority and carries its subject name",
          "[launcher][credentials]") {
  const RunAuthority authority(kOrganization, kValidity);
  const X509Ptr ca = certificateOf(authority.certificatePem());
  const IssuedIdentity identity = authority.issue("supernode-3");
  const X509Ptr certificate = certificateOf(identity.certificate_pem);

  CHECK(verifiesAgainst(certificate.get(), ca.get()));
  CHECK(identity.subject_name == "CN=supernode-3,O=wsntrack run 1a2b3c");
  // Exactly CN then O: printed in certificate order (RFC 2253 without its reversal) it is the
  // returned string; Cyclone prints it RFC 2253 style, last entry first.
  const X509_NAME* subject = X509_get_subject_name(certificate.get());
  CHECK(X509_NAME_entry_count(subject) == 2);
  CHECK(printed(subject, XN_FLAG_RFC2253 & ~XN_FLAG_DN_REV) == identity.subject_name);
  const std::string cyclone_view = printed(subject, XN_FLAG_RFC2253);
  CHECK(cyclone_view == "O=wsntrack run 1a2b3c,CN=supernode-3");
  CHECK(cycloneSubjectsEqual(identity.subject_name, cyclone_view));
  // The negative control of that comparison: another role's grant does not match.
  CHECK_FALSE(cycloneSubjectsEqual("CN=supernode-2,O=wsntrack run 1a2b3c", cyclone_view));
  CHECK_FALSE(cycloneSubjectsEqual("CN=supernode-3, O=wsntrack run 1a2b3c", cyclone_view));

  const PkeyPtr key = privateKeyOf(identity.private_key_pem);
  CHECK(identity.private_key_pem.rfind("-----BEGIN PRIVATE KEY-----\n", 0) == 0);
  CHECK(X509_check_private_key(certificate.get(), key.get()) == 1);
  CHECK(EVP_PKEY_get_bits(key.get()) == 256);
  CHECK(X509_get_signature_nid(certificate.get()) == NID_ecdsa_with_SHA256);
  CHECK(X509_check_ca(certificate.get()) == 0);
  CHECK(X509_get_key_usage(certificate.get()) == (KU_DIGITAL_SIGNATURE | KU_KEY_AGREEMENT));

  // A 128-bit positive serial, different for the next certificate.
  const BignumPtr serial(ASN1_INTEGER_to_BN(X509_get0_serialNumber(certificate.get()), nullptr));
  CHECK(BN_num_bits(serial.get()) == 128);
  CHECK_FALSE(BN_is_negative(serial.get()));
  const X509Ptr next = certificateOf(authority.issue("supernode-3").certificate_pem);
  CHECK(ASN1_INTEGER_cmp(X509_get0_serialNumber(certificate.get()), X509_get0_serialNumber(next.get())) != 0);
}

TEST_CASE("a certificate from another authority does not verify against this one", "[launcher][credentials]") {
  // The same organization: only the key tells the two authorities apart.
  const RunAuthority authority(kOrganization, kValidity);
  const RunAuthority other(kOrganization, kValidity);
  const X509Ptr ca = certificateOf(authority.certificatePem());
  const X509Ptr foreign = certificateOf(other.issue("supernode-3").certificate_pem);
  const X509Ptr own = certificateOf(authority.issue("supernode-3").certificate_pem);
  CHECK(verifiesAgainst(own.get(), ca.get()));
  CHECK_FALSE(verifiesAgainst(foreign.get(), ca.get()));
}

TEST_CASE("a signed document verifies as Cyclone reads it and gives the document back",
          "[launcher][credentials]") {
  const RunAuthority authority(kOrganization, kValidity);
  const X509Ptr ca = certificateOf(authority.certificatePem());
  const std::string signed_document = authority.sign(kPermissions);

  CHECK(signed_document.find("Content-Type: multipart/signed; protocol=\"application/x-pkcs7-signature\"; "
                             "micalg=\"sha-256\"") != std::string::npos);
  const auto verified = cycloneVerified(signed_document, ca.get());
  REQUIRE(verified);
  CHECK(*verified == withCrlf(kPermissions));

  // One character of the clear-text copy changed after signing: the digest no longer matches.
  std::string altered = signed_document;
  const auto at = altered.find("CN=supernode-3");
  REQUIRE(at != std::string::npos);
  altered[at + 13] = '4';
  CHECK_FALSE(cycloneVerified(altered, ca.get()));

  // Signed by another run's authority: its certificate is in the message but not in the store.
  const RunAuthority other(kOrganization, kValidity);
  CHECK_FALSE(cycloneVerified(other.sign(kPermissions), ca.get()));
}

TEST_CASE("the openssl command verifies a signed document", "[launcher][credentials]") {
  if (!haveOpenssl()) {
    WARN("no " << kOpenssl << ": the command-line check is not run");
    return;
  }
  const RunAuthority authority(kOrganization, kValidity);
  const TempDirectory dir;
  dir.write("ca.pem", authority.certificatePem());
  dir.write("signed.p7s", authority.sign(kPermissions));
  CHECK(runOpenssl(dir, "smime -verify -text -CAfile ca.pem -in signed.p7s -out verified.xml"));
  CHECK(dir.read("verified.xml") == withCrlf(kPermissions));

  std::string altered = authority.sign(kPermissions);
  altered[altered.find("CN=supernode-3") + 13] = '4';
  dir.write("altered.p7s", altered);
  CHECK_FALSE(runOpenssl(dir, "smime -verify -text -CAfile ca.pem -in altered.p7s -out altered.xml"));
}

/// The S/MIME text up to the base64 signature, with its boundary replaced by "BOUNDARY": what is
/// the same every time a document is signed.
std::string layoutOf(const std::string& smime) {
  const std::string marker = "boundary=\"";
  const auto start = smime.find(marker);
  REQUIRE(start != std::string::npos);
  const auto end = smime.find('"', start + marker.size());
  const std::string boundary = smime.substr(start + marker.size(), end - start - marker.size());
  const std::string last_header = "filename=\"smime.p7s\"\n\n";
  const auto cut = smime.find(last_header);
  REQUIRE(cut != std::string::npos);
  std::string layout = smime.substr(0, cut + last_header.size());
  for (auto at = layout.find(boundary); at != std::string::npos; at = layout.find(boundary, at))
    layout.replace(at, boundary.size(), "BOUNDARY");
  return layout;
}

TEST_CASE("a signed document is laid out as openssl smime -sign -text lays it out", "[launcher][credentials]") {
  if (!haveOpenssl()) {
    WARN("no " << kOpenssl << ": the command-line comparison is not run");
    return;
  }
  // The command signs with an identity's key and certificate (both P-256, so SHA-256 either way):
  // the authority's own key never leaves memory.
  const RunAuthority authority(kOrganization, kValidity);
  const IssuedIdentity signer = authority.issue("launcher");
  const TempDirectory dir;
  dir.write("signer.pem", signer.certificate_pem);
  dir.write("signer.key", signer.private_key_pem);
  dir.write("doc.xml", kPermissions);
  REQUIRE(runOpenssl(dir, "smime -sign -text -in doc.xml -signer signer.pem -inkey signer.key -out doc.p7s"));
  CHECK(layoutOf(authority.sign(kPermissions)) == layoutOf(dir.read("doc.p7s")));
}

TEST_CASE("issue refuses common names Cyclone would split or escape", "[launcher][credentials]") {
  const RunAuthority authority(kOrganization, kValidity);
  CHECK_THROWS_AS(authority.issue(""), std::invalid_argument);
  CHECK_THROWS_AS(authority.issue("node,0"), std::invalid_argument);
  CHECK_THROWS_AS(authority.issue("CN=node-0"), std::invalid_argument);
  CHECK_THROWS_AS(authority.issue("node/0"), std::invalid_argument);
  CHECK_THROWS_AS(authority.issue("node 0"), std::invalid_argument);
  CHECK_NOTHROW(authority.issue("Node_0.tile-1"));
}

TEST_CASE("the authority refuses organizations it could not quote and windows already over",
          "[launcher][credentials]") {
  CHECK_THROWS_AS(RunAuthority("wsntrack, run", kValidity), std::invalid_argument);
  CHECK_THROWS_AS(RunAuthority("O=x", kValidity), std::invalid_argument);
  CHECK_THROWS_AS(RunAuthority(" wsntrack", kValidity), std::invalid_argument);
  CHECK_THROWS_AS(RunAuthority("wsntrack  run", kValidity), std::invalid_argument);
  CHECK_THROWS_AS(RunAuthority("", kValidity), std::invalid_argument);
  // Certificates start an hour back, so an hour's validity would end now.
  CHECK_THROWS_AS(RunAuthority(kOrganization, std::chrono::hours(1)), std::invalid_argument);
  CHECK_NOTHROW(RunAuthority(kOrganization, std::chrono::hours(2)));
}

TEST_CASE("a moved authority keeps issuing from the same key", "[launcher][credentials]") {
  RunAuthority first(kOrganization, kValidity);
  const std::string pem = first.certificatePem();
  const RunAuthority moved(std::move(first));
  CHECK(moved.certificatePem() == pem);
  const X509Ptr ca = certificateOf(pem);
  const X509Ptr issued = certificateOf(moved.issue("node-0").certificate_pem);
  CHECK(verifiesAgainst(issued.get(), ca.get()));
}

}  // namespace
}  // namespace wsn::launcher

// A run's certificate authority and its identity certificates and S/MIME signatures, made with the
// OpenSSL 3 C API in the forms Cyclone DDS 0.10's builtin security plugins accept
// (src/security/builtin_plugins/{authentication,access_control}/src/*_utils.c).
#include "launcher/credentials.hpp"
#include "launcher/openssl_handles.hpp"

#include <openssl/asn1.h>
#include <openssl/bio.h>
#include <openssl/bn.h>
#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/objects.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/rand.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>

#include <array>
#include <climits>
#include <ctime>
#include <stdexcept>
#include <utility>

namespace wsn::launcher {
namespace {

using namespace openssl;

// Cyclone's authentication plugin takes EC keys of 256 bits or RSA keys of 2048 (auth_utils.c,
// check_key_type_and_size); P-256 is the smaller and faster of the two, for keys and handshakes.
constexpr const char* kCurve = "P-256";
// The CA's common name has spaces, which issue() refuses in a common name, so no identity can
// ever carry the CA's subject and look self-issued to a chain builder.
constexpr const char* kAuthorityCommonName = "wsntrack run authority";
// Certificates start an hour in the past so that hosts whose clocks lag still accept them
// (Cyclone refuses a certificate whose notBefore is ahead of its own clock).
constexpr long kBackdateSeconds = 3600;
constexpr std::chrono::hours kMaxValidity{24 * 365 * 100};

/// Throws std::runtime_error "credentials: <what> failed: <OpenSSL errors>", emptying the queue.
[[noreturn]] void throwOpenssl(const std::string& what) {
  std::string message = "credentials: " + what + " failed";
  const char* separator = ": ";
  std::array<char, 256> text{};
  for (unsigned long code = ERR_get_error(); code != 0; code = ERR_get_error()) {
    ERR_error_string_n(code, text.data(), text.size());
    message += separator;
    message += text.data();
    separator = "; ";
  }
  throw std::runtime_error(message);
}

/// For the many OpenSSL calls that return a positive number on success and 0 or -1 on failure.
void check(long rc, const std::string& what) {
  if (rc <= 0) throwOpenssl(what);
}

template <class T>
T* checked(T* object, const std::string& what) {
  if (object == nullptr) throwOpenssl(what);
  return object;
}

bool isNameCharacter(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
         c == '-';
}

// Cyclone prints a certificate's subject as RFC 2253 (escaping ,+"\<>;#= and edge spaces) and
// then splits it at ',', '/' and '|' and at the first '='; these characters pass both unchanged.
void requireCommonName(const std::string& name) {
  if (name.empty()) throw std::invalid_argument("credentials: an identity needs a common name");
  for (const char c : name)
    if (!isNameCharacter(c))
      throw std::invalid_argument("credentials: common name '" + name + "' has a character outside [A-Za-z0-9._-]");
}

void requireOrganization(const std::string& organization) {
  bool word_start = true;  // an empty name, a leading, trailing or doubled space all fail here
  for (const char c : organization) {
    if (c == ' ' && !word_start) {
      word_start = true;
    } else if (isNameCharacter(c)) {
      word_start = false;
    } else {
      word_start = true;
      break;
    }
  }
  if (word_start)
    throw std::invalid_argument("credentials: organization '" + organization +
                                "' is not words of [A-Za-z0-9._-] separated by single spaces");
}

PkeyPtr newKey() {
  PkeyPtr key(EVP_PKEY_Q_keygen(nullptr, nullptr, "EC", kCurve));
  if (!key) throwOpenssl("generating an EC P-256 key");
  return key;
}

/// Exactly the two entries CN, O in this order, so that the certificate and subjectNameOf agree.
NamePtr nameOf(const std::string& common_name, const std::string& organization) {
  NamePtr name(checked(X509_NAME_new(), "allocating a subject name"));
  for (const auto& [field, value] : {std::pair{"CN", &common_name}, std::pair{"O", &organization}})
    check(X509_NAME_add_entry_by_txt(name.get(), field, MBSTRING_UTF8,
                                     reinterpret_cast<const unsigned char*>(value->c_str()), -1, -1, 0),
          std::string("setting ") + field + " of a subject name");
  return name;
}

std::string subjectNameOf(const std::string& common_name, const std::string& organization) {
  return "CN=" + common_name + ",O=" + organization;
}

void setRandomSerial(X509* certificate) {
  std::array<unsigned char, 16> bytes{};
  check(RAND_bytes(bytes.data(), static_cast<int>(bytes.size())), "drawing a serial number");
  // The top bit set: a 128-bit number, never zero; BN_bin2bn reads it unsigned, so it is positive.
  bytes[0] |= 0x80;
  const BignumPtr serial(checked(BN_bin2bn(bytes.data(), static_cast<int>(bytes.size()), nullptr), "reading a serial"));
  checked(BN_to_ASN1_INTEGER(serial.get(), X509_get_serialNumber(certificate)), "setting a serial number");
}

/// An unsigned v3 certificate of `key` for `subject`, by `issuer`, with a random serial.
X509Ptr newCertificate(EVP_PKEY* key, const X509_NAME* subject, const X509_NAME* issuer) {
  X509Ptr certificate(checked(X509_new(), "allocating a certificate"));
  check(X509_set_version(certificate.get(), X509_VERSION_3), "setting a certificate's version");
  setRandomSerial(certificate.get());
  check(X509_set_subject_name(certificate.get(), subject), "setting a certificate's subject");
  check(X509_set_issuer_name(certificate.get(), issuer), "setting a certificate's issuer");
  check(X509_set_pubkey(certificate.get(), key), "setting a certificate's public key");
  return certificate;
}

/// Adds an extension written as in an openssl.cnf ("critical,CA:TRUE"); `issuer` is read by the
/// authority key identifier.
void addExtension(X509* certificate, X509* issuer, int nid, const char* value) {
  X509V3_CTX context;
  X509V3_set_ctx_nodb(&context);
  X509V3_set_ctx(&context, issuer, certificate, nullptr, nullptr, 0);
  const ExtensionPtr extension(X509V3_EXT_conf_nid(nullptr, &context, nid, value));
  if (!extension) throwOpenssl(std::string("making extension ") + OBJ_nid2sn(nid) + "=" + value);
  check(X509_add_ext(certificate, extension.get(), -1), std::string("adding extension ") + OBJ_nid2sn(nid));
}

std::string contentsOf(BIO* bio) {
  char* data = nullptr;
  const long size = BIO_get_mem_data(bio, &data);
  return size > 0 ? std::string(data, static_cast<std::size_t>(size)) : std::string();
}

BioPtr memoryBio() { return BioPtr(checked(BIO_new(BIO_s_mem()), "allocating a memory BIO")); }

std::string pemOf(X509* certificate) {
  const BioPtr bio = memoryBio();
  check(PEM_write_bio_X509(bio.get(), certificate), "writing a certificate as PEM");
  return contentsOf(bio.get());
}

/// PKCS#8 ("BEGIN PRIVATE KEY"), unencrypted: Cyclone reads it with PEM_read_bio_PrivateKey and
/// an empty password when the configuration gives none.
std::string pemOf(EVP_PKEY* key) {
  const BioPtr bio = memoryBio();
  check(PEM_write_bio_PrivateKey(bio.get(), key, nullptr, nullptr, 0, nullptr, nullptr), "writing a key as PEM");
  return contentsOf(bio.get());
}

}  // namespace

struct RunAuthority::State {
  std::string organization;
  PkeyPtr key;
  X509Ptr certificate;
  std::string certificate_pem;
};

RunAuthority::RunAuthority(const std::string& organization, std::chrono::hours validity)
    : state_(std::make_unique<State>()) {
  requireOrganization(organization);
  if (validity <= std::chrono::hours(kBackdateSeconds / 3600) || validity > kMaxValidity)
    throw std::invalid_argument(
        "credentials: validity must be over 1 h (certificates start an hour ago) and at most 100 years");
  ERR_clear_error();
  state_->organization = organization;
  state_->key = newKey();
  const NamePtr subject = nameOf(kAuthorityCommonName, organization);
  state_->certificate = newCertificate(state_->key.get(), subject.get(), subject.get());
  X509* const ca = state_->certificate.get();

  std::time_t now = std::time(nullptr);
  const auto days = static_cast<int>(validity.count() / 24);
  const long seconds = static_cast<long>(validity.count() % 24) * 3600 - kBackdateSeconds;
  checked(X509_time_adj_ex(X509_getm_notBefore(ca), 0, -kBackdateSeconds, &now), "setting notBefore");
  checked(X509_time_adj_ex(X509_getm_notAfter(ca), days, seconds, &now), "setting notAfter");

  addExtension(ca, ca, NID_basic_constraints, "critical,CA:TRUE");
  // digitalSignature besides the CA bits: this certificate also signs the governance and
  // permissions documents, and PKCS7_verify checks the signer for the S/MIME signing purpose,
  // which refuses a key usage without digitalSignature or nonRepudiation ("unsuitable
  // certificate purpose", so Cyclone would reject both documents).
  addExtension(ca, ca, NID_key_usage, "critical,digitalSignature,keyCertSign,cRLSign");
  addExtension(ca, ca, NID_subject_key_identifier, "hash");
  check(X509_sign(ca, state_->key.get(), EVP_sha256()), "signing the CA certificate");
  state_->certificate_pem = pemOf(ca);
}

RunAuthority::~RunAuthority() = default;
RunAuthority::RunAuthority(RunAuthority&&) noexcept = default;
RunAuthority& RunAuthority::operator=(RunAuthority&&) noexcept = default;

const std::string& RunAuthority::certificatePem() const { return state_->certificate_pem; }

IssuedIdentity RunAuthority::issue(const std::string& common_name) const {
  requireCommonName(common_name);
  ERR_clear_error();
  X509* const ca = state_->certificate.get();
  PkeyPtr key = newKey();
  const NamePtr subject = nameOf(common_name, state_->organization);
  const X509Ptr certificate = newCertificate(key.get(), subject.get(), X509_get_subject_name(ca));
  X509* const cert = certificate.get();
  // The CA's window: an identity never outlives the authority that vouches for it.
  check(X509_set1_notBefore(cert, X509_get0_notBefore(ca)), "setting notBefore");
  check(X509_set1_notAfter(cert, X509_get0_notAfter(ca)), "setting notAfter");
  addExtension(cert, ca, NID_basic_constraints, "CA:FALSE");
  // digitalSignature signs the handshake; keyAgreement covers the ECDH of the handshake.
  addExtension(cert, ca, NID_key_usage, "critical,digitalSignature,keyAgreement");
  addExtension(cert, ca, NID_subject_key_identifier, "hash");
  addExtension(cert, ca, NID_authority_key_identifier, "keyid:always");
  check(X509_sign(cert, state_->key.get(), EVP_sha256()), "signing the certificate of " + common_name);
  return IssuedIdentity{pemOf(cert), pemOf(key.get()), subjectNameOf(common_name, state_->organization)};
}

std::string RunAuthority::sign(const std::string& document) const {
  if (document.size() > static_cast<std::size_t>(INT_MAX))
    throw std::invalid_argument("credentials: a document to sign must be under 2 GiB");
  ERR_clear_error();
  // The flags `openssl smime -sign -text` signs with (apps/smime.c adds PKCS7_STREAM for detached
  // S/MIME output). PKCS7_TEXT is what Cyclone's PKCS7_verify(..., PKCS7_TEXT) needs: it refuses
  // content without the "Content-Type: text/plain" header that text mode puts in front.
  constexpr int kFlags = PKCS7_DETACHED | PKCS7_TEXT | PKCS7_STREAM;
  const BioPtr in(checked(BIO_new_mem_buf(document.data(), static_cast<int>(document.size())), "reading a document"));
  // The signer certificate goes in (no PKCS7_NOCERTS): Cyclone's store holds only the CA and
  // PKCS7_verify finds the signer among the certificates in the message.
  const Pkcs7Ptr pkcs7(checked(PKCS7_sign(state_->certificate.get(), state_->key.get(), nullptr, in.get(), kFlags),
                               "signing a document"));
  const BioPtr out = memoryBio();
  check(SMIME_write_PKCS7(out.get(), pkcs7.get(), in.get(), kFlags), "writing a signed document as S/MIME");
  return contentsOf(out.get());
}

}  // namespace wsn::launcher

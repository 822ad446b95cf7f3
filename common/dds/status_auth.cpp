// HMAC-SHA256 of process-status samples (status_auth.hpp): OpenSSL's, over a fixed little-endian
// layout of the fields, so that the bytes signed do not depend on the compiler's struct padding.
#include "common/dds/status_auth.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace wsn::dds {
namespace {

template <typename Integer>
void appendLittleEndian(std::vector<std::uint8_t>& out, Integer value) {
  auto bits = static_cast<std::make_unsigned_t<Integer>>(value);
  for (std::size_t i = 0; i < sizeof(Integer); ++i) {
    out.push_back(static_cast<std::uint8_t>(bits & 0xffu));
    bits = static_cast<decltype(bits)>(bits >> 8);
  }
}

/// A string with its length first: ("ab", "c") and ("a", "bc") sign differently.
void appendString(std::vector<std::uint8_t>& out, const char* text) {
  const std::size_t length = text == nullptr ? 0 : std::strlen(text);
  appendLittleEndian(out, static_cast<std::uint64_t>(length));
  out.insert(out.end(), text, text + length);
}

}  // namespace

StatusKey StatusKey::generate() {
  Bytes bytes{};
  if (RAND_bytes(bytes.data(), static_cast<int>(bytes.size())) != 1)
    throw std::runtime_error("OpenSSL could not generate the run's status key");
  StatusKey key;
  key.bytes_ = bytes;
  return key;
}

StatusKey StatusKey::fromHex(const std::string& hex) {
  Bytes bytes{};
  if (hex.size() != 2 * bytes.size())
    throw std::invalid_argument("a status key is " + std::to_string(2 * bytes.size()) + " hexadecimal digits, got " +
                                std::to_string(hex.size()) + " characters");
  std::size_t length = 0;
  if (OPENSSL_hexstr2buf_ex(bytes.data(), bytes.size(), &length, hex.c_str(), '\0') != 1 || length != bytes.size())
    throw std::invalid_argument("a status key is hexadecimal digits only");
  StatusKey key;
  key.bytes_ = bytes;
  return key;
}

StatusKey StatusKey::readLine(int fd) {
  std::string line;
  while (line.size() <= 2 * sizeof(Bytes)) {
    char c = 0;
    const ssize_t n = ::read(fd, &c, 1);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error(std::string("cannot read the status key: ") + std::strerror(errno));
    if (n == 0) throw std::runtime_error("standard input ended before the launcher's status key");
    if (c == '\n') return fromHex(line);
    line.push_back(c);
  }
  throw std::invalid_argument("the first line of standard input is not a status key");
}

std::string StatusKey::hex() const {
  if (!bytes_) return "";
  std::array<char, 2 * sizeof(Bytes) + 1> text{};
  if (OPENSSL_buf2hexstr_ex(text.data(), text.size(), nullptr, bytes_->data(), bytes_->size(), '\0') != 1)
    throw std::runtime_error("OpenSSL could not write the status key as hex");
  return text.data();
}

StatusKey::Bytes StatusKey::mac(const wsn_msg_ProcessStatus& sample) const {
  std::vector<std::uint8_t> message;
  appendLittleEndian(message, sample.run_id);
  appendString(message, sample.role);
  appendLittleEndian(message, sample.index);
  appendLittleEndian(message, static_cast<std::int32_t>(sample.state));
  appendLittleEndian(message, sample.tick);
  appendString(message, sample.message);
  Bytes out{};
  unsigned int length = 0;
  if (HMAC(EVP_sha256(), bytes_->data(), static_cast<int>(bytes_->size()), message.data(), message.size(), out.data(),
           &length) == nullptr ||
      length != out.size())
    throw std::runtime_error("OpenSSL could not compute a status sample's HMAC");
  return out;
}

void StatusKey::sign(wsn_msg_ProcessStatus& sample) const {
  const Bytes value = bytes_ ? mac(sample) : Bytes{};
  std::memcpy(sample.mac, value.data(), value.size());
}

bool StatusKey::authentic(const wsn_msg_ProcessStatus& sample) const {
  if (!bytes_) return true;
  const Bytes expected = mac(sample);
  return CRYPTO_memcmp(expected.data(), sample.mac, expected.size()) == 0;
}

}  // namespace wsn::dds

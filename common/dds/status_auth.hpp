// Authenticity of process-status samples without DDS Security: each sample carries an HMAC under a
// key that the launcher gives only its own processes, so that a program on the domain cannot make
// the launcher enact a fault, a role take a live process for lost, or the run start or end early.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "wsntrack.h"

namespace wsn::dds {

/// The run's status key: 32 random bytes, or none for a role started by hand (which then neither
/// signs nor checks, like the run it is tried in).
class StatusKey {
 public:
  using Bytes = std::array<std::uint8_t, 32>;

  StatusKey() = default;
  /// A fresh key from OpenSSL's random generator.
  static StatusKey generate();
  /// Parses the 64 hexadecimal digits that hex() writes; throws std::invalid_argument otherwise.
  static StatusKey fromHex(const std::string& hex);
  /// Reads one line (the key's hex) from `fd` byte by byte, so that nothing after it is consumed
  /// (a remote role's standard input is then its lifeline); throws std::runtime_error at its end.
  static StatusKey readLine(int fd);

  bool present() const { return bytes_.has_value(); }
  std::string hex() const;

  /// Fills `sample.mac` with the HMAC-SHA256 of its other fields (zeros without a key).
  void sign(wsn_msg_ProcessStatus& sample) const;
  /// True when `sample.mac` is the HMAC of its fields under this key; always true without a key.
  bool authentic(const wsn_msg_ProcessStatus& sample) const;

 private:
  Bytes mac(const wsn_msg_ProcessStatus& sample) const;
  std::optional<Bytes> bytes_;
};

}  // namespace wsn::dds

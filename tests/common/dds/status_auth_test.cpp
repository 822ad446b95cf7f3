// The status key (common/dds/status_auth.hpp): a signed sample is authentic under its key and no
// other, any change of a field makes it forged, and the key travels as one line of hex.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <string>

#include "common/dds/status_auth.hpp"

using wsn::dds::StatusKey;

namespace {

struct Sample {
  std::string role = "supernode";
  std::string message = "kill supernode 1 at tick 7";
  wsn_msg_ProcessStatus status{};
  Sample() {
    status.run_id = 0x1234abcdULL;
    status.role = role.data();
    status.index = 1;
    status.state = wsn_msg_FAULTED;
    status.tick = 7;
    status.message = message.data();
  }
};

}  // namespace

TEST_CASE("A status sample signed with the run's key is authentic under it and no other", "[status_auth]") {
  const StatusKey key = StatusKey::generate(), other = StatusKey::generate();
  REQUIRE(key.hex() != other.hex());
  Sample s;
  key.sign(s.status);
  CHECK(key.authentic(s.status));
  CHECK_FALSE(other.authentic(s.status));
}

TEST_CASE("Changing any field of a signed status sample makes it forged", "[status_auth]") {
  const StatusKey key = StatusKey::generate();
  Sample s;
  key.sign(s.status);
  SECTION("run id") { s.status.run_id += 1; }
  SECTION("role") { s.role[0] = 'S'; }
  SECTION("index") { s.status.index = 2; }
  SECTION("state") { s.status.state = wsn_msg_DONE; }
  SECTION("tick") { s.status.tick = 0; }
  SECTION("message") { s.message += "!"; s.status.message = s.message.data(); }
  SECTION("the mac itself") { s.status.mac[31] ^= 1; }
  CHECK_FALSE(key.authentic(s.status));
}

TEST_CASE("A stranger's unsigned sample is forged, and a role without a key checks nothing", "[status_auth]") {
  Sample s;  // mac all zeros, as a program without the key leaves it
  CHECK_FALSE(StatusKey::generate().authentic(s.status));
  const StatusKey none;
  CHECK_FALSE(none.present());
  CHECK(none.authentic(s.status));
  none.sign(s.status);
  for (const auto byte : s.status.mac) CHECK(byte == 0);
}

TEST_CASE("The role and message are signed with their lengths, so text cannot move between them", "[status_auth]") {
  const StatusKey key = StatusKey::generate();
  Sample a, b;
  a.role = "ab";
  a.status.role = a.role.data();
  a.message = "c";
  a.status.message = a.message.data();
  b.role = "a";
  b.status.role = b.role.data();
  b.message = "bc";
  b.status.message = b.message.data();
  key.sign(a.status);
  std::memcpy(b.status.mac, a.status.mac, sizeof a.status.mac);
  CHECK_FALSE(key.authentic(b.status));
}

TEST_CASE("A status key reads back from its line of hex and leaves the rest of the pipe", "[status_auth]") {
  const StatusKey key = StatusKey::generate();
  REQUIRE(key.hex().size() == 64);
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  const std::string text = key.hex() + "\nlifeline";
  REQUIRE(::write(fds[1], text.data(), text.size()) == static_cast<ssize_t>(text.size()));
  ::close(fds[1]);
  const StatusKey read = StatusKey::readLine(fds[0]);
  CHECK(read.hex() == key.hex());
  char rest[16] = {};
  CHECK(::read(fds[0], rest, sizeof rest) == 8);
  CHECK(std::string(rest) == "lifeline");
  ::close(fds[0]);
  Sample s;
  key.sign(s.status);
  CHECK(read.authentic(s.status));
}

TEST_CASE("A malformed or missing status key is a clear error", "[status_auth]") {
  CHECK_THROWS_WITH(StatusKey::fromHex("abc"), Catch::Contains("64 hexadecimal digits"));
  CHECK_THROWS_WITH(StatusKey::fromHex(std::string(63, 'a') + "g"), Catch::Contains("hexadecimal digits only"));
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  ::close(fds[1]);
  CHECK_THROWS_WITH(StatusKey::readLine(fds[0]), Catch::Contains("ended before the launcher's status key"));
  ::close(fds[0]);
  // A first line longer than any key is refused without reading on to its end.
  REQUIRE(::pipe(fds) == 0);
  const std::string long_line(100, 'a');
  REQUIRE(::write(fds[1], long_line.data(), long_line.size()) == static_cast<ssize_t>(long_line.size()));
  CHECK_THROWS_WITH(StatusKey::readLine(fds[0]), Catch::Contains("is not a status key"));
  ::close(fds[1]);
  ::close(fds[0]);
}

#include "sim/pty.hpp"

#include <catch2/catch.hpp>
#include <cerrno>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

using namespace std::chrono_literals;

TEST_CASE("a pty passes bytes unchanged in both directions", "[pty]") {
  auto pty = subfeed::sim::Pty::open();
  REQUIRE(pty);
  CHECK(std::filesystem::exists(pty->slave_path()));
  const int slave = ::open(pty->slave_path().c_str(), O_RDWR | O_NOCTTY);
  REQUIRE(slave >= 0);
  // Bytes a cooked tty would translate or swallow: CR, XON/XOFF, Ctrl-X, 0x84.
  const std::string raw = "G1 X1\r\n\x11\x13\x18\x84?";
  REQUIRE(::write(slave, raw.data(), raw.size()) == static_cast<ssize_t>(raw.size()));
  std::string got;
  char buf[64];
  while (got.size() < raw.size()) {
    const auto n = pty->read(buf, 1000ms);
    REQUIRE(n);
    REQUIRE(*n > 0);
    got.append(buf, *n);
  }
  CHECK(got == raw);
  REQUIRE(pty->write_all(std::string_view("ok\r\n")));
  char back[8] = {};
  CHECK(::read(slave, back, sizeof back) == 4);
  CHECK(std::string(back, 4) == "ok\r\n");
  ::close(slave);
}

TEST_CASE("a pty read times out with zero bytes", "[pty]") {
  auto pty = subfeed::sim::Pty::open().value();
  const int slave = ::open(pty.slave_path().c_str(), O_RDWR | O_NOCTTY);
  char buf[8];
  CHECK(pty.read(buf, 20ms).value() == 0);
  ::close(slave);
}

TEST_CASE("a pty closes its master when it dies", "[pty]") {
  // The far side, held open across the death: it sees the hang-up. (Reopening the slave's
  // path is no test: another test running beside this one may be given the same pty number.)
  int slave = -1;
  {
    auto pty = subfeed::sim::Pty::open().value();
    slave = ::open(pty.slave_path().c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
    REQUIRE(slave >= 0);
    char byte = 0;
    CHECK(::read(slave, &byte, 1) < 0); // nothing yet: the master is open, so EAGAIN
    CHECK(errno == EAGAIN);
    auto moved = std::move(pty); // ownership moves, no double close
    CHECK(moved.master_fd() >= 0);
    CHECK(pty.master_fd() == -1);
  }
  char byte = 0;
  const auto got = ::read(slave, &byte, 1);
  CHECK((got == 0 || (got < 0 && errno == EIO))); // hung up, not "nothing yet"
  ::close(slave);
}

// The simulated control's overrun alarm (087) judges what a sender writes after the DC3
// has left, not what sat in the pty because the control's thread ran late. A raw writer on
// the slave side plays the sender, so each case controls exactly when bytes are written.

#include "sim/fanuc_sim.hpp"
#include "sim/pty.hpp"
#include "support/fanuc_alarm.hpp"

#include <catch2/catch.hpp>
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <thread>
#include <unistd.h>

using namespace std::chrono_literals;

namespace {

// The slave end in raw mode: no output translation, and DC3 from the control does not
// stop our writes in the line discipline (this sender must be free to overrun).
struct RawSender {
  explicit RawSender(const std::string& path) : fd(::open(path.c_str(), O_RDWR | O_NOCTTY)) {
    REQUIRE(fd >= 0);
    termios tio{};
    REQUIRE(::tcgetattr(fd, &tio) == 0);
    ::cfmakeraw(&tio);
    tio.c_cflag |= CSTOPB; // the control's 2 stop bits: no TH framing alarm
    REQUIRE(::tcsetattr(fd, TCSANOW, &tio) == 0);
  }
  RawSender(const RawSender&) = delete;
  RawSender& operator=(const RawSender&) = delete;
  ~RawSender() { ::close(fd); }

  void write(const std::string& bytes) const {
    REQUIRE(::write(fd, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size()));
  }

  // True once the control has sent DC3 (within `timeout`).
  [[nodiscard]] bool wait_for_dc3(std::chrono::milliseconds timeout) const {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, 20) == 1) {
        char c = 0;
        if (::read(fd, &c, 1) == 1 && c == 0x13) {
          return true;
        }
      }
    }
    return false;
  }

  int fd;
};

// A control that never drains: the characters carry no end of block, so everything stays
// in its 4 KB buffer. DC3 at 100 characters; 9600 baud paces its reads to about one
// character a millisecond, so a burst written at once is read over hundreds of reads.
subfeed::sim::FanucSimOptions holding_control() {
  subfeed::sim::FanucSimOptions o;
  o.buffer = 4096;
  o.high_water = 100;
  o.low_water = 50;
  o.overrun_tolerance = 10;
  o.baud = 9600;
  return o;
}

// Waits until the control has read `count` characters (its buffer fill) or 5 s have gone.
void wait_for_fill(const subfeed::sim::FanucSim& control, int count) {
  for (int i = 0; i < 250 && control.stats().max_fill < count; ++i) {
    std::this_thread::sleep_for(20ms);
  }
}

} // namespace

TEST_CASE("a pty reports the bytes written to it that no read has taken", "[pty]") {
  auto pty = subfeed::sim::Pty::open().value();
  const RawSender sender(pty.slave_path());
  CHECK(pty.unread() == 0);
  sender.write("G01 X1.0");
  for (int i = 0; i < 50 && pty.unread() < 8; ++i) {
    std::this_thread::sleep_for(2ms);
  }
  CHECK(pty.unread() == 8);
  char buffer[4];
  REQUIRE(pty.read(buffer, 100ms).value() == 4);
  CHECK(pty.unread() == 4);
}

TEST_CASE("characters written before the DC3 left are no overrun, however late they are read",
          "[pty]") {
  subfeed::sim::FanucSim control(
      std::make_unique<subfeed::sim::Pty>(subfeed::sim::Pty::open().value()), holding_control());
  control.start();
  const RawSender sender(control.address());
  // One burst of 400 characters before the control has read any: it reads them in many
  // small batches and sends DC3 at the 100th, with some 300 still waiting in the pty.
  sender.write(std::string(400, 'X'));
  wait_for_fill(control, 400);
  const auto stats = control.stats();
  CHECK(stats.max_fill == 400);
  CHECK(stats.xoff_sent == 1);
  CHECK(stats.alarm.empty());
  CHECK(stats.max_after_xoff == 0);
}

TEST_CASE("a sender that goes on writing after DC3 raises alarm 087", "[pty]") {
  subfeed::sim::FanucSim control(
      std::make_unique<subfeed::sim::Pty>(subfeed::sim::Pty::open().value()), holding_control());
  control.start();
  const RawSender sender(control.address());
  sender.write(std::string(120, 'X'));
  REQUIRE(sender.wait_for_dc3(5000ms));
  wait_for_fill(control, 120);
  CHECK(control.stats().alarm.empty());
  sender.write(std::string(10, 'Y')); // within the tolerance
  wait_for_fill(control, 130);
  CHECK(control.stats().alarm.empty());
  CHECK(control.stats().max_after_xoff == 10);
  sender.write("Z"); // one more: the eleventh after DC3
  wait_for_fill(control, 131);
  CHECK(subfeed::testing::alarm_within(control, 1000ms) == "087 overrun: 11 characters after DC3");
}

TEST_CASE("characters written within the link's latency after DC3 are in flight", "[pty]") {
  auto o = holding_control();
  o.link_latency = 500ms;
  subfeed::sim::FanucSim control(
      std::make_unique<subfeed::sim::Pty>(subfeed::sim::Pty::open().value()), o);
  control.start();
  const RawSender sender(control.address());
  sender.write(std::string(120, 'X'));
  REQUIRE(sender.wait_for_dc3(5000ms));
  sender.write(std::string(30, 'Y')); // as if the DC3 reached us late
  wait_for_fill(control, 150);
  CHECK(control.stats().alarm.empty());
  CHECK(control.stats().max_after_xoff == 0);
  std::this_thread::sleep_for(600ms); // the window has closed
  sender.write(std::string(11, 'Z'));
  wait_for_fill(control, 161);
  CHECK(subfeed::testing::alarm_within(control, 1000ms) == "087 overrun: 11 characters after DC3");
}

#include "drivers/port_list.hpp"
#include "drivers/serial_port.hpp"
#include "sim/pty.hpp"

#include <catch2/catch.hpp>
#include <filesystem>

using namespace std::chrono_literals;
using subfeed::drivers::SerialOptions;
using subfeed::drivers::SerialPort;

TEST_CASE("a serial port on a pty talks to the far side", "[pty]") {
  auto pty = subfeed::sim::Pty::open().value();
  auto port = SerialPort::open(pty.slave_path(), SerialOptions{});
  REQUIRE(port);
  const std::string line = "$I\n";
  CHECK(port->write(line, 1000ms).value() == line.size());
  REQUIRE(port->drain());
  char buf[16];
  const auto n = pty.read(buf, 1000ms).value();
  CHECK(std::string(buf, n) == line);

  REQUIRE(pty.write_all(std::string_view("[OPT:VL,15,128]\r\nok\r\n")));
  std::string reply;
  while (reply.size() < 21) {
    const auto got = port->read(buf, 1000ms);
    REQUIRE(got);
    REQUIRE(*got > 0);
    reply.append(buf, *got);
  }
  CHECK(reply == "[OPT:VL,15,128]\r\nok\r\n");
}

TEST_CASE("a serial read with nothing to read times out with zero bytes", "[pty]") {
  auto pty = subfeed::sim::Pty::open().value();
  auto port = SerialPort::open(pty.slave_path(), SerialOptions{}).value();
  char buf[4];
  CHECK(port.read(buf, 30ms).value() == 0);
}

TEST_CASE("framing options are accepted by the port", "[pty]") {
  auto pty = subfeed::sim::Pty::open().value();
  const SerialOptions fanuc{9600, 7, subfeed::drivers::SerialParity::even, 2,
                            subfeed::drivers::SerialFlow::none};
  CHECK(SerialPort::open(pty.slave_path(), fanuc).has_value());
}

TEST_CASE("a port that does not exist is a machine fault naming it", "[pty]") {
  const auto port = SerialPort::open("/dev/nonexistent-tty", SerialOptions{});
  REQUIRE_FALSE(port);
  CHECK(port.error().code == subfeed::ErrorCode::machine_fault);
  CHECK(port.error().where.file == "/dev/nonexistent-tty");
}

TEST_CASE("a vanished port is a read error, not a silent timeout", "[pty]") {
  auto pty = subfeed::sim::Pty::open().value();
  auto port = SerialPort::open(pty.slave_path(), SerialOptions{}).value();
  pty.close();
  char buf[4];
  const auto got = port.read(buf, 200ms);
  REQUIRE_FALSE(got);
  CHECK(got.error().code == subfeed::ErrorCode::machine_fault);
}

TEST_CASE("a second sender cannot open a port that is in use", "[pty]") {
  auto pty = subfeed::sim::Pty::open().value();
  auto first = SerialPort::open(pty.slave_path(), SerialOptions{});
  REQUIRE(first);
  const auto second = SerialPort::open(pty.slave_path(), SerialOptions{});
  REQUIRE_FALSE(second);
  CHECK(second.error().message == "port is in use by another program");
}

TEST_CASE("a path that is not a tty is refused", "[pty]") {
  const auto port = SerialPort::open("/dev/null", SerialOptions{});
  REQUIRE_FALSE(port);
  CHECK(port.error().describe() == "/dev/null: not a serial port (not a tty)");
}

TEST_CASE("an unsupported baud rate is a bad-input error", "[pty]") {
  auto pty = subfeed::sim::Pty::open().value();
  const auto port = SerialPort::open(pty.slave_path(), SerialOptions{12345});
  REQUIRE_FALSE(port);
  CHECK(port.error().code == subfeed::ErrorCode::bad_input);
  CHECK(port.error().message == "unsupported baud rate 12345");
}

TEST_CASE("listed serial ports exist and are described", "[pty]") {
  const auto ports = subfeed::drivers::list_serial_ports();
  REQUIRE(ports);
  for (const auto& port : *ports) {
    INFO(port.path);
    CHECK(std::filesystem::exists(port.path));
    CHECK((port.transport == "native" || port.transport == "usb" || port.transport == "bluetooth"));
  }
}

TEST_CASE("a port list reads as paths with descriptions") {
  using subfeed::drivers::PortInfo;
  CHECK(subfeed::drivers::describe_ports({}) == "none");
  const std::vector<PortInfo> ports{
      {"/dev/ttyUSB0", "FT232R USB UART", "usb", 0x0403, 0x6001, "FTDI", "FT232R", "A1"},
      {"/dev/ttyS0", "", "native", {}, {}, "", "", ""}};
  CHECK(subfeed::drivers::describe_ports(ports) == "/dev/ttyUSB0 (FT232R USB UART), /dev/ttyS0");
}

#pragma once
// The serial ports this computer has, as libserialport finds them, with what the OS knows of
// each (USB vendor and product, serial number), so that a user can tell the controller's
// port from the others. Pseudo-terminals are not listed; they are opened by path.

#include "base/error.hpp"

#include <optional>
#include <string>
#include <vector>

namespace subfeed::drivers {

struct PortInfo {
  std::string path;        // e.g. /dev/ttyUSB0
  std::string description; // the OS's description
  std::string transport;   // native, usb or bluetooth
  std::optional<int> usb_vid;
  std::optional<int> usb_pid;
  std::string manufacturer; // USB strings; empty when unknown
  std::string product;
  std::string serial_number;
};

[[nodiscard]] Expected<std::vector<PortInfo>> list_serial_ports();

// "path (description)" for each port, comma-separated, or "none".
[[nodiscard]] std::string describe_ports(const std::vector<PortInfo>& ports);

} // namespace subfeed::drivers

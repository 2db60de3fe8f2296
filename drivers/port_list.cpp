#include "drivers/port_list.hpp"

#include <libserialport.h>

namespace subfeed::drivers {

namespace {

std::string text(const char* s) {
  return s != nullptr ? s : "";
}

PortInfo describe(sp_port* port) {
  PortInfo info;
  info.path = text(sp_get_port_name(port));
  info.description = text(sp_get_port_description(port));
  switch (sp_get_port_transport(port)) {
  case SP_TRANSPORT_USB: {
    info.transport = "usb";
    int vid = 0, pid = 0;
    if (sp_get_port_usb_vid_pid(port, &vid, &pid) == SP_OK) {
      info.usb_vid = vid;
      info.usb_pid = pid;
    }
    info.manufacturer = text(sp_get_port_usb_manufacturer(port));
    info.product = text(sp_get_port_usb_product(port));
    info.serial_number = text(sp_get_port_usb_serial(port));
    break;
  }
  case SP_TRANSPORT_BLUETOOTH:
    info.transport = "bluetooth";
    break;
  default:
    info.transport = "native";
    break;
  }
  return info;
}

} // namespace

Expected<std::vector<PortInfo>> list_serial_ports() {
  sp_port** list = nullptr;
  if (sp_list_ports(&list) != SP_OK) {
    char* message = sp_last_error_message();
    const std::string why = text(message);
    sp_free_error_message(message);
    return fail(ErrorCode::machine_fault, "cannot list serial ports: " + why);
  }
  std::vector<PortInfo> ports;
  for (sp_port** p = list; *p != nullptr; ++p) {
    ports.push_back(describe(*p));
  }
  sp_free_port_list(list);
  return ports;
}

std::string describe_ports(const std::vector<PortInfo>& ports) {
  if (ports.empty()) {
    return "none";
  }
  std::string out;
  for (const auto& port : ports) {
    out += (out.empty() ? "" : ", ") + port.path;
    if (!port.description.empty()) {
      out += " (" + port.description + ")";
    }
  }
  return out;
}

} // namespace subfeed::drivers

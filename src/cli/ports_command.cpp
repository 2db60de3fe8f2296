// `subfeed ports`: the serial ports this computer has, with USB vendor, product and serial
// number, to find which one is the machine's controller.

#include "command.hpp"

#include "drivers/port_list.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace subfeed::cli {

namespace {

Expected<void> list_ports(Logger& log) {
  SUBFEED_TRY_ASSIGN(const auto ports, drivers::list_serial_ports());
  if (ports.empty()) {
    log.info("no serial ports found (pseudo-terminals are not listed; give their path to --port)");
    return {};
  }
  for (const auto& p : ports) {
    std::string line = fmt::format("{}  {}  [{}]", p.path, p.description, p.transport);
    if (p.usb_vid && p.usb_pid) {
      line += fmt::format("  USB {:04x}:{:04x}", *p.usb_vid, *p.usb_pid);
    }
    for (const auto* field : {&p.manufacturer, &p.product}) {
      if (!field->empty()) {
        line += "  " + *field;
      }
    }
    if (!p.serial_number.empty()) {
      line += "  serial " + p.serial_number;
    }
    log.info(line);
  }
  return {};
}

} // namespace

void add_ports_command(CLI::App& app, Action& chosen) {
  CLI::App* cmd = app.add_subcommand("ports", "List this computer's serial ports");
  cmd->callback([&chosen] { chosen = [](Logger& log) { return list_ports(log); }; });
}

} // namespace subfeed::cli

// `subfeed send FILE (--port DEV | --tcp HOST:PORT | --sim grbl|grblhal)`: drip-feeds a G-code
// file to a GRBL-style controller with character counting. --sim starts the simulated
// controller on a pty and reaches it through the very serial code a real port uses.

#include "command.hpp"
#include "control_thread.hpp"
#include "stream_reporter.hpp"

#include "drivers/grbl_streamer.hpp"
#include "drivers/port_list.hpp"
#include "drivers/serial_port.hpp"
#include "drivers/tcp_transport.hpp"
#include "post/machine_config.hpp"
#include "sim/grbl_sim.hpp"
#include "sim/pty.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace subfeed::cli {

namespace {

struct SendOptions {
  std::string file;
  std::string port;
  std::string tcp;
  std::string sim;
  std::string machine;
  int baud = 0; // 0: from the machine config, else 115200
  int rx_buffer = 0;
  int line_limit = 0;
  double connect_timeout_s = 5.0;
  double sim_speed = 1.0;
  int sim_baud = -1; // -1: the link's baud
  bool json = false;
  drivers::GrblStreamOptions stream;
};

struct Link {
  std::unique_ptr<sim::GrblSim> simulator; // declared first: dies after the port
  std::unique_ptr<drivers::Transport> transport;
  std::optional<int> baud; // for link use; none for TCP
};

drivers::SerialParity to_driver(post::Parity p) {
  return p == post::Parity::even  ? drivers::SerialParity::even
         : p == post::Parity::odd ? drivers::SerialParity::odd
                                  : drivers::SerialParity::none;
}

drivers::SerialFlow to_driver(post::FlowControl f) {
  switch (f) {
  case post::FlowControl::xon_xoff:
    return drivers::SerialFlow::xon_xoff;
  case post::FlowControl::rts_cts:
    return drivers::SerialFlow::rts_cts;
  case post::FlowControl::both:
    return drivers::SerialFlow::both;
  case post::FlowControl::none:
    break;
  }
  return drivers::SerialFlow::none;
}

// Settings from --machine, then flags on top.
Expected<drivers::SerialOptions> apply_machine(SendOptions& o) {
  drivers::SerialOptions serial;
  if (!o.machine.empty()) {
    SUBFEED_TRY_ASSIGN(const auto config, post::load_machine_config(o.machine));
    if (config.controller.protocol != post::Protocol::grbl) {
      return fail(ErrorCode::bad_input,
                  "this machine's controller speaks the fanuc protocol; send supports grbl so far",
                  {o.machine, 0, "controller.protocol"});
    }
    const auto& s = config.controller.serial;
    serial = {s.baud, s.data_bits, to_driver(s.parity), s.stop_bits, to_driver(s.flow_control)};
    if (!o.stream.line_limit) {
      o.stream.line_limit = config.controller.line_length;
    }
    if (!o.stream.rx_buffer && config.controller.rx_buffer) {
      o.stream.rx_buffer = *config.controller.rx_buffer;
    }
  }
  if (o.baud > 0) {
    serial.baud = o.baud;
  }
  return serial;
}

Expected<Link> open_link(const SendOptions& o, const drivers::SerialOptions& serial) {
  Link link;
  std::string port = o.port;
  if (!o.sim.empty()) {
    SUBFEED_TRY_ASSIGN(auto pty, sim::Pty::open());
    sim::GrblSimOptions sim_options;
    sim_options.grblhal = o.sim == "grblhal";
    sim_options.axes = sim_options.grblhal ? 5 : 3;
    sim_options.rx_buffer = sim_options.grblhal ? 1024 : 128;
    sim_options.planner_blocks = sim_options.grblhal ? 100 : 16;
    sim_options.line_limit = sim_options.grblhal ? 256 : 79;
    sim_options.baud = o.sim_baud >= 0 ? o.sim_baud : serial.baud;
    sim_options.motion.speed = o.sim_speed;
    link.simulator =
        std::make_unique<sim::GrblSim>(std::make_unique<sim::Pty>(std::move(pty)), sim_options);
    link.simulator->start();
    port = link.simulator->address();
    link.baud = sim_options.baud > 0 ? std::optional<int>(sim_options.baud) : std::nullopt;
  }
  if (!o.tcp.empty()) {
    SUBFEED_TRY_ASSIGN(
        auto tcp, drivers::TcpTransport::connect(o.tcp, std::chrono::milliseconds(static_cast<long>(
                                                            o.connect_timeout_s * 1000))));
    link.transport = std::make_unique<drivers::TcpTransport>(std::move(tcp));
    return link;
  }
  auto serial_port = drivers::SerialPort::open(port, serial);
  if (!serial_port) {
    Error error = serial_port.error();
    if (const auto ports = drivers::list_serial_ports(); ports && o.sim.empty()) {
      error.message += "; serial ports here: " + drivers::describe_ports(*ports);
    }
    return std::unexpected(error);
  }
  link.transport = std::make_unique<drivers::SerialPort>(std::move(*serial_port));
  if (o.sim.empty()) {
    link.baud = serial.baud;
  }
  return link;
}

Expected<void> send(SendOptions o, Logger& log) {
  block_stop_signals(); // before the simulator's or the control thread starts
  if (o.rx_buffer > 0) {
    o.stream.rx_buffer = o.rx_buffer;
  }
  if (o.line_limit > 0) {
    o.stream.line_limit = o.line_limit;
  }
  o.stream.connect_timeout =
      std::chrono::milliseconds(static_cast<long>(o.connect_timeout_s * 1000));
  SUBFEED_TRY_ASSIGN(const auto serial, apply_machine(o));
  SUBFEED_TRY_ASSIGN(auto source, drivers::GcodeSource::open(o.file, {}));
  SUBFEED_TRY_ASSIGN(auto link, open_link(o, serial));
  SUBFEED_TRY_ASSIGN(auto inbox, drivers::ControlInbox::create());
  StreamReporter reporter(log, o.json);
  const ControlThread control(*inbox, !o.json);
  const auto summary =
      drivers::stream_grbl(*link.transport, source, o.stream, inbox.get(), reporter);
  if (!summary) {
    reporter.failed(summary.error());
    return std::unexpected(summary.error());
  }
  reporter.finished(*summary, link.baud);
  return {};
}

} // namespace

void add_send_command(CLI::App& app, Action& chosen) {
  auto o = std::make_shared<SendOptions>();
  CLI::App* cmd =
      app.add_subcommand("send", "Drip-feed a G-code file to a GRBL or grblHAL controller");
  cmd->add_option("file", o->file, "G-code program")->required()->type_name("FILE.nc");
  auto* link = cmd->add_option_group("link", "Where the controller is (exactly one)");
  link->add_option("--port", o->port, "Serial port (any tty path, ptys included)")
      ->type_name("DEV");
  link->add_option("--tcp", o->tcp, "TCP stream (grblHAL Ethernet, serial-to-TCP server)")
      ->type_name("HOST:PORT");
  link->add_option("--sim", o->sim, "Start a simulated controller on a pty and stream to it")
      ->check(CLI::IsMember({"grbl", "grblhal"}));
  link->require_option(1);
  cmd->add_option("--machine", o->machine,
                  "Machine config: serial settings, line length, rx buffer")
      ->type_name("M.toml");
  cmd->add_option("--baud", o->baud, "Serial baud rate (default 115200 or the machine's)");
  cmd->add_option("--rx-buffer", o->rx_buffer,
                  "Controller RX buffer in bytes (default: read from $I, else 128)")
      ->check(CLI::Range(16, 65536));
  cmd->add_option("--line-limit", o->line_limit,
                  "Longest line the controller takes (default 79, grblHAL 256)")
      ->check(CLI::Range(16, 1024));
  cmd->add_flag("--send-and-wait", o->stream.send_and_wait,
                "Send each line alone and wait for its answer");
  cmd->add_flag("--keep-comments", o->stream.keep_comments, "Send comments and spaces as written");
  cmd->add_flag("--continue-on-error", o->stream.continue_on_error,
                "Report error:N answers and go on (for check runs)");
  cmd->add_flag("--check", o->stream.check_first,
                "Run the file through check mode ($C) first; stop on any error");
  cmd->add_option("--status-hz", o->stream.status_hz, "Status polls per second")
      ->check(CLI::Range(0.5, 20.0));
  cmd->add_option("--connect-timeout", o->connect_timeout_s, "Seconds to wait for the controller")
      ->check(CLI::Range(0.1, 600.0));
  cmd->add_option("--sim-speed", o->sim_speed,
                  "With --sim: run the machine N times faster than real time")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--sim-baud", o->sim_baud, "With --sim: emulated wire speed (0 = unlimited)")
      ->check(CLI::Range(0, 4000000));
  cmd->add_flag("--json", o->json, "Events as JSON, one per line, on stdout");
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return send(*o, log); }; });
}

} // namespace subfeed::cli

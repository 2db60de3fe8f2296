// `subfeed send FILE (--port DEV | --tcp HOST:PORT | --sim grbl|grblhal)`: drip-feeds a G-code
// file to a GRBL-style controller with character counting. --sim starts the simulated
// controller on a pty and reaches it through the very serial code a real port uses.

#include "command.hpp"
#include "control_thread.hpp"
#include "controller_link.hpp"
#include "option_checks.hpp"
#include "stream_reporter.hpp"

#include "drivers/fanuc_program.hpp"
#include "drivers/fanuc_streamer.hpp"
#include "drivers/gcode_source.hpp"
#include "drivers/grbl_streamer.hpp"
#include "drivers/journal.hpp"
#include "drivers/port_list.hpp"
#include "drivers/serial_port.hpp"
#include "drivers/tcp_transport.hpp"
#include "post/machine_config.hpp"
#include "sim/fanuc_sim.hpp"
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
  std::string protocol; // grbl or fanuc; default from --sim, --machine, else grbl
  std::string data_bits, parity, stop_bits, flow; // framing flags (empty: config or default)
  drivers::GrblStreamOptions stream;
  drivers::FanucStreamOptions dnc;
  std::string eob = "lf";
  double request_timeout_s = 60.0;
  double xoff_timeout_s = 30.0;
  long from_line = 0;
  std::string journal; // default: the program's path + ".journal"
};

void apply_framing_flags(const SendOptions& o, drivers::SerialOptions& serial) {
  if (o.baud > 0) {
    serial.baud = o.baud;
  }
  if (!o.data_bits.empty()) {
    serial.data_bits = o.data_bits == "7" ? 7 : 8; // CLI11 let only 7 and 8 through
  }
  if (!o.parity.empty()) {
    serial.parity = o.parity == "even"  ? drivers::SerialParity::even
                    : o.parity == "odd" ? drivers::SerialParity::odd
                                        : drivers::SerialParity::none;
  }
  if (!o.stop_bits.empty()) {
    serial.stop_bits = o.stop_bits == "2" ? 2 : 1;
  }
  if (!o.flow.empty()) {
    serial.flow = o.flow == "xon-xoff"  ? drivers::SerialFlow::xon_xoff
                  : o.flow == "rts-cts" ? drivers::SerialFlow::rts_cts
                  : o.flow == "both"    ? drivers::SerialFlow::both
                                        : drivers::SerialFlow::none;
  }
}

// Settings from --machine, then flags on top.
Expected<drivers::SerialOptions> apply_machine(SendOptions& o) {
  drivers::SerialOptions serial;
  if (!o.machine.empty()) {
    SUBFEED_TRY_ASSIGN(const auto config, post::load_machine_config(o.machine));
    const std::string protocol(post::to_string(config.controller.protocol));
    if (!o.protocol.empty() && o.protocol != protocol) {
      return fail(ErrorCode::usage,
                  "--protocol " + o.protocol + " contradicts the machine's " + protocol,
                  {o.machine, 0, "controller.protocol"});
    }
    o.protocol = protocol;
    o.dnc.program_number = config.controller.program_number;
    serial = serial_options_for(config);
    if (!o.stream.line_limit) {
      o.stream.line_limit = config.controller.line_length;
    }
    if (!o.stream.rx_buffer && config.controller.rx_buffer) {
      o.stream.rx_buffer = *config.controller.rx_buffer;
    }
  }
  if (!o.sim.empty()) {
    const std::string simulated = o.sim == "fanuc" ? "fanuc" : "grbl";
    if (!o.protocol.empty() && o.protocol != simulated) {
      return fail(ErrorCode::usage,
                  "--sim " + o.sim + " speaks " + simulated + ", not the " + o.protocol +
                      " protocol",
                  {{}, 0, "--sim"});
    }
    o.protocol = simulated;
  }
  if (o.protocol.empty()) {
    o.protocol = "grbl";
  }
  if (o.protocol == "fanuc" && o.machine.empty()) {
    serial = o.dnc.serial; // 7E2 with XON/XOFF, the common ISO tape setting
  }
  apply_framing_flags(o, serial);
  return serial;
}

LinkRequest link_request(const SendOptions& o) {
  LinkRequest r;
  r.port = o.port;
  r.tcp = o.tcp;
  r.sim = o.sim;
  r.protocol = o.protocol;
  r.connect_timeout_s = o.connect_timeout_s;
  r.sim_speed = o.sim_speed;
  r.sim_baud = o.sim_baud;
  r.sim_requests_tape = o.dnc.wait_for_request;
  r.eia_cr = o.dnc.eia_cr;
  return r;
}

Expected<drivers::StreamSummary> send_dnc(SendOptions& o, const drivers::SerialOptions& serial,
                                          drivers::Transport& link, drivers::ControlInbox* inbox,
                                          drivers::StreamObserver& reporter) {
  if (!o.tcp.empty()) {
    return fail(ErrorCode::usage, "fanuc drip feed runs over a serial port, not --tcp",
                {{}, 0, "--tcp"});
  }
  SUBFEED_TRY_ASSIGN(auto program, drivers::FanucProgram::open(o.file));
  o.dnc.serial = serial;
  o.dnc.eia_cr = o.eob == "cr";
  o.dnc.request_timeout = std::chrono::milliseconds(static_cast<long>(o.request_timeout_s * 1000));
  o.dnc.xoff_timeout = std::chrono::milliseconds(static_cast<long>(o.xoff_timeout_s * 1000));
  if (o.from_line > 0) {
    o.dnc.from_line = o.from_line;
  }
  return drivers::stream_fanuc(link, program, o.dnc, inbox, reporter);
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
  SUBFEED_TRY_ASSIGN(auto journal,
                     drivers::Journal::open(o.journal.empty() ? o.file + ".journal" : o.journal));
  SUBFEED_TRY_ASSIGN(auto link, open_link(link_request(o), serial));
  SUBFEED_TRY_ASSIGN(auto inbox, drivers::ControlInbox::create());
  StreamReporter reporter(log, o.json);
  drivers::JournaledObserver observer(reporter, journal);
  journal.start(o.protocol, o.file, link.transport->name());
  const ControlThread control(*inbox, !o.json);
  const auto summary =
      o.protocol == "fanuc"
          ? send_dnc(o, serial, *link.transport, inbox.get(), observer)
          : drivers::stream_grbl(*link.transport, source, o.stream, inbox.get(), observer);
  journal.end(summary);
  if (!summary) {
    const Error error = with_simulated_alarm(summary.error(), link);
    reporter.failed(error);
    return std::unexpected(error);
  }
  reporter.finished(*summary, link.baud, drivers::bits_per_character(serial));
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
      ->check(CLI::IsMember({"grbl", "grblhal", "fanuc"}));
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
      ->check(positive_number());
  cmd->add_option("--sim-baud", o->sim_baud, "With --sim: emulated wire speed (0 = unlimited)")
      ->check(CLI::Range(0, 4000000));
  cmd->add_flag("--json", o->json, "Events as JSON, one per line, on stdout");
  cmd->add_option("--journal", o->journal,
                  "Append the job's journal to FILE (default: the program's path + .journal)")
      ->type_name("FILE");
  cmd->add_option("--protocol", o->protocol, "grbl (character counting) or fanuc (DNC drip feed)")
      ->check(CLI::IsMember({"grbl", "fanuc"}));
  cmd->add_option("--data-bits", o->data_bits, "Serial data bits")
      ->check(CLI::IsMember({"7", "8"}));
  cmd->add_option("--parity", o->parity, "Serial parity")
      ->check(CLI::IsMember({"none", "even", "odd"}));
  cmd->add_option("--stop-bits", o->stop_bits, "Serial stop bits")
      ->check(CLI::IsMember({"1", "2"}));
  cmd->add_option("--flow", o->flow, "Flow control")
      ->check(CLI::IsMember({"none", "xon-xoff", "rts-cts", "both"}));
  cmd->add_option("--eob", o->eob, "fanuc: end of block, lf (ISO) or cr (EIA option)")
      ->check(CLI::IsMember({"lf", "cr"}));
  cmd->add_option("--program-number", o->dnc.program_number,
                  "fanuc: O-number when the file has no framing")
      ->check(CLI::Range(1, 9999));
  cmd->add_option("--nul-leader", o->dnc.nul_leader, "fanuc: NUL characters before the program")
      ->check(CLI::Range(0, 10000));
  cmd->add_option("--nul-trailer", o->dnc.nul_trailer, "fanuc: NUL characters after it")
      ->check(CLI::Range(0, 10000));
  cmd->add_flag("--wait-for-request", o->dnc.wait_for_request,
                "fanuc: send once the control requests the tape (DC1)");
  cmd->add_option("--request-timeout", o->request_timeout_s,
                  "fanuc: seconds to wait for the request")
      ->check(CLI::Range(0.1, 3600.0));
  cmd->add_option("--xoff-timeout", o->xoff_timeout_s,
                  "fanuc: seconds the control may hold the tape")
      ->check(CLI::Range(0.1, 3600.0));
  cmd->add_option("--from", o->from_line,
                  "fanuc: restart at this file line, restoring the modal state first")
      ->check(positive_number());
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return send(*o, log); }; });
}

} // namespace subfeed::cli

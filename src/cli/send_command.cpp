// `subfeed send FILE (--port DEV | --tcp HOST:PORT | --sim grbl|grblhal)`: drip-feeds a G-code
// file to a GRBL-style controller with character counting. --sim starts the simulated
// controller on a pty and reaches it through the very serial code a real port uses.

#include "command.hpp"
#include "job/control_thread.hpp"
#include "job/controller_link.hpp"
#include "option_checks.hpp"
#include "stream_reporter.hpp"

#include "job/send_request.hpp"

#include "drivers/gcode_source.hpp"
#include "drivers/journal.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace subfeed::cli {

using namespace subfeed::job; // NOLINT: the front wires the job library

namespace {

struct SendOptions {
  SendRequest request;
  int rx_buffer = 0;
  int line_limit = 0;
  double connect_timeout_s = 5.0;
  bool json = false;
};

Expected<void> send(SendOptions o, Logger& log) {
  block_stop_signals(); // before the simulator's or the control thread starts
  auto& r = o.request;
  if (o.rx_buffer > 0) {
    r.stream.rx_buffer = o.rx_buffer;
  }
  if (o.line_limit > 0) {
    r.stream.line_limit = o.line_limit;
  }
  r.connect_timeout_s = o.connect_timeout_s;
  r.stream.connect_timeout =
      std::chrono::milliseconds(static_cast<long>(o.connect_timeout_s * 1000));
  SUBFEED_TRY_ASSIGN(const auto serial, resolve_settings(r));
  SUBFEED_TRY_ASSIGN(auto source, drivers::GcodeSource::open(r.file, {}));
  SUBFEED_TRY_ASSIGN(auto journal,
                     drivers::Journal::open(r.journal.empty() ? r.file + ".journal" : r.journal));
  SUBFEED_TRY_ASSIGN(auto link, open_link(link_request(r), serial));
  SUBFEED_TRY_ASSIGN(auto inbox, drivers::ControlInbox::create());
  StreamReporter reporter(log, o.json);
  drivers::JournaledObserver observer(reporter, journal);
  journal.start(r.protocol, r.file, link.transport->name());
  const ControlThread control(*inbox, !o.json);
  const auto summary = stream_file(r, serial, source, *link.transport, inbox.get(), observer);
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
  cmd->add_option("file", o->request.file, "G-code program")->required()->type_name("FILE.nc");
  auto* link = cmd->add_option_group("link", "Where the controller is (exactly one)");
  link->add_option("--port", o->request.port, "Serial port (any tty path, ptys included)")
      ->type_name("DEV");
  link->add_option("--tcp", o->request.tcp, "TCP stream (grblHAL Ethernet, serial-to-TCP server)")
      ->type_name("HOST:PORT");
  link->add_option("--sim", o->request.sim,
                   "Start a simulated controller on a pty and stream to it")
      ->check(CLI::IsMember({"grbl", "grblhal", "fanuc"}));
  link->require_option(1);
  cmd->add_option("--machine", o->request.machine,
                  "Machine config: serial settings, line length, rx buffer")
      ->type_name("M.toml");
  cmd->add_option("--baud", o->request.baud, "Serial baud rate (default 115200 or the machine's)");
  cmd->add_option("--rx-buffer", o->rx_buffer,
                  "Controller RX buffer in bytes (default: read from $I, else 128)")
      ->check(CLI::Range(16, 65536));
  cmd->add_option("--line-limit", o->line_limit,
                  "Longest line the controller takes (default 79, grblHAL 256)")
      ->check(CLI::Range(16, 1024));
  cmd->add_flag("--send-and-wait", o->request.stream.send_and_wait,
                "Send each line alone and wait for its answer");
  cmd->add_flag("--keep-comments", o->request.stream.keep_comments,
                "Send comments and spaces as written");
  cmd->add_flag("--continue-on-error", o->request.stream.continue_on_error,
                "Report error:N answers and go on (for check runs)");
  cmd->add_flag("--check", o->request.stream.check_first,
                "Run the file through check mode ($C) first; stop on any error");
  cmd->add_option("--status-hz", o->request.stream.status_hz, "Status polls per second")
      ->check(CLI::Range(0.5, 20.0));
  cmd->add_option("--connect-timeout", o->connect_timeout_s, "Seconds to wait for the controller")
      ->check(CLI::Range(0.1, 600.0));
  cmd->add_option("--sim-speed", o->request.sim_speed,
                  "With --sim: run the machine N times faster than real time")
      ->check(positive_number());
  cmd->add_option("--sim-baud", o->request.sim_baud,
                  "With --sim: emulated wire speed (0 = unlimited)")
      ->check(CLI::Range(0, 4000000));
  cmd->add_flag("--json", o->json, "Events as JSON, one per line, on stdout");
  cmd->add_option("--journal", o->request.journal,
                  "Append the job's journal to FILE (default: the program's path + .journal)")
      ->type_name("FILE");
  cmd->add_option("--protocol", o->request.protocol,
                  "grbl (character counting) or fanuc (DNC drip feed)")
      ->check(CLI::IsMember({"grbl", "fanuc"}));
  cmd->add_option("--data-bits", o->request.data_bits, "Serial data bits")
      ->check(CLI::IsMember({"7", "8"}));
  cmd->add_option("--parity", o->request.parity, "Serial parity")
      ->check(CLI::IsMember({"none", "even", "odd"}));
  cmd->add_option("--stop-bits", o->request.stop_bits, "Serial stop bits")
      ->check(CLI::IsMember({"1", "2"}));
  cmd->add_option("--flow", o->request.flow, "Flow control")
      ->check(CLI::IsMember({"none", "xon-xoff", "rts-cts", "both"}));
  cmd->add_option("--eob", o->request.eob, "fanuc: end of block, lf (ISO) or cr (EIA option)")
      ->check(CLI::IsMember({"lf", "cr"}));
  cmd->add_option("--program-number", o->request.dnc.program_number,
                  "fanuc: O-number when the file has no framing")
      ->check(CLI::Range(1, 9999));
  cmd->add_option("--nul-leader", o->request.dnc.nul_leader,
                  "fanuc: NUL characters before the program")
      ->check(CLI::Range(0, 10000));
  cmd->add_option("--nul-trailer", o->request.dnc.nul_trailer, "fanuc: NUL characters after it")
      ->check(CLI::Range(0, 10000));
  cmd->add_flag("--wait-for-request", o->request.dnc.wait_for_request,
                "fanuc: send once the control requests the tape (DC1)");
  cmd->add_option("--request-timeout", o->request.request_timeout_s,
                  "fanuc: seconds to wait for the request")
      ->check(CLI::Range(0.1, 3600.0));
  cmd->add_option("--xoff-timeout", o->request.xoff_timeout_s,
                  "fanuc: seconds the control may hold the tape")
      ->check(CLI::Range(0.1, 3600.0));
  cmd->add_option("--from", o->request.from_line,
                  "fanuc: restart at this file line, restoring the modal state first")
      ->check(positive_number());
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return send(*o, log); }; });
}

} // namespace subfeed::cli

#include "job/send_request.hpp"

#include "drivers/fanuc_program.hpp"
#include "post/machine_config.hpp"

namespace subfeed::job {

namespace {

void apply_framing_flags(const SendRequest& o, drivers::SerialOptions& serial) {
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
} // namespace

Expected<drivers::SerialOptions> resolve_settings(SendRequest& o) {
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

LinkRequest link_request(const SendRequest& o) {
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

namespace {

Expected<drivers::StreamSummary> send_dnc(SendRequest& o, const drivers::SerialOptions& serial,
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

} // namespace

Expected<drivers::StreamSummary> stream_file(SendRequest& o, const drivers::SerialOptions& serial,
                                             drivers::GcodeSource& source, drivers::Transport& link,
                                             drivers::ControlInbox* inbox,
                                             drivers::StreamObserver& observer) {
  if (o.protocol == "fanuc") {
    return send_dnc(o, serial, link, inbox, observer);
  }
  return drivers::stream_grbl(link, source, o.stream, inbox, observer);
}

} // namespace subfeed::job

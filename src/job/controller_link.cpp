#include "job/controller_link.hpp"

#include "drivers/fanuc_streamer.hpp"
#include "drivers/port_list.hpp"
#include "drivers/tcp_transport.hpp"
#include "sim/pty.hpp"

namespace subfeed::job {

namespace {

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

} // namespace

drivers::SerialOptions serial_options_for(const post::MachineConfig& machine) {
  const auto& s = machine.controller.serial;
  return {s.baud, s.data_bits, to_driver(s.parity), s.stop_bits, to_driver(s.flow_control)};
}

std::string simulator_for(const post::MachineConfig& machine) {
  if (machine.controller.protocol == post::Protocol::fanuc) {
    return "fanuc";
  }
  const bool rotary = machine.axes[3] || machine.axes[4] || machine.axes[5];
  return rotary || machine.controller.line_length > 79 ? "grblhal" : "grbl";
}

Error with_simulated_alarm(Error error, const Link& link) {
  if (link.control) {
    if (const auto alarm = link.control->stats().alarm; !alarm.empty()) {
      error.message += "; the simulated control shows alarm " + alarm;
    }
  }
  return error;
}

Expected<Link> open_link(const LinkRequest& o, const drivers::SerialOptions& serial) {
  Link link;
  std::string port = o.port;
  if (o.sim == "fanuc") {
    SUBFEED_TRY_ASSIGN(auto pty, sim::Pty::open());
    sim::FanucSimOptions control;
    control.baud = o.sim_baud >= 0 ? o.sim_baud : serial.baud;
    control.data_bits = serial.data_bits;
    control.parity = serial.parity == drivers::SerialParity::none
                         ? 'N'
                         : (serial.parity == drivers::SerialParity::odd ? 'O' : 'E');
    control.stop_bits = serial.stop_bits;
    control.request_tape = o.sim_requests_tape;
    control.eia_cr = o.eia_cr;
    control.motion.speed = o.sim_speed;
    // The dry run judges delivery, not the sender's DC3 reaction (the transport tests do,
    // at 9600 baud and no latency): a pty on a busy machine can take milliseconds to hand
    // the DC3 over, which at 115200 baud is more than the control's 10 characters.
    control.link_latency = std::chrono::milliseconds(50);
    link.control =
        std::make_unique<sim::FanucSim>(std::make_unique<sim::Pty>(std::move(pty)), control);
    link.control->start();
    port = link.control->address();
    link.baud = control.baud > 0 ? std::optional<int>(control.baud) : std::nullopt;
  } else if (!o.sim.empty()) {
    SUBFEED_TRY_ASSIGN(auto pty, sim::Pty::open());
    sim::GrblSimOptions sim_options;
    sim_options.grblhal = o.sim == "grblhal";
    sim_options.axes = sim_options.grblhal ? 6 : 3; // grblHAL: X Y Z A B C, any 5-axis type
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
  const auto port_options = o.protocol == "fanuc" ? drivers::dnc_port_options(serial) : serial;
  auto serial_port = drivers::SerialPort::open(port, port_options);
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

} // namespace subfeed::job

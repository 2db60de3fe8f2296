#pragma once
// The link to a controller for `send`, `run` and `resume`: a serial port, a TCP stream, or a
// simulated controller started on a pty and reached through the very serial code a real
// port uses. The simulator, when there is one, lives as long as the Link.

#include "base/error.hpp"
#include "drivers/serial_port.hpp"
#include "drivers/transport.hpp"
#include "post/machine_config.hpp"
#include "sim/fanuc_sim.hpp"
#include "sim/grbl_sim.hpp"

#include <memory>
#include <optional>
#include <string>

namespace subfeed::job {

struct LinkRequest {
  std::string port;
  std::string tcp;
  std::string sim;      // grbl, grblhal or fanuc; empty for a real controller
  std::string protocol; // grbl or fanuc
  double connect_timeout_s = 5.0;
  double sim_speed = 1.0;
  int sim_baud = -1;              // -1: the link's baud
  bool sim_requests_tape = false; // fanuc sim: asks for the tape (DC1) on connect
  bool eia_cr = false;            // fanuc: CR ends blocks
};

struct Link {
  std::unique_ptr<sim::GrblSim> simulator; // declared first: dies after the port
  std::unique_ptr<sim::FanucSim> control;
  std::unique_ptr<drivers::Transport> transport;
  std::optional<int> baud; // for link use; none for TCP
};

[[nodiscard]] drivers::SerialOptions serial_options_for(const post::MachineConfig& machine);

// The simulator that matches a machine: fanuc for the Fanuc protocol; grblhal (six axes,
// 1024-byte buffer, 256-character lines) for a GRBL machine with rotary axes or long lines;
// plain GRBL 1.1 otherwise.
[[nodiscard]] std::string simulator_for(const post::MachineConfig& machine);

// `error` with the alarm a simulated Fanuc control shows on its screen appended, so the
// one error line says why the tape was held (a real control tells the sender nothing: it
// just holds the tape); unchanged without a simulated control or an alarm.
[[nodiscard]] Error with_simulated_alarm(Error error, const Link& link);

[[nodiscard]] Expected<Link> open_link(const LinkRequest& request,
                                       const drivers::SerialOptions& serial);

} // namespace subfeed::job

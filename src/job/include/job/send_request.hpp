#pragma once
// What `send` drips to a controller and how: the settings of a machine config with the
// user's own on top (a flag given wins; a flag that contradicts the machine or the
// simulator is refused), the link they ask for, and the stream of the file over it by the
// machine's protocol (GRBL character counting or Fanuc-style DNC).

#include "base/error.hpp"
#include "job/controller_link.hpp"

#include "drivers/control_inbox.hpp"
#include "drivers/fanuc_streamer.hpp"
#include "drivers/gcode_source.hpp"
#include "drivers/grbl_streamer.hpp"
#include "drivers/serial_port.hpp"

#include <string>

namespace subfeed::job {

struct SendRequest {
  std::string file;
  std::string port;
  std::string tcp;
  std::string sim;
  std::string machine;
  int baud = 0; // 0: from the machine config, else 115200
  double connect_timeout_s = 5.0;
  double sim_speed = 1.0;
  int sim_baud = -1;    // -1: the link's baud
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

// The serial settings: the machine's (or for DNC without one, 7E2 with XON/XOFF), then the
// flags. Settles `protocol` and fills the stream options the machine knows.
[[nodiscard]] Expected<drivers::SerialOptions> resolve_settings(SendRequest& request);

[[nodiscard]] LinkRequest link_request(const SendRequest& request);

// Streams the file over `link` by the settled protocol (`source`, opened by the caller
// before the link so that a missing file is told first, is the GRBL stream's).
[[nodiscard]] Expected<drivers::StreamSummary>
stream_file(SendRequest& request, const drivers::SerialOptions& serial,
            drivers::GcodeSource& source, drivers::Transport& link, drivers::ControlInbox* inbox,
            drivers::StreamObserver& observer);

} // namespace subfeed::job

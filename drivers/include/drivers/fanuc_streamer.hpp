#pragma once
// Drip-feeds a program to a Fanuc-style control over RS-232 (DNC). A pty or a USB adapter
// holds bytes the sender can no longer take back, so the sender paces its own writes at the
// line's character rate (start bit, data bits, parity, stop bits) and keeps about one
// character in flight: after DC3 (XOFF) it stops within one character, and resumes on DC1
// (XON). Above 19200 baud a character is shorter than the OS timer's resolution and the
// sender writes a few at a time. The program is framed as the control expects ('%' leader,
// O-number, blocks with LF or CR, '%' trailer) unless the file is framed already.

#include "base/error.hpp"
#include "drivers/block_source.hpp"
#include "drivers/control_inbox.hpp"
#include "drivers/grbl_streamer.hpp"
#include "drivers/serial_port.hpp"
#include "drivers/transport.hpp"

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace subfeed::drivers {

struct FanucStreamOptions {
  SerialOptions serial{9600, 7, SerialParity::even, 2,
                       SerialFlow::xon_xoff}; // for the character rate
  bool eia_cr = false;                        // end blocks with CR (EIA option) instead of LF (ISO)
  int program_number = 1;                     // O-number when the file has no framing
  int nul_leader = 0;                         // NUL characters before the program
  int nul_trailer = 0;                        // and after it
  bool wait_for_request = false;              // send only once the control asks for the tape (DC1)
  std::chrono::milliseconds request_timeout{60000};
  std::chrono::milliseconds xoff_timeout{30000}; // the control may hold the tape this long
  std::optional<long> from_line; // restart: restore the modal state, then send from this line
  // With from_line: blocks sent after the modal state is restored and before that line (a
  // resume's safe approach); they count as line 0.
  std::vector<std::string> restart_blocks;
};

// Progress is reported through StreamObserver: lines_sent counts blocks sent (the control
// does not acknowledge blocks), link_state is "XOFF" while the control holds the tape.
[[nodiscard]] Expected<StreamSummary> stream_fanuc(Transport& link, BlockSource& program,
                                                   const FanucStreamOptions& options,
                                                   ControlInbox* inbox, StreamObserver& observer);

// How to open the port for DNC: XON/XOFF is handled by the sender itself (the OS must pass
// DC1/DC3 through, or it would stop its own backlog late); RTS/CTS stays with the OS.
[[nodiscard]] SerialOptions dnc_port_options(const SerialOptions& serial);

// Bits on the wire per character for a framing: start, data, parity, stop.
[[nodiscard]] int bits_per_character(const SerialOptions& serial);

} // namespace subfeed::drivers

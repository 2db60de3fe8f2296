#pragma once
// Streams a G-code file to a GRBL 1.1 or grblHAL controller with character counting: the
// bytes of unacknowledged lines (each with its '\n') never exceed the controller's serial RX
// buffer, read from `$I` ([OPT:]) unless overridden, 128 when the controller does not say.
// Lines that write EEPROM, and every line with --send-and-wait, go alone. Realtime bytes
// bypass the count. Every reply is mapped back to the file line it answers.
//
// Faults stop motion first and explain second: no program line is written once a fault
// reply has been read. An `error:N` or an unexpected reset (welcome banner) puts the
// machine in feed hold at once, waits until it has stopped and resets it (unless errors are
// to be collected); an ALARM ends the stream at once. The report, built once the
// controller has answered what it will, lists the lines acknowledged and the lines sent but
// not run (refused, or dropped unread by the reset). A lost link, a controller that falls
// silent and a lost acknowledgement are reported with the last line known acknowledged. A
// stop command (Ctrl-C) holds, waits for Hold:0, then resets, so the controller raises no
// ALARM:3.

#include "base/error.hpp"
#include "drivers/control_inbox.hpp"
#include "drivers/grbl_reply.hpp"
#include "drivers/line_source.hpp"
#include "drivers/transport.hpp"

#include <chrono>
#include <optional>
#include <string>

namespace subfeed::drivers {

struct GrblStreamOptions {
  std::optional<int> rx_buffer;  // bytes; overrides what the controller reports
  std::optional<int> line_limit; // characters; default 79 (GRBL) or 256 (grblHAL)
  bool send_and_wait = false;    // every line alone (slow, for debugging a machine)
  bool keep_comments = false;
  bool continue_on_error = false; // report errors and go on (check runs)
  bool check_first = false;       // run the whole file through check mode ($C) first
  double status_hz = 5.0;         // status polls per second; GRBL wants at most 5
  std::chrono::milliseconds connect_timeout{5000};
  std::chrono::milliseconds silence_timeout{10000}; // no byte from a controller with work pending
  std::chrono::milliseconds hold_timeout{5000};     // waiting for Hold:0 when stopping
};

struct ControllerInfo {
  std::string banner;  // empty when the controller did not reset on connect
  std::string version; // from [VER:]
  bool grblhal = false;
  int rx_buffer = 128;
  bool rx_buffer_reported = false; // false: fallback or override
  std::optional<int> planner_blocks;
  int line_limit = 79;
};

struct StreamProgress {
  long lines_total = 0;
  long lines_sent = 0;
  long lines_acked = 0;
  long bytes_sent = 0;
  int rx_in_flight = 0; // bytes
  double elapsed_s = 0.0;
  bool checking = false; // the check-mode pass of --check
  std::optional<StatusReport> status;
  std::string link_state; // shown when there is no status report (DNC: "send", "XOFF")
};

struct LineError {
  std::string file;
  long line = 0;
  int code = 0;
  bool latched = false; // grblHAL rejected it for an earlier error, not on its own merits
};

// What a stream reports while it runs; all calls come from the streaming thread.
class StreamObserver {
public:
  virtual ~StreamObserver() = default;
  virtual void connected(const ControllerInfo& /*info*/) {}
  virtual void progress(const StreamProgress& /*progress*/) {}
  virtual void message(std::string_view /*line*/) {} // [MSG:], [GC:], settings ...
  virtual void line_error(const LineError& /*error*/) {}
  virtual void phase(std::string_view /*name*/) {} // "check", "stream", "finishing"
  // For the journal: a program line (GRBL) or block (DNC) went out, and its answer.
  virtual void line_sent(long /*line*/, long /*bytes*/) {}
  virtual void line_answered(long /*line*/, int /*error_code*/) {}
  // Things on the link a resume must know of: "alarm", "reset", "xoff", "xon", "hold".
  virtual void link_event(std::string_view /*name*/, std::string_view /*detail*/) {}
};

struct StreamSummary {
  ControllerInfo controller;
  long lines = 0;
  long bytes = 0;
  long errors = 0; // answered with error:N (only with continue_on_error)
  double seconds = 0.0;
  long unknown_replies = 0; // line noise and anything unrecognised
};

// `inbox` may be null. The link stays open; the caller owns it.
[[nodiscard]] Expected<StreamSummary> stream_grbl(Transport& link, LineSource& source,
                                                  const GrblStreamOptions& options,
                                                  ControlInbox* inbox, StreamObserver& observer);

} // namespace subfeed::drivers

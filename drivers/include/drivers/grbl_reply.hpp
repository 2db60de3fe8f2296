#pragma once
// What one line from a GRBL 1.1 or grblHAL controller means to a sender. Only `ok` and
// `error:N` answer (retire) a sent line; everything else is a push message that must never
// be counted against the sender's queue.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace subfeed::drivers {

enum class ReplyKind {
  ok,
  error,        // error:N (code)
  alarm,        // ALARM:N (code)
  banner,       // welcome message: the controller has just reset
  status,       // <...> status report
  feedback,     // [MSG:...], [GC:...], [HLP:...], [VER:...], [OPT:...], [echo:...], [G54:...] ...
  setting,      // $n=v while dumping settings, $Nn=... startup lines
  startup_echo, // >G54G20:ok  (the ":ok" is not an answer)
  empty,
  unknown, // line noise or anything else; never counted
};

struct Reply {
  ReplyKind kind = ReplyKind::unknown;
  int code = 0;          // for error and alarm
  bool grblhal = false;  // for banner
  std::string_view text; // the line without its terminator
};

[[nodiscard]] Reply classify_reply(std::string_view line);

struct StatusReport {
  std::string state; // Idle, Run, Hold, Jog, Alarm, Door, Check, Home, Sleep, Tool
  int substate = -1; // Hold:0/1, Door:0-3; -1 when absent
  std::vector<double> machine_position; // MPos (or WPos when work_position)
  bool work_position = false;
  std::optional<int> planner_free;                // Bf: blocks
  std::optional<int> rx_free;                     // Bf: bytes
  std::optional<double> feed;                     // FS/F: mm/min
  std::optional<double> spindle;                  // FS: rpm
  std::optional<long> line_number;                // Ln:
  std::optional<std::vector<double>> work_offset; // WCO:
  std::optional<std::array<int, 3>> overrides;    // Ov: feed, rapid, spindle %
};

// A status report's fields; nullopt when the line is not a well-formed report.
[[nodiscard]] std::optional<StatusReport> parse_status(std::string_view line);

struct BuildOptions {
  std::optional<int> planner_blocks;
  std::optional<int> rx_buffer;
};

// [OPT:flags,blocks,rx(,...)] from $I.
[[nodiscard]] BuildOptions parse_build_options(std::string_view line);

// GRBL 1.1's meaning of error:N and ALARM:N, for reports.
[[nodiscard]] std::string_view error_meaning(int code);
[[nodiscard]] std::string_view alarm_meaning(int code);

} // namespace subfeed::drivers

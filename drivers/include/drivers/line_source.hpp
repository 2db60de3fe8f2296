#pragma once
// Where the GRBL streamer takes a program's lines from: a file on disk (GcodeSource) or a
// program still being posted (LiveGcode). Lines come prepared for the controller (comments
// and spaces removed unless kept, upper case, checked against the line limit) and numbered
// as lines of the program text, blank ones counted, so replies map back to file lines.

#include "base/error.hpp"
#include "drivers/gcode_line.hpp"

#include <chrono>
#include <optional>
#include <string>

namespace subfeed::drivers {

struct SourceLine {
  long number = 0; // 1-based line in the program text
  PreparedLine line;
};

struct ScanSummary {
  long lines_to_send = 0; // non-blank lines; 0 when not known ahead (a live program)
  long bytes_to_send = 0; // including one '\n' per line
};

class LineSource {
public:
  virtual ~LineSource() = default;
  [[nodiscard]] virtual const std::string& name() const = 0;
  virtual void set_rules(const LineRules& rules) = 0;
  // Checks every line before anything is sent where the whole program is at hand.
  [[nodiscard]] virtual Expected<ScanSummary> scan() = 0;
  // Back to the first line; a live program can only be "rewound" before it is read.
  [[nodiscard]] virtual Expected<void> rewind() = 0;
  // The next line with something to send; nullopt at the end of the program.
  [[nodiscard]] virtual Expected<std::optional<SourceLine>> next() = 0;
  // Whether next() answers without waiting on whoever writes the program, waiting up to
  // `wait` for that: a sender serves the controller (polls, faults, stops) meanwhile instead
  // of falling silent. A file is always ready.
  [[nodiscard]] virtual bool ready(std::chrono::milliseconds /*wait*/) { return true; }
};

} // namespace subfeed::drivers

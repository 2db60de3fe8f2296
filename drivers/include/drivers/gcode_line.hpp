#pragma once
// Turns one line of a G-code file into the bytes a GRBL-style controller is sent: comments
// and spaces removed (unless kept), letters upper-cased. Refuses, before anything is sent,
// what the controller would misread: characters it takes as realtime commands ('?', '!',
// '~' and bytes from 0x80, which act even inside a comment), control characters, and lines
// longer than its line buffer.

#include "base/error.hpp"

#include <string>
#include <string_view>

namespace subfeed::drivers {

struct LineRules {
  int line_limit = 79;        // characters after stripping (GRBL 1.1: 79; grblHAL: 256)
  bool keep_comments = false; // send comments and spaces as written
};

struct PreparedLine {
  std::string text;           // without the line ending; empty for a blank or comment line
  bool send_and_wait = false; // must be sent alone (EEPROM write or system command)
};

// `where` names the file and line for errors.
[[nodiscard]] Expected<PreparedLine> prepare_line(std::string_view raw, const LineRules& rules,
                                                  const Where& where);

// `$` system commands and settings, G10 L2/L20, G28.1, G30.1: commands that write EEPROM
// (the AVR stops reading serial while it does) or whose answer the sender waits for.
[[nodiscard]] bool needs_send_and_wait(std::string_view stripped);

} // namespace subfeed::drivers

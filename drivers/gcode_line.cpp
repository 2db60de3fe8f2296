#include "drivers/gcode_line.hpp"

#include "gcode/words.hpp"

#include <cctype>
#include <cstdio>

namespace subfeed::drivers {

namespace {

bool realtime_character(unsigned char c) {
  return c == '?' || c == '!' || c == '~' || c >= 0x80;
}

std::string describe_byte(unsigned char c) {
  char text[16];
  if (std::isprint(c) != 0) {
    std::snprintf(text, sizeof text, "'%c'", c);
  } else {
    std::snprintf(text, sizeof text, "byte 0x%02X", c);
  }
  return text;
}

} // namespace

bool needs_send_and_wait(std::string_view s) {
  if (!s.empty() && s.front() == '$') {
    return true;
  }
  bool g10 = false, l2 = false, home_set = false;
  // Words up to the first that is not one: the controller will refuse such a line anyway.
  (void)gcode::for_each_word(s, [&](const gcode::Word& w) {
    g10 = g10 || (w.letter == 'G' && w.number == "10");
    l2 = l2 || (w.letter == 'L' && (w.number == "2" || w.number == "20"));
    home_set = home_set || (w.letter == 'G' && (w.number == "28.1" || w.number == "30.1"));
  });
  return (g10 && l2) || home_set;
}

Expected<PreparedLine> prepare_line(std::string_view raw, const LineRules& rules,
                                    const Where& where) {
  for (const char ch : raw) {
    const auto c = static_cast<unsigned char>(ch);
    if (realtime_character(c)) {
      return fail(ErrorCode::bad_input,
                  describe_byte(c) + " would act as a realtime command on the controller", where);
    }
    if (c < 0x20 && c != '\t') {
      return fail(ErrorCode::bad_input, "control character " + describe_byte(c) + " in line",
                  where);
    }
  }
  const std::string stripped = gcode::strip(raw).text;
  if (static_cast<int>(stripped.size()) > rules.line_limit) {
    return fail(ErrorCode::bad_input,
                "line is " + std::to_string(stripped.size()) + " characters after stripping; the " +
                    "controller takes at most " + std::to_string(rules.line_limit),
                where);
  }
  PreparedLine line;
  line.send_and_wait = needs_send_and_wait(stripped);
  if (rules.keep_comments && !stripped.empty()) {
    line.text = std::string(raw);
    while (!line.text.empty() && (line.text.back() == ' ' || line.text.back() == '\t')) {
      line.text.pop_back();
    }
  } else {
    line.text = stripped;
  }
  return line;
}

} // namespace subfeed::drivers

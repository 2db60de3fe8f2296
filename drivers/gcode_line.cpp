#include "drivers/gcode_line.hpp"

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

// The G-code words of a stripped line whose letter is `letter`, as text after the letter.
bool has_word(std::string_view line, char letter, std::string_view value) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] != letter) {
      continue;
    }
    std::size_t end = i + 1;
    while (end < line.size() && (std::isdigit(static_cast<unsigned char>(line[end])) != 0 ||
                                 line[end] == '.' || line[end] == '-' || line[end] == '+')) {
      ++end;
    }
    if (line.substr(i + 1, end - i - 1) == value) {
      return true;
    }
  }
  return false;
}

std::string strip(std::string_view raw) {
  std::string out;
  bool in_comment = false;
  for (const char c : raw) {
    if (in_comment) {
      in_comment = c != ')';
    } else if (c == '(') {
      in_comment = true;
    } else if (c == ';') {
      break;
    } else if (c != ' ' && c != '\t') {
      out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
  }
  return out;
}

} // namespace

bool needs_send_and_wait(std::string_view s) {
  if (!s.empty() && s.front() == '$') {
    return true;
  }
  return (has_word(s, 'G', "10") && (has_word(s, 'L', "2") || has_word(s, 'L', "20"))) ||
         has_word(s, 'G', "28.1") || has_word(s, 'G', "30.1");
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
  const std::string stripped = strip(raw);
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

#include "restart_point.hpp"

#include "base/number_text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>

namespace subfeed::cli {

namespace {

// Axis words of one line onto the joints; `tcp` follows G43.4 (on) and G49 (off). Whether
// the line had an axis word.
bool apply_words(std::string_view line, LineEnd& end) {
  bool comment = false;
  bool axis_word = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (comment || c == '(') {
      comment = c != ')';
      continue;
    }
    const auto axis = post::axis_letters.find(c);
    if (axis == std::string_view::npos && c != 'G') {
      continue; // only axis and G words matter: no number parsed for the others
    }
    const auto number = parse_double_prefix(line.substr(i + 1));
    if (!number) {
      continue;
    }
    const double value = number->value;
    if (axis != std::string_view::npos) {
      end.words[axis] = value;
      axis_word = true;
    } else if (std::abs(value - 43.4) < 1e-9) {
      end.tcp = true;
    } else if (std::abs(value - 49.0) < 1e-9) {
      end.tcp = false;
    }
  }
  return axis_word;
}

std::optional<double> place_on_move(const ProgramMove& m, const std::vector<double>& position,
                                    int decimals) {
  const double tolerance = 0.75 * std::pow(10.0, -std::min(decimals, 3));
  const std::size_t n = std::min<std::size_t>(6, position.size());
  double along = 0.0, length2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    along += (position[i] - m.start[i]) * (m.end[i] - m.start[i]);
    length2 += (m.end[i] - m.start[i]) * (m.end[i] - m.start[i]);
  }
  const double t = length2 > 0.0 ? std::clamp(along / length2, 0.0, 1.0) : 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(m.start[i] + t * (m.end[i] - m.start[i]) - position[i]) > tolerance) {
      return std::nullopt;
    }
  }
  return t;
}

} // namespace

bool moves_an_axis(std::string_view line) {
  LineEnd ignored;
  return apply_words(line, ignored);
}

Expected<ProgramWindow> read_window(const std::string& program, long lo, long hi, long extra) {
  std::ifstream in(program);
  if (!in) {
    return fail(ErrorCode::bad_input, "cannot read the program", {program, 0, {}});
  }
  ProgramWindow w;
  LineEnd end;
  w.line_end[0] = end;
  std::string text;
  while (std::getline(in, text)) {
    ++w.lines;
    const Joints before = end.words;
    const bool moves = apply_words(text, end);
    if ((w.lines >= lo - 1 && w.lines <= hi) || w.lines == extra) {
      w.line_end[w.lines] = end;
    }
    if (w.lines >= lo && w.lines <= hi && moves) {
      w.moves.push_back({w.lines, before, end.words});
    }
  }
  if (extra > w.lines) {
    w.line_end[extra] = end; // past the end: nothing is left to run
  }
  return w;
}

std::optional<RestartPoint> find_machine(const ProgramWindow& window,
                                         const std::vector<double>& position, int decimals) {
  std::optional<RestartPoint> found;
  for (const auto& m : window.moves) {
    const auto t = place_on_move(m, position, decimals);
    if (!t) {
      continue;
    }
    const bool at_end = *t >= 1.0 || place_on_move({m.line, m.end, m.end}, position, decimals);
    const bool at_start =
        *t <= 0.0 || place_on_move({m.line, m.start, m.start}, position, decimals);
    const RestartPoint here{at_end ? m.line : m.line - 1, !at_end && !at_start};
    if (!found || here.after >= found->after) {
      found = here;
    }
  }
  return found;
}

namespace {

// The sequence number a program line starts with, if it starts with one.
std::optional<long> sequence_number(const std::string& text) {
  const auto start = text.find_first_not_of(' ');
  if (start == std::string::npos || std::toupper(static_cast<unsigned char>(text[start])) != 'N') {
    return std::nullopt;
  }
  const std::string_view rest = std::string_view(text).substr(start + 1);
  return parse_long(rest.substr(0, rest.find_first_not_of("0123456789")));
}

} // namespace

Expected<long> find_sequence_number(const std::string& program, long number, long last_sent) {
  std::ifstream in(program);
  if (!in) {
    return fail(ErrorCode::bad_input, "cannot read the program", {program, 0, {}});
  }
  long line = 0, found = 0;
  std::string text;
  while (line < last_sent && std::getline(in, text)) {
    ++line;
    if (sequence_number(text) == number) {
      found = line;
    }
  }
  while (found == 0 && std::getline(in, text)) {
    ++line;
    if (const auto n = sequence_number(text)) {
      if (*n == number) {
        found = line;
      }
      break;
    }
  }
  if (found == 0) {
    return fail(
        ErrorCode::usage,
        fmt::format("no block N{} among the {} lines sent or the next block", number, last_sent),
        {program, 0, "--block"});
  }
  return found;
}

} // namespace subfeed::cli

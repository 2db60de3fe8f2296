#include "job/restart_point.hpp"

#include "base/number_text.hpp"
#include "gcode/words.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>

namespace subfeed::job {

namespace {

// Axis words of one line onto the joints; `tcp` follows G43.4 (on) and G49 (off). Whether
// the line had an axis word; an error (message only) where it is not words.
Expected<bool> apply_words(std::string_view line, LineEnd& end) {
  bool axis_word = false;
  SUBFEED_TRY(gcode::for_each_word(line, [&](const gcode::Word& w) {
    if (const auto axis = post::axis_letters.find(w.letter); axis != std::string_view::npos) {
      end.words[axis] = w.value;
      axis_word = true;
    } else if (w.letter == 'G' && std::abs(w.value - 43.4) < 1e-9) {
      end.tcp = true;
    } else if (w.letter == 'G' && std::abs(w.value - 49.0) < 1e-9) {
      end.tcp = false;
    }
  }));
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
  return apply_words(line, ignored).value_or(false);
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
    auto moves = apply_words(text, end);
    if (!moves) {
      return fail(ErrorCode::bad_input, moves.error().message,
                  {program, static_cast<int>(w.lines), {}});
    }
    if ((w.lines >= lo - 1 && w.lines <= hi) || w.lines == extra) {
      w.line_end[w.lines] = end;
    }
    if (w.lines >= lo && w.lines <= hi && *moves) {
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
  const auto words = gcode::split_words(text);
  if (!words || words->empty() || words->front().letter != 'N') {
    return std::nullopt;
  }
  return parse_long(words->front().number);
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

} // namespace subfeed::job

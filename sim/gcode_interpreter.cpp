#include "sim/gcode_interpreter.hpp"

#include "grbl_codes.hpp"

#include <cctype>
#include <cmath>
#include <optional>
#include <string>

namespace subfeed::sim {

namespace {

using namespace grbl_code;

struct Word {
  char letter;
  double value;
};

// A GRBL number: optional sign, digits, optional point and digits. Returns the length read.
std::size_t read_number(std::string_view text, double& value) {
  std::size_t i = 0;
  bool negative = false;
  if (i < text.size() && (text[i] == '-' || text[i] == '+')) {
    negative = text[i] == '-';
    ++i;
  }
  double result = 0.0;
  bool digits = false;
  while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) != 0) {
    result = result * 10.0 + (text[i++] - '0');
    digits = true;
  }
  if (i < text.size() && text[i] == '.') {
    ++i;
    double scale = 0.1;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) != 0) {
      result += (text[i++] - '0') * scale;
      scale *= 0.1;
      digits = true;
    }
  }
  value = negative ? -result : result;
  return digits ? i : 0;
}

bool is_integer(double v) {
  return std::abs(v - std::round(v)) < 1e-9;
}

int axis_index(char letter) {
  switch (letter) {
  case 'X':
    return 0;
  case 'Y':
    return 1;
  case 'Z':
    return 2;
  case 'A':
    return 3;
  case 'B':
    return 4;
  case 'C':
    return 5;
  default:
    return -1;
  }
}

bool supported_g(double g) {
  static constexpr double codes[] = {0,  1,    2,  3,    4,  10,   17, 18, 19, 20, 21,
                                     28, 28.1, 30, 30.1, 40, 43.1, 49, 53, 54, 55, 56,
                                     57, 58,   59, 61,   80, 90,   91, 92, 93, 94};
  for (const double c : codes) {
    if (std::abs(g - c) < 1e-9) {
      return true;
    }
  }
  return false;
}

bool supported_m(int m) {
  return m == 0 || m == 1 || m == 2 || m == 3 || m == 4 || m == 5 || m == 7 || m == 8 || m == 9 ||
         m == 30;
}

} // namespace

void GcodeInterpreter::reset() {
  absolute_ = true;
  inches_ = false;
  inverse_time_ = false;
  motion_ = 0;
  feed_ = 0.0;
}

SimLineResult GcodeInterpreter::execute(std::string_view line, const AxisArray& position) {
  SimLineResult result;
  std::optional<double> axis_words[6];
  std::optional<double> feed;
  std::optional<double> dwell;
  bool absolute = absolute_, inches = inches_, inverse_time = inverse_time_;
  int motion = motion_;
  bool motion_word = false, l_word = false, g10 = false, g4 = false;
  std::string seen;
  for (std::size_t i = 0; i < line.size();) {
    const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(line[i])));
    if (letter < 'A' || letter > 'Z') {
      return {expected_command_letter, {}, 0.0, false};
    }
    double value = 0.0;
    const std::size_t used = read_number(line.substr(i + 1), value);
    if (used == 0) {
      return {bad_number_format, {}, 0.0, false};
    }
    i += 1 + used;
    const int axis = axis_index(letter);
    if (letter != 'G' && letter != 'M') {
      if (seen.find(letter) != std::string::npos) {
        return {word_repeated, {}, 0.0, false};
      }
      seen += letter;
    }
    if (axis >= 0) {
      if (axis >= axes_) {
        return {unsupported_command, {}, 0.0, false};
      }
      axis_words[axis] = value;
    } else if (letter == 'G') {
      if (!supported_g(value)) {
        return {unsupported_command, {}, 0.0, false};
      }
      const double g = value;
      if (g == 0 || g == 1 || g == 2 || g == 3) {
        if (motion_word) {
          return {modal_group_violation, {}, 0.0, false};
        }
        motion_word = true;
        motion = static_cast<int>(g);
      } else if (g == 90 || g == 91) {
        absolute = g == 90;
      } else if (g == 20 || g == 21) {
        inches = g == 20;
      } else if (g == 93 || g == 94) {
        inverse_time = g == 93;
      } else if (g == 4) {
        g4 = true;
      } else if (g == 10) {
        g10 = true;
      } else if (std::abs(g - 28.1) < 1e-9 || std::abs(g - 30.1) < 1e-9) {
        result.writes_eeprom = true;
      }
    } else if (letter == 'M') {
      if (!is_integer(value)) {
        return {command_not_integer, {}, 0.0, false};
      }
      if (!supported_m(static_cast<int>(value))) {
        return {unsupported_command, {}, 0.0, false};
      }
    } else if (letter == 'F') {
      feed = value;
    } else if (letter == 'P') {
      dwell = value;
    } else if (letter == 'L') {
      l_word = true;
    } else if (letter == 'N' || letter == 'S' || letter == 'T' || letter == 'I' || letter == 'J' ||
               letter == 'K' || letter == 'R') {
      // accepted and not needed for motion timing
    } else {
      return {unsupported_command, {}, 0.0, false};
    }
  }
  if (g10 && l_word) {
    result.writes_eeprom = true; // G10 L2 / L20 write coordinate offsets to EEPROM
  }
  if (g4) {
    result.dwell_s = dwell.value_or(0.0);
  }
  const double unit = inches ? 25.4 : 1.0;
  bool any_axis = false;
  AxisArray target = position;
  for (int a = 0; a < 6; ++a) {
    if (axis_words[a]) {
      any_axis = true;
      const double v = *axis_words[a] * (a < 3 ? unit : 1.0);
      target[a] = absolute ? v + work_offset_[static_cast<std::size_t>(a)] : position[a] + v;
      if (!std::isfinite(target[a])) {
        return {invalid_target, {}, 0.0, false};
      }
    }
  }
  double feed_value = feed_;
  if (feed) {
    feed_value = *feed * (inverse_time ? 1.0 : unit);
  }
  if (any_axis && !g10 && motion != 0) {
    if ((inverse_time && (!feed || *feed <= 0.0)) || (!inverse_time && feed_value <= 0.0)) {
      return {undefined_feed_rate, {}, 0.0, false};
    }
  }
  absolute_ = absolute;
  inches_ = inches;
  inverse_time_ = inverse_time;
  motion_ = motion;
  if (!inverse_time) {
    feed_ = feed_value;
  }
  if (any_axis && !g10) {
    result.move = {true, motion == 0, target, inverse_time ? 0.0 : feed_value,
                   inverse_time && motion != 0 ? 1.0 / feed_value : 0.0};
  }
  return result;
}

} // namespace subfeed::sim

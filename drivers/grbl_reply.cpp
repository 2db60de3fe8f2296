#include "drivers/grbl_reply.hpp"

#include "base/number_text.hpp"

#include <charconv>

namespace subfeed::drivers {

namespace {

std::optional<long> to_integer(std::string_view text) {
  return parse_long(text);
}

std::optional<double> to_number(std::string_view text) {
  return parse_double(text);
}

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const auto at = text.find(separator, start);
    parts.push_back(text.substr(start, at - start));
    if (at == std::string_view::npos) {
      return parts;
    }
    start = at + 1;
  }
}

std::optional<std::vector<double>> numbers(std::string_view text) {
  std::vector<double> values;
  for (const auto part : split(text, ',')) {
    const auto v = to_number(part);
    if (!v) {
      return std::nullopt;
    }
    values.push_back(*v);
  }
  return values;
}

bool apply_field(StatusReport& r, std::string_view field) {
  const auto colon = field.find(':');
  if (colon == std::string_view::npos) {
    return false;
  }
  const auto name = field.substr(0, colon);
  const auto value = field.substr(colon + 1);
  const auto values = numbers(value);
  if (!values) {
    return name == "Pn" || name == "A"; // pin and accessory letters are not numbers
  }
  if (name == "MPos" || name == "WPos") {
    r.machine_position = *values;
    r.work_position = name == "WPos";
    return values->size() >= 3 && values->size() <= 6;
  }
  if (name == "Bf" && values->size() == 2) {
    r.planner_free = static_cast<int>((*values)[0]);
    r.rx_free = static_cast<int>((*values)[1]);
  } else if (name == "FS" && values->size() == 2) {
    r.feed = (*values)[0];
    r.spindle = (*values)[1];
  } else if (name == "F" && values->size() == 1) {
    r.feed = (*values)[0];
  } else if (name == "Ln" && values->size() == 1) {
    r.line_number = static_cast<long>((*values)[0]);
  } else if (name == "WCO") {
    r.work_offset = *values;
  } else if (name == "Ov" && values->size() == 3) {
    r.overrides = {static_cast<int>((*values)[0]), static_cast<int>((*values)[1]),
                   static_cast<int>((*values)[2])};
  }
  return true; // unknown fields (grblHAL adds several) are skipped
}

} // namespace

Reply classify_reply(std::string_view line) {
  Reply reply;
  reply.text = line;
  if (line.empty()) {
    reply.kind = ReplyKind::empty;
  } else if (line == "ok") {
    reply.kind = ReplyKind::ok;
  } else if (line.starts_with("error:")) {
    const auto code = to_integer(line.substr(6));
    reply.kind = code ? ReplyKind::error : ReplyKind::unknown;
    reply.code = static_cast<int>(code.value_or(0));
  } else if (line.starts_with("ALARM:")) {
    const auto code = to_integer(line.substr(6));
    reply.kind = code ? ReplyKind::alarm : ReplyKind::unknown;
    reply.code = static_cast<int>(code.value_or(0));
  } else if (line.starts_with("Grbl ") || line.starts_with("GrblHAL ")) {
    reply.kind = ReplyKind::banner;
    reply.grblhal = line.starts_with("GrblHAL ");
  } else if (line.front() == '<' && line.back() == '>') {
    reply.kind = ReplyKind::status;
  } else if (line.front() == '[' && line.back() == ']') {
    reply.kind = ReplyKind::feedback;
  } else if (line.front() == '$' && line.find('=') != std::string_view::npos) {
    reply.kind = ReplyKind::setting;
  } else if (line.front() == '>') {
    reply.kind = ReplyKind::startup_echo;
  }
  return reply;
}

std::optional<StatusReport> parse_status(std::string_view line) {
  if (line.size() < 3 || line.front() != '<' || line.back() != '>') {
    return std::nullopt;
  }
  const auto fields = split(line.substr(1, line.size() - 2), '|');
  StatusReport r;
  const auto state = split(fields[0], ':');
  r.state = std::string(state[0]);
  if (r.state.empty()) {
    return std::nullopt;
  }
  if (state.size() == 2) {
    const auto sub = to_integer(state[1]);
    if (!sub) {
      return std::nullopt;
    }
    r.substate = static_cast<int>(*sub);
  }
  for (std::size_t i = 1; i < fields.size(); ++i) {
    if (!apply_field(r, fields[i])) {
      return std::nullopt;
    }
  }
  return r;
}

BuildOptions parse_build_options(std::string_view line) {
  BuildOptions options;
  if (!line.starts_with("[OPT:") || !line.ends_with("]")) {
    return options;
  }
  const auto fields = split(line.substr(5, line.size() - 6), ',');
  if (fields.size() >= 3) {
    const auto blocks = to_integer(fields[1]);
    const auto rx = to_integer(fields[2]);
    if (blocks && *blocks > 0) {
      options.planner_blocks = static_cast<int>(*blocks);
    }
    if (rx && *rx > 0) {
      options.rx_buffer = static_cast<int>(*rx);
    }
  }
  return options;
}

std::string_view error_meaning(int code) {
  static constexpr std::array<std::string_view, 39> meanings{
      "unknown error",
      "G-code words consist of a letter and a value; letter was not found",
      "numeric value format is not valid or missing an expected value",
      "'$' system command was not recognized or supported",
      "negative value received for an expected positive value",
      "homing cycle is not enabled via settings",
      "minimum step pulse time must be greater than 3 usec",
      "EEPROM read failed; reset and restored to default values",
      "'$' command cannot be used unless the controller is idle",
      "G-code locked out during alarm or jog state",
      "soft limits cannot be enabled without homing also enabled",
      "max characters per line exceeded; line was not processed",
      "'$' setting value exceeds the maximum step rate supported",
      "safety door detected as opened and door state initiated",
      "build info or startup line exceeded EEPROM line length limit",
      "jog target exceeds machine travel; command ignored",
      "jog command with no '=' or contains prohibited G-code",
      "laser mode requires PWM output",
      "unknown error",
      "unknown error",
      "unsupported or invalid G-code command found in block",
      "more than one G-code command from the same modal group found in block",
      "feed rate has not yet been set or is undefined",
      "G-code command in block requires an integer value",
      "two G-code commands that both require the use of the XYZ axis words were detected",
      "a G-code word was repeated in the block",
      "a G-code command implicitly or explicitly requires XYZ axis words, but none were found",
      "N line number value is not within the valid range of 1 - 9,999,999",
      "a G-code command was sent, but is missing some required P or L value words",
      "system only supports six work coordinate systems G54-G59",
      "G53 G-code command requires either a G0 seek or G1 feed motion mode to be active",
      "axis words found in block when no command or current modal state uses them",
      "G2 and G3 arcs require at least one in-plane axis word",
      "motion command target is invalid",
      "arc radius value is invalid",
      "G2 and G3 arcs require at least one in-plane offset word",
      "unused value words were found in block",
      "G43.1 dynamic tool length offset is not assigned to configured tool length axis",
      "tool number greater than max supported value"};
  return code >= 0 && code < static_cast<int>(meanings.size())
             ? meanings[static_cast<std::size_t>(code)]
             : "unknown error";
}

std::string_view alarm_meaning(int code) {
  static constexpr std::array<std::string_view, 10> meanings{
      "unknown alarm",
      "hard limit triggered; position is likely lost, re-homing is highly recommended",
      "G-code motion target exceeds machine travel (soft limit)",
      "reset while in motion; position is likely lost, re-homing is highly recommended",
      "probe fail: the probe is not in the expected initial state",
      "probe fail: the probe did not contact the workpiece",
      "homing fail: reset during active homing cycle",
      "homing fail: safety door was opened during homing",
      "homing fail: cycle failed to clear the limit switch when pulling off",
      "homing fail: could not find the limit switch within the search distance"};
  return code >= 0 && code < static_cast<int>(meanings.size())
             ? meanings[static_cast<std::size_t>(code)]
             : "unknown alarm";
}

} // namespace subfeed::drivers

#include "post/machine_config.hpp"

#include "toml_table_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <sstream>

namespace subfeed::post {

std::string_view to_string(KinematicsType type) {
  constexpr std::array<std::string_view, 4> names{"xyz", "xyzac-trt", "xyzbc-trt", "xyzac-head"};
  return names[static_cast<std::size_t>(type)];
}
std::string_view to_string(Protocol protocol) {
  return protocol == Protocol::grbl ? "grbl" : "fanuc";
}
std::string_view to_string(Dialect dialect) {
  constexpr std::array<std::string_view, 3> names{"grbl", "fanuc", "linuxcnc"};
  return names[static_cast<std::size_t>(dialect)];
}
std::string_view to_string(Parity parity) {
  constexpr std::array<std::string_view, 3> names{"none", "even", "odd"};
  return names[static_cast<std::size_t>(parity)];
}
std::string_view to_string(FlowControl flow) {
  constexpr std::array<std::string_view, 4> names{"none", "xon-xoff", "rts-cts", "both"};
  return names[static_cast<std::size_t>(flow)];
}

namespace {

constexpr double max_linear_travel = 100000.0; // mm
constexpr double max_rotary_limit = 3600.0;    // deg: ten turns of a limited axis
constexpr double max_feed_limit = 1.0e6;       // mm/min or deg/min
constexpr std::array standard_bauds{300,   600,   1200,   2400,   4800,   9600,  19200,
                                    38400, 57600, 115200, 230400, 460800, 921600};

template <class T>
Expected<T> from_names(TomlTableReader& table, std::string_view key,
                       std::initializer_list<std::string_view> names) {
  SUBFEED_TRY_ASSIGN(const std::string name, table.choice(key, names));
  int index = 0;
  for (const auto n : names) {
    if (n == name) {
      break;
    }
    ++index;
  }
  return static_cast<T>(index);
}

Expected<long> integer_in(TomlTableReader& table, std::string_view key, long lo, long hi) {
  SUBFEED_TRY_ASSIGN(const long value, table.integer(key));
  if (value < lo || value > hi) {
    return table.invalid(key, std::to_string(value) + " is outside " + std::to_string(lo) + ".." +
                                  std::to_string(hi));
  }
  return value;
}

Expected<double> number_in(TomlTableReader& table, std::string_view key, double lo, double hi,
                           std::string_view unit) {
  SUBFEED_TRY_ASSIGN(const double value, table.number(key));
  if (value < lo || value > hi) {
    std::ostringstream message;
    message << value << ' ' << unit << " is outside " << lo << ".." << hi << ' ' << unit;
    return table.invalid(key, message.str());
  }
  return value;
}

Expected<AxisLimits> read_axis(TomlTableReader& axis, bool rotary) {
  AxisLimits limits;
  const std::string_view unit = rotary ? "deg" : "mm";
  const double bound = rotary ? max_rotary_limit : max_linear_travel;
  if (rotary && axis.has("cyclic")) {
    SUBFEED_TRY_ASSIGN(limits.cyclic, axis.boolean("cyclic"));
  }
  if (limits.cyclic) {
    for (const auto key : {"min", "max"}) {
      if (axis.has(key)) {
        return axis.invalid(key, "a cyclic axis has no travel limits");
      }
    }
  } else {
    SUBFEED_TRY_ASSIGN(limits.min, number_in(axis, "min", -bound, bound, unit));
    SUBFEED_TRY_ASSIGN(limits.max, number_in(axis, "max", -bound, bound, unit));
    if (limits.min >= limits.max) {
      return axis.invalid("max", "must be greater than min");
    }
  }
  SUBFEED_TRY_ASSIGN(limits.max_feed, number_in(axis, "max_feed", 1e-3, max_feed_limit,
                                                rotary ? "deg/min" : "mm/min"));
  SUBFEED_TRY(axis.finish());
  return limits;
}

Expected<AxisSet> read_axes(TomlTableReader& top, KinematicsType type) {
  SUBFEED_TRY_ASSIGN(auto axes_table, top.table("axes"));
  const std::string_view letters = type == KinematicsType::xyz         ? "xyz"
                                   : type == KinematicsType::xyzbc_trt ? "xyzbc"
                                                                       : "xyzac";
  AxisSet axes;
  for (const char letter : letters) {
    const std::string key(1, letter);
    SUBFEED_TRY_ASSIGN(auto axis_table, axes_table.table(key));
    const auto index = axis_letters.find(static_cast<char>(std::toupper(letter)));
    SUBFEED_TRY_ASSIGN(axes[index], read_axis(axis_table, is_rotary_axis(index)));
  }
  SUBFEED_TRY(axes_table.finish());
  return axes;
}

Expected<int> direction(TomlTableReader& table, std::string_view key) {
  SUBFEED_TRY_ASSIGN(const long value, table.integer(key));
  if (value != 1 && value != -1) {
    return table.invalid(
        key, "must be 1 (ISO: the tool turns by the right-hand rule) or -1 (LinuxCNC default)");
  }
  return static_cast<int>(value);
}

Expected<double> length(TomlTableReader& k, std::string_view key) {
  return number_in(k, key, -max_linear_travel, max_linear_travel, "mm");
}

Expected<void> read_pivot(TomlTableReader& k, RotaryGeometry& g) {
  SUBFEED_TRY_ASSIGN(const auto pivot, k.numbers("pivot", 3));
  for (std::size_t i = 0; i < 3; ++i) {
    if (std::abs(pivot[i]) > max_linear_travel) {
      return k.invalid("pivot", "coordinate outside the work volume bound of 100000 mm");
    }
    g.pivot[i] = pivot[i];
  }
  return {};
}

// Keys per type, as LinuxCNC's kinematics modules name them.
Expected<RotaryGeometry> read_rotary(TomlTableReader& top, KinematicsType type) {
  SUBFEED_TRY_ASSIGN(auto k, top.table("kinematics"));
  RotaryGeometry g;
  if (type == KinematicsType::xyzac_head) {
    SUBFEED_TRY_ASSIGN(g.pivot_length, number_in(k, "pivot_length", 0.0, 10000.0, "mm"));
  } else {
    SUBFEED_TRY(read_pivot(k, g));
    if (type == KinematicsType::xyzbc_trt) {
      SUBFEED_TRY_ASSIGN(g.x_offset, length(k, "x_offset"));
    } else {
      SUBFEED_TRY_ASSIGN(g.y_offset, length(k, "y_offset"));
    }
    SUBFEED_TRY_ASSIGN(g.z_offset, length(k, "z_offset"));
  }
  if (k.has("tool_length")) {
    SUBFEED_TRY_ASSIGN(g.tool_length, number_in(k, "tool_length", 0.0, 10000.0, "mm"));
  }
  const auto tilt_key = type == KinematicsType::xyzbc_trt ? "b_direction" : "a_direction";
  SUBFEED_TRY_ASSIGN(g.tilt_direction, direction(k, tilt_key));
  SUBFEED_TRY_ASSIGN(g.c_direction, direction(k, "c_direction"));
  SUBFEED_TRY(k.finish());
  return g;
}

Expected<PostSettings> read_post(TomlTableReader& top, const AxisSet& axes) {
  PostSettings s;
  if (!top.has("post")) {
    return s;
  }
  SUBFEED_TRY_ASSIGN(auto p, top.table("post"));
  if (p.has("singularity_cone")) {
    SUBFEED_TRY_ASSIGN(s.singularity_cone, number_in(p, "singularity_cone", 0.0, 10.0, "deg"));
  }
  if (p.has("retract")) {
    SUBFEED_TRY_ASSIGN(s.retract, number_in(p, "retract", 0.0, 1000.0, "mm"));
  }
  if (p.has("safe_z")) {
    SUBFEED_TRY_ASSIGN(s.safe_z, length(p, "safe_z"));
    const auto& z = *axes[2];
    if (*s.safe_z < z.min || *s.safe_z > z.max) {
      return p.invalid("safe_z", "must lie within the Z travel limits");
    }
  }
  if (p.has("preferred_tilt")) {
    enum class Tilt { positive, negative, either };
    SUBFEED_TRY_ASSIGN(const Tilt tilt,
                       from_names<Tilt>(p, "preferred_tilt", {"positive", "negative", "either"}));
    s.preferred_tilt = tilt == Tilt::positive ? 1 : tilt == Tilt::negative ? -1 : 0;
  }
  SUBFEED_TRY(p.finish());
  return s;
}

Expected<SerialSettings> read_serial(TomlTableReader& controller, Protocol protocol) {
  SerialSettings s;
  if (protocol == Protocol::fanuc) { // the common ISO tape setting, 7E2 with XON/XOFF
    s = {9600, 7, Parity::even, 2, FlowControl::xon_xoff};
  }
  if (!controller.has("serial")) {
    return s;
  }
  SUBFEED_TRY_ASSIGN(auto serial, controller.table("serial"));
  if (serial.has("baud")) {
    SUBFEED_TRY_ASSIGN(const long baud, serial.integer("baud"));
    if (std::ranges::find(standard_bauds, baud) == standard_bauds.end()) {
      return serial.invalid("baud", std::to_string(baud) + " is not a standard rate (300..921600)");
    }
    s.baud = static_cast<int>(baud);
  }
  if (serial.has("data_bits")) {
    SUBFEED_TRY_ASSIGN(s.data_bits, integer_in(serial, "data_bits", 7, 8));
  }
  if (serial.has("parity")) {
    SUBFEED_TRY_ASSIGN(s.parity, from_names<Parity>(serial, "parity", {"none", "even", "odd"}));
  }
  if (serial.has("stop_bits")) {
    SUBFEED_TRY_ASSIGN(s.stop_bits, integer_in(serial, "stop_bits", 1, 2));
  }
  if (serial.has("flow_control")) {
    SUBFEED_TRY_ASSIGN(
        s.flow_control,
        from_names<FlowControl>(serial, "flow_control", {"none", "xon-xoff", "rts-cts", "both"}));
  }
  SUBFEED_TRY(serial.finish());
  return s;
}

Expected<void> read_controller_options(TomlTableReader& c, ControllerSettings& s) {
  if (c.has("rx_buffer")) {
    SUBFEED_TRY_ASSIGN(s.rx_buffer, integer_in(c, "rx_buffer", 16, 65536));
  }
  if (c.has("line_length")) {
    SUBFEED_TRY_ASSIGN(s.line_length, integer_in(c, "line_length", 16, 1024));
  }
  if (c.has("decimals")) {
    SUBFEED_TRY_ASSIGN(s.decimals, integer_in(c, "decimals", 0, 6));
  }
  if (c.has("tcp")) {
    SUBFEED_TRY_ASSIGN(s.tcp, c.boolean("tcp"));
    if (s.tcp && s.dialect == Dialect::grbl) {
      return c.invalid("tcp", "the grbl dialect has no tool-centre-point control");
    }
  }
  if (c.has("program_number")) {
    if (s.dialect != Dialect::fanuc) {
      return c.invalid("program_number", "applies to the fanuc dialect only");
    }
    SUBFEED_TRY_ASSIGN(s.program_number, integer_in(c, "program_number", 1, 9999));
  }
  return {};
}

Expected<ControllerSettings> read_controller(TomlTableReader& top) {
  SUBFEED_TRY_ASSIGN(auto c, top.table("controller"));
  ControllerSettings s;
  SUBFEED_TRY_ASSIGN(s.protocol, from_names<Protocol>(c, "protocol", {"grbl", "fanuc"}));
  s.dialect = s.protocol == Protocol::grbl ? Dialect::grbl : Dialect::fanuc;
  s.line_length = s.protocol == Protocol::grbl ? 79 : 256;
  if (c.has("dialect")) {
    SUBFEED_TRY_ASSIGN(s.dialect, from_names<Dialect>(c, "dialect", {"grbl", "fanuc", "linuxcnc"}));
  }
  SUBFEED_TRY(read_controller_options(c, s));
  SUBFEED_TRY_ASSIGN(s.serial, read_serial(c, s.protocol));
  SUBFEED_TRY(c.finish());
  return s;
}

Expected<MachineConfig> read_config(const toml::table& root, const std::string& source) {
  TomlTableReader top(root, "", source, 1);
  MachineConfig config;
  config.source = source;
  SUBFEED_TRY_ASSIGN(auto machine, top.table("machine"));
  SUBFEED_TRY_ASSIGN(config.name, machine.string("name"));
  if (config.name.empty()) {
    return machine.invalid("name", "must not be empty");
  }
  SUBFEED_TRY_ASSIGN(config.kinematics,
                     from_names<KinematicsType>(machine, "kinematics",
                                                {"xyz", "xyzac-trt", "xyzbc-trt", "xyzac-head"}));
  SUBFEED_TRY(machine.finish());
  SUBFEED_TRY_ASSIGN(config.axes, read_axes(top, config.kinematics));
  if (config.kinematics != KinematicsType::xyz) {
    SUBFEED_TRY_ASSIGN(config.rotary, read_rotary(top, config.kinematics));
  } else if (top.has("kinematics")) {
    return top.invalid("kinematics", "an xyz machine has no rotary geometry");
  }
  SUBFEED_TRY_ASSIGN(config.post, read_post(top, config.axes));
  SUBFEED_TRY_ASSIGN(config.controller, read_controller(top));
  SUBFEED_TRY(top.finish());
  return config;
}

} // namespace

Expected<MachineConfig> parse_machine_config(std::string_view text, const std::string& source) {
  SUBFEED_TRY_ASSIGN(const auto root, parse_toml(text, source));
  return read_config(root, source);
}

Expected<MachineConfig> load_machine_config(const std::filesystem::path& path) {
  SUBFEED_TRY_ASSIGN(const auto text, read_config_text(path, "machine config"));
  return parse_machine_config(text, path.string());
}

std::optional<double> tilt_range_deg(const MachineConfig& machine) {
  const std::size_t tilt = tilt_axis(machine.kinematics);
  const auto& a = machine.axes[tilt];
  const auto& c = machine.axes[5];
  if (tilt == 0 || !a || !c) {
    return std::nullopt;
  }
  if (a->cyclic) {
    return 180.0;
  }
  const double near = std::min(std::abs(a->min), std::abs(a->max));
  const double far = std::max(std::abs(a->min), std::abs(a->max));
  const bool whole_turn = c->cyclic || c->max - c->min >= 360.0;
  // One-sided travel (min and max of one sign) leans only one way: C must turn it round.
  const bool both_signs = a->min <= 0.0 && a->max >= 0.0;
  return std::min(180.0, whole_turn ? far : (both_signs ? near : 0.0));
}

} // namespace subfeed::post

#pragma once
// One machine as its config file describes it: kinematic type and geometry, axis limits,
// and the controller it is driven by. A MachineConfig from load_machine_config() is complete
// and every value is inside its documented range (configs/README.md), so consumers need no
// checks of their own. Lengths in mm, angles in degrees, feeds in mm/min (deg/min for
// rotary axes).

#include "base/error.hpp"

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace subfeed::post {

enum class KinematicsType {
  xyz,       // three linear axes
  xyzac_trt, // table tilts A about X and carries C about Z (LinuxCNC xyzac-trt-kins)
};

enum class Protocol { grbl, fanuc };
enum class Dialect { grbl, fanuc, linuxcnc };
enum class Parity { none, even, odd };
enum class FlowControl { none, xon_xoff, rts_cts, both };

// Axis letters in the order they appear in G-code words and in AxisSet indices.
inline constexpr std::string_view axis_letters = "XYZABC";

struct AxisLimits {
  double min = 0.0;      // mm or deg; ignored for a cyclic rotary axis
  double max = 0.0;      // mm or deg
  double max_feed = 0.0; // mm/min or deg/min
  bool cyclic = false;   // rotary axis without travel limits (turns any number of times)
};

// X, Y, Z are linear (mm); A, B, C rotate about them (deg).
[[nodiscard]] constexpr bool is_rotary_axis(std::size_t index) {
  return index >= 3;
}

using AxisSet = std::array<std::optional<AxisLimits>, axis_letters.size()>;

// LinuxCNC xyzac-trt parameters (PROTOCOLS.md). direction +1: ISO 841, a positive angle
// moves the tool relative to the work by the right-hand rule (the table turns the other
// way); -1: the opposite, LinuxCNC's default.
struct TableTableGeometry {
  std::array<double, 3> pivot{}; // rotation point (xr, yr, zr), mm, machine frame
  double y_offset = 0.0;         // Dy, mm
  double z_offset = 0.0;         // Dz, mm
  double tool_length = 0.0;      // mm, added to Dz
  int a_direction = 1;
  int c_direction = 1;
};

struct SerialSettings {
  int baud = 115200;
  int data_bits = 8;
  Parity parity = Parity::none;
  int stop_bits = 1;
  FlowControl flow_control = FlowControl::none;
};

struct ControllerSettings {
  Protocol protocol = Protocol::grbl;
  Dialect dialect = Dialect::grbl;
  std::optional<int> rx_buffer; // bytes; unset: GRBL reads it from $I
  int line_length = 79;         // characters after stripping
  int decimals = 3;             // digits after the point for mm words
  bool tcp = false;             // tool-centre-point control (G43.4/G43.5) available
  int program_number = 1;       // Fanuc O-number
  SerialSettings serial;
};

struct MachineConfig {
  std::string source; // file it came from
  std::string name;
  KinematicsType kinematics = KinematicsType::xyz;
  AxisSet axes;
  std::optional<TableTableGeometry> table_table; // set exactly for xyzac_trt
  ControllerSettings controller;
};

[[nodiscard]] std::string_view to_string(KinematicsType type);
[[nodiscard]] std::string_view to_string(Protocol protocol);
[[nodiscard]] std::string_view to_string(Dialect dialect);
[[nodiscard]] std::string_view to_string(Parity parity);
[[nodiscard]] std::string_view to_string(FlowControl flow);

// Errors name the file, the line and the dotted key: unknown keys, wrong types, missing
// required keys and values out of range.
[[nodiscard]] Expected<MachineConfig> load_machine_config(const std::filesystem::path& path);
[[nodiscard]] Expected<MachineConfig> parse_machine_config(std::string_view text,
                                                           const std::string& source);

} // namespace subfeed::post

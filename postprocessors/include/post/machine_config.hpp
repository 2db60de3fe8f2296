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
  xyz,        // three linear axes
  xyzac_trt,  // table tilts A about X and carries C about Z (LinuxCNC xyzac-trt-kins)
  xyzbc_trt,  // table tilts B about Y and carries C about Z (LinuxCNC xyzbc-trt-kins)
  xyzac_head, // spindle head turns C about Z and carries the A fork that tilts the tool
};

// The tilting rotary axis of a five-axis type: 3 (A) or 4 (B); 0 for xyz.
[[nodiscard]] constexpr std::size_t tilt_axis(KinematicsType type) {
  return type == KinematicsType::xyz ? 0 : type == KinematicsType::xyzbc_trt ? 4 : 3;
}

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

// Geometry of the five-axis types, named as LinuxCNC names it (docs/PROTOCOLS.md). A direction
// of +1 is ISO 841: a positive angle moves the tool relative to the work by the right-hand
// rule (a table therefore turns the other way); -1 is the opposite, LinuxCNC's default.
struct RotaryGeometry {
  std::array<double, 3> pivot{}; // table types: rotation point (xr, yr, zr), mm, machine frame
  double x_offset = 0.0;         // Dx between the B and C axes (xyzbc-trt), mm
  double y_offset = 0.0;         // Dy between the A and C axes (xyzac-trt), mm
  double z_offset = 0.0;         // Dz between the tilt axis and the table surface, mm
  double pivot_length = 0.0;     // head: from the tool-holder face to the tilt axis, mm
  double tool_length = 0.0;      // mm: added to Dz (tables) or to the pivot length (head)
  int tilt_direction = 1;        // of A (or B for xyzbc-trt)
  int c_direction = 1;
};

// How the post moves the machine where the CL data says nothing.
struct PostSettings {
  double singularity_cone = 0.05; // deg: within this of the C axis, C holds still
  double retract = 5.0;           // mm along the tool axis before an unwind or a branch change
  std::optional<double> safe_z;   // machine Z for rotary repositioning; unset: the Z max limit
  int preferred_tilt = 0;         // +1 / -1: tilt sign chosen when both are equally good
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
  std::optional<RotaryGeometry> rotary; // set exactly for the five-axis types
  ControllerSettings controller;
  PostSettings post;
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

// The most the machine leans the tool from its spindle's Z, degrees, in every direction
// round it: the tilt axis's larger travel when C turns a whole circle, else its smaller
// one (either sign with half a turn of C). Nothing for a three-axis machine.
[[nodiscard]] std::optional<double> tilt_range_deg(const MachineConfig& machine);

} // namespace subfeed::post

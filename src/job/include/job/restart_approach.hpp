#pragma once
// The blocks a resume sends before the program continues: the modes the program had built
// up (units, plane, distance, feed mode and feed, work offset, tool length or TCP, spindle,
// coolant) and a safe way back to the restart point. The approach moves in machine joints,
// with TCP cancelled (G49) when the program runs under G43.4, whose restore re-enables it:
// retract along the tool axis by the clearance (only when the machine's position is known;
// otherwise straight up in Z, which is along the tool on a machine whose table tilts),
// rise to the safe Z, turn the rotary axes, position X Y above the restart point, and
// plunge along the tool axis to it.

#include "base/error.hpp"
#include "job/restart_point.hpp"
#include "post/machine_config.hpp"

#include <optional>
#include <string>
#include <vector>

namespace subfeed::job {

// The machine joints for a line's end: its axis words, or under TCP the joints that put the
// tool tip there with the rotary axes at the angles written.
[[nodiscard]] Joints machine_joints(const post::MachineConfig& machine, const LineEnd& end);

// Whether the tool axis keeps its direction in the machine frame (the table tilts, or
// nothing does): a move straight up in Z is then a retract along the tool.
[[nodiscard]] bool tool_axis_fixed(const post::MachineConfig& machine);

struct Approach {
  std::optional<Joints> from; // where the machine stands, if known
  Joints to{};                // the restart point, machine joints
  double clearance = 2.0;     // mm along the tool axis
  double feed = 300.0;        // mm/min of the retract and the plunge
  bool tcp = false;           // the program runs under G43.4 there
};

[[nodiscard]] std::vector<std::string> approach_blocks(const post::MachineConfig& machine,
                                                       const Approach& a);

// The restore blocks for a restart after line `after` of `program`.
[[nodiscard]] Expected<std::vector<std::string>> restore_blocks(const std::string& program,
                                                                long after);

} // namespace subfeed::job

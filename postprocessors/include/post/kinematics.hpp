#pragma once
// Machine kinematics as a pair, in the manner of LinuxCNC's kinematicsForward/Inverse: from
// a tool pose in the workpiece frame to the joint positions that put the tool there, and
// back. One machine type per file; each states its sign conventions at its top.
//
// Frames and units (docs/ARCHITECTURE.md): right-handed, workpiece Z up; a pose is the tool tip
// (mm) and the unit tool axis pointing from the tip toward the spindle. Joints are X Y Z in
// mm and A B C in degrees; axes a machine lacks stay 0. Radians only inside.

#include "post/machine_config.hpp"

#include <array>
#include <memory>
#include <vector>

namespace subfeed::post {

struct ToolPose {
  std::array<double, 3> tip{};  // mm, workpiece frame
  std::array<double, 3> axis{}; // unit, tip toward spindle
};

using JointPosition = std::array<double, 6>; // X Y Z mm, A B C deg

class Kinematics {
public:
  virtual ~Kinematics() = default;
  // Every joint solution that reaches `pose`, ignoring travel limits (choosing among them is
  // the post's job). Where a rotary axis is free (the tool along a rotary axis: the
  // singularity), it keeps its value from `near`. Empty when the machine cannot point the
  // tool that way at all (a 3-axis machine and a tilted tool).
  [[nodiscard]] virtual std::vector<JointPosition> inverse(const ToolPose& pose,
                                                           const JointPosition& near) const = 0;
  [[nodiscard]] virtual ToolPose forward(const JointPosition& joints) const = 0;
};

[[nodiscard]] std::unique_ptr<Kinematics> make_kinematics(const MachineConfig& machine);

} // namespace subfeed::post

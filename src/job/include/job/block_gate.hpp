#pragma once
// The motion gate (geometry/motion_gate.hpp) held to the posted program: every block the
// post makes, its own approach, retract-and-turn and unwinding moves included, replayed as
// the control moves the joints and checked before it is written or streamed. A gate on the
// CL poses cannot see those moves, nor a rapid whose joints turn a rotary axis and swing the
// tool along a curve.
//
// Each block's joints are interpolated linearly from the last block's (a G0 too; a control
// that moves G0 axes one by one takes another path, not modelled) and forward kinematics
// gives the tool's pose: at the block's end for a feed block (the post splits those until
// the tip stays within its tolerance of the straight move), and at least every half degree
// a rotary axis turns and 8 times a block for a rapid. Under tool-centre-point control the
// tip is X Y Z, moving straight, and the axis from the angles or I J K. Poses are checked
// from the first block that sets X, Y and Z; a rotary axis no block has set yet counts as
// at 0, as `check` replays it (the post sets every axis before the first cut). Cuts may go the post's tolerance deeper than
// the CL gate allows: the gate given should allow for it (MotionGate::sibling).

#include "base/error.hpp"
#include "geometry/motion_gate.hpp"
#include "post/kinematics.hpp"
#include "post/machine_config.hpp"
#include "post/motion_block.hpp"

#include <array>
#include <memory>

namespace subfeed::job {

class BlockGate {
public:
  BlockGate(const post::MachineConfig& machine, geometry::MotionGate gate);

  // The block's move, as the machine makes it, through the gate; the error names the CL line
  // the block serves.
  [[nodiscard]] Expected<void> check(const post::MotionBlock& block);
  [[nodiscard]] const geometry::GateReport& report() const { return gate_.report(); }

private:
  [[nodiscard]] Expected<void> pass(const post::ToolPose& pose, const post::MotionBlock& block);

  std::unique_ptr<post::Kinematics> kinematics_;
  geometry::MotionGate gate_;
  post::JointPosition joints_{};
  std::array<bool, 3> known_{}; // X, Y, Z set by a block yet (rotary axes start at 0)
  post::ToolPose last_{};       // the pose the last block ended at
};

} // namespace subfeed::job

#pragma once
// Chooses, pose after pose, which joint solution the machine takes: the rotary solution
// choice of the post. Rules in order: travel limits (every axis), then continuity (the
// smallest rotary move from where the machine is, except that the tilt changes sign only
// where the path passes the pole within the cone: elsewhere C follows the tool round the
// pole, since no motion joins the two branches without leaving the path), then the
// config's preferred tilt sign.
// Within the singularity cone around the C axis, C holds still and the tilt follows the
// tool as closely as that allows (the axis error is at most the cone's half-angle).
//
// When the limits force a solution other than the nearest one (another branch or another
// turn of a limited rotary axis) the step says `reposition`: the machine cannot get there
// while cutting and the post must retract, turn and re-approach.

#include "base/error.hpp"
#include "cl/cl_pose.hpp"
#include "post/kinematics.hpp"

#include <optional>
#include <vector>

namespace subfeed::post {

struct TrackedStep {
  JointPosition joints{};
  bool reposition = false; // limits forced a far solution: retract, turn, re-approach
  bool in_cone = false;    // C held still near the pole
};

class RotaryTracker {
public:
  RotaryTracker(const Kinematics& kinematics, const MachineConfig& machine);

  // Every solution of `pose` inside all travel limits, one per branch and per turn of a
  // limited rotary axis: the starting states the look-ahead compares. Error (naming the CL
  // line) when there is none.
  [[nodiscard]] Expected<std::vector<JointPosition>> start_candidates(const cl::ClPose& pose) const;
  // Whether C is free (held) for a tool along this axis.
  [[nodiscard]] bool in_cone(const std::array<double, 3>& axis) const;
  // The one of `options` a fresh start takes: least rotation from zero, then the preferred tilt.
  [[nodiscard]] JointPosition prefer(const std::vector<JointPosition>& options) const;
  void start_at(const JointPosition& joints);
  [[nodiscard]] bool started() const { return started_; }
  [[nodiscard]] const JointPosition& current() const { return current_; }

  // The joints for the next pose, continuing from current(); current() becomes them.
  [[nodiscard]] Expected<TrackedStep> step(const cl::ClPose& pose);

  // The solution moving continuously from `start` along the great circle of tool axes (the
  // tip on a line) reaches at `to`, limits ignored: near the pole the nearest solution can
  // lie on the other branch, which no motion along the path reaches.
  [[nodiscard]] JointPosition follow(const JointPosition& start, const ToolPose& to) const;

  // The solution of `pose` nearest to `near` in rotary motion, limits ignored (for points
  // between two chosen solutions, which lie within the same limits).
  [[nodiscard]] JointPosition nearest(const ToolPose& pose, const JointPosition& near) const;

private:
  struct Candidates {
    std::vector<JointPosition> unconstrained; // one per branch, each axis turned nearest
    std::vector<JointPosition> feasible;      // all turns inside every limit
    bool in_cone = false;
  };
  [[nodiscard]] Candidates candidates(const ToolPose& pose, const JointPosition& near) const;
  // The solution continuous motion from current() reaches: `free` (the nearest) unless that
  // flips the tilt through a pole the path does not pass within the cone.
  [[nodiscard]] JointPosition continuous(const ToolPose& target, const JointPosition& free) const;
  [[nodiscard]] ToolPose cone_pose(const ToolPose& pose, const JointPosition& near) const;
  [[nodiscard]] bool within_limits(const JointPosition& j) const;
  [[nodiscard]] double rotary_distance(const JointPosition& a, const JointPosition& b) const;
  [[nodiscard]] std::unexpected<Error> unreachable(const cl::ClPose& pose,
                                                   const JointPosition& nearest) const;
  [[nodiscard]] const JointPosition* best(const std::vector<JointPosition>& options,
                                          const JointPosition& near) const;

  const Kinematics* kinematics_;
  const MachineConfig* machine_;
  std::size_t tilt_; // joint index of the tilting axis (3 or 4); 0 on a 3-axis machine
  double cone_cos_;  // cos of the singularity cone half-angle
  JointPosition current_{};
  bool started_ = false;
};

} // namespace subfeed::post

#pragma once
// Table-table A/C (LinuxCNC xyzac-trt-kins): the table tilts about X (A) and carries a
// rotary table about Z (C); the spindle stays vertical.
//
// Sign convention. With p = a_direction, q = c_direction (each +1 or -1), Q = P - pivot
// and D = (0, Dy, Dz + tool length):
//   machine point  J = Rx(-p A) (Rz(-q C) Q - D) + D + pivot
// which for p = q = s is docs/PROTOCOLS.md's joint formula written as rotations. +1 is the
// standard (ISO 841) table convention: positive A and C move the tool relative to the work
// by the right-hand rule, so the table itself turns the other way; -1 is LinuxCNC's default.
// The tool axis in the work frame is the fixed spindle direction carried back:
//   K = Rz(q C) Rx(p A) (0, 0, 1) = (p q sin A sin C, -p sin A cos C, cos A)
// so A = acos(Kz) and C = atan2(p q Kx, -p Ky); the second solution is (-A, C + 180 deg).
// At Kz = +-1 C is free: it keeps its current value.

#include "post/kinematics.hpp"

namespace subfeed::post {

class XyzacTrtKinematics final : public Kinematics {
public:
  explicit XyzacTrtKinematics(const RotaryGeometry& geometry);

  [[nodiscard]] std::vector<JointPosition> inverse(const ToolPose& pose,
                                                   const JointPosition& near) const override;
  [[nodiscard]] ToolPose forward(const JointPosition& joints) const override;

private:
  [[nodiscard]] JointPosition joints_for(const ToolPose& pose, double a_deg, double c_deg) const;

  RotaryGeometry g_;
  double p_;  // A direction
  double q_;  // C direction
  double dz_; // Dz plus tool length
};

} // namespace subfeed::post

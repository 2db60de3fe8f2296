#pragma once
// Table-table B/C (LinuxCNC xyzbc-trt-kins): the table tilts about Y (B) and carries a
// rotary table about Z (C); the spindle stays vertical.
//
// Sign convention. With p = b_direction, q = c_direction (each +1 or -1), Q = P - pivot
// and D = (Dx, 0, Dz + tool length):
//   machine point  J = Ry(-p B) (Rz(-q C) Q - D) + D + pivot
// +1 is ISO 841: positive B and C move the tool relative to the work by the right-hand
// rule, the table turns the other way; -1 is LinuxCNC's default. The tool axis in the work
// frame is
//   K = Rz(q C) Ry(p B) (0, 0, 1) = (p sin B cos C, p q sin B sin C, cos B)
// so B = acos(Kz) and C = atan2(p q Ky, p Kx); the second solution is (-B, C + 180 deg).
// At Kz = +-1 C is free: it keeps its current value.

#include "post/kinematics.hpp"

namespace subfeed::post {

class XyzbcTrtKinematics final : public Kinematics {
public:
  explicit XyzbcTrtKinematics(const RotaryGeometry& geometry);

  [[nodiscard]] std::vector<JointPosition> inverse(const ToolPose& pose,
                                                   const JointPosition& near) const override;
  [[nodiscard]] ToolPose forward(const JointPosition& joints) const override;

private:
  [[nodiscard]] JointPosition joints_for(const ToolPose& pose, double b_deg, double c_deg) const;

  RotaryGeometry g_;
  double p_;  // B direction
  double q_;  // C direction
  double dz_; // Dz plus tool length
};

} // namespace subfeed::post

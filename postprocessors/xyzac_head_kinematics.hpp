#pragma once
// Head-head A/C: the spindle head turns about Z (C) and carries a fork that tilts the
// spindle about X (A); the table does not move. The machine's X Y Z position the pivot (the
// point where the A axis crosses the spindle line); the tool tip lies the pivot length plus
// the tool length from it, down the spindle. The work frame is the machine frame.
//
// Sign convention. With p = a_direction, q = c_direction: +1 is ISO 841, the head turns the
// tool by the right-hand rule about +X and +Z; -1 the opposite. The tool axis is
//   K = Rz(q C) Rx(p A) (0, 0, 1) = (p q sin A sin C, -p sin A cos C, cos A)
// (the same as xyzac-trt's, since ISO signs describe the tool's motion relative to the work
// either way), so A = acos(Kz) and C = atan2(p q Kx, -p Ky); the second solution is
// (-A, C + 180 deg). The joints are J = tip + L K with L = pivot length + tool length.

#include "post/kinematics.hpp"

namespace subfeed::post {

class XyzacHeadKinematics final : public Kinematics {
public:
  explicit XyzacHeadKinematics(const RotaryGeometry& geometry);

  [[nodiscard]] std::vector<JointPosition> inverse(const ToolPose& pose,
                                                   const JointPosition& near) const override;
  [[nodiscard]] ToolPose forward(const JointPosition& joints) const override;

private:
  [[nodiscard]] JointPosition joints_for(const ToolPose& pose, double a_deg, double c_deg) const;

  double p_;
  double q_;
  double length_; // pivot to tool tip, mm
};

} // namespace subfeed::post

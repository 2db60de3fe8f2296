#include "xyzac_trt_kinematics.hpp"

#include "angles.hpp"

#include <algorithm>
#include <cmath>

namespace subfeed::post {

XyzacTrtKinematics::XyzacTrtKinematics(const RotaryGeometry& geometry)
    : g_(geometry), p_(geometry.tilt_direction), q_(geometry.c_direction),
      dz_(geometry.z_offset + geometry.tool_length) {}

JointPosition XyzacTrtKinematics::joints_for(const ToolPose& pose, double a_deg,
                                             double c_deg) const {
  const double ca = std::cos(a_deg * radians_per_degree), sa = std::sin(a_deg * radians_per_degree);
  const double cc = std::cos(c_deg * radians_per_degree), sc = std::sin(c_deg * radians_per_degree);
  const double qx = pose.tip[0] - g_.pivot[0];
  const double qy = pose.tip[1] - g_.pivot[1];
  const double qz = pose.tip[2] - g_.pivot[2];
  // V = Rz(-q C) Q - D, then J = Rx(-p A) V + D + pivot.
  const double vx = cc * qx + q_ * sc * qy;
  const double vy = -q_ * sc * qx + cc * qy - g_.y_offset;
  const double vz = qz - dz_;
  JointPosition j{};
  j[0] = vx + g_.pivot[0];
  j[1] = ca * vy + p_ * sa * vz + g_.y_offset + g_.pivot[1];
  j[2] = -p_ * sa * vy + ca * vz + dz_ + g_.pivot[2];
  j[3] = a_deg;
  j[5] = c_deg;
  return j;
}

std::vector<JointPosition> XyzacTrtKinematics::inverse(const ToolPose& pose,
                                                       const JointPosition& near) const {
  const auto& k = pose.axis;
  const double a = std::acos(std::clamp(k[2], -1.0, 1.0)) / radians_per_degree;
  if (std::hypot(k[0], k[1]) < rotary_pole_sine) {
    return {joints_for(pose, a, near[5])}; // along the C axis: C keeps its value
  }
  const double c = std::atan2(p_ * q_ * k[0], -p_ * k[1]) / radians_per_degree;
  return {joints_for(pose, a, c), joints_for(pose, -a, wrap_degrees(c + 180.0))};
}

ToolPose XyzacTrtKinematics::forward(const JointPosition& j) const {
  const double a = j[3] * radians_per_degree, c = j[5] * radians_per_degree;
  const double ca = std::cos(a), sa = std::sin(a), cc = std::cos(c), sc = std::sin(c);
  // W = Rx(p A) (J - D - pivot) + D, then P = Rz(q C) W + pivot.
  const double ux = j[0] - g_.pivot[0];
  const double uy = j[1] - g_.y_offset - g_.pivot[1];
  const double uz = j[2] - dz_ - g_.pivot[2];
  const double wx = ux;
  const double wy = ca * uy - p_ * sa * uz + g_.y_offset;
  const double wz = p_ * sa * uy + ca * uz + dz_;
  ToolPose pose;
  pose.tip = {cc * wx - q_ * sc * wy + g_.pivot[0], q_ * sc * wx + cc * wy + g_.pivot[1],
              wz + g_.pivot[2]};
  pose.axis = {p_ * q_ * sa * sc, -p_ * sa * cc, ca};
  return pose;
}

} // namespace subfeed::post

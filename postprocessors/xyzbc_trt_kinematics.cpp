#include "xyzbc_trt_kinematics.hpp"

#include "angles.hpp"

#include <algorithm>
#include <cmath>

namespace subfeed::post {

XyzbcTrtKinematics::XyzbcTrtKinematics(const RotaryGeometry& geometry)
    : g_(geometry), p_(geometry.tilt_direction), q_(geometry.c_direction),
      dz_(geometry.z_offset + geometry.tool_length) {}

JointPosition XyzbcTrtKinematics::joints_for(const ToolPose& pose, double b_deg,
                                             double c_deg) const {
  const double cb = std::cos(b_deg * radians_per_degree), sb = std::sin(b_deg * radians_per_degree);
  const double cc = std::cos(c_deg * radians_per_degree), sc = std::sin(c_deg * radians_per_degree);
  const double qx = pose.tip[0] - g_.pivot[0];
  const double qy = pose.tip[1] - g_.pivot[1];
  const double qz = pose.tip[2] - g_.pivot[2];
  // V = Rz(-q C) Q - D, then J = Ry(-p B) V + D + pivot.
  const double vx = cc * qx + q_ * sc * qy - g_.x_offset;
  const double vy = -q_ * sc * qx + cc * qy;
  const double vz = qz - dz_;
  JointPosition j{};
  j[0] = cb * vx - p_ * sb * vz + g_.x_offset + g_.pivot[0];
  j[1] = vy + g_.pivot[1];
  j[2] = p_ * sb * vx + cb * vz + dz_ + g_.pivot[2];
  j[4] = b_deg;
  j[5] = c_deg;
  return j;
}

std::vector<JointPosition> XyzbcTrtKinematics::inverse(const ToolPose& pose,
                                                       const JointPosition& near) const {
  const auto& k = pose.axis;
  const double b = std::acos(std::clamp(k[2], -1.0, 1.0)) / radians_per_degree;
  if (std::hypot(k[0], k[1]) < rotary_pole_sine) {
    return {joints_for(pose, b, near[5])};
  }
  const double c = std::atan2(p_ * q_ * k[1], p_ * k[0]) / radians_per_degree;
  return {joints_for(pose, b, c), joints_for(pose, -b, wrap_degrees(c + 180.0))};
}

ToolPose XyzbcTrtKinematics::forward(const JointPosition& j) const {
  const double b = j[4] * radians_per_degree, c = j[5] * radians_per_degree;
  const double cb = std::cos(b), sb = std::sin(b), cc = std::cos(c), sc = std::sin(c);
  // W = Ry(p B) (J - D - pivot) + D, then P = Rz(q C) W + pivot.
  const double ux = j[0] - g_.x_offset - g_.pivot[0];
  const double uy = j[1] - g_.pivot[1];
  const double uz = j[2] - dz_ - g_.pivot[2];
  const double wx = cb * ux + p_ * sb * uz + g_.x_offset;
  const double wy = uy;
  const double wz = -p_ * sb * ux + cb * uz + dz_;
  ToolPose pose;
  pose.tip = {cc * wx - q_ * sc * wy + g_.pivot[0], q_ * sc * wx + cc * wy + g_.pivot[1],
              wz + g_.pivot[2]};
  pose.axis = {p_ * sb * cc, p_ * q_ * sb * sc, cb};
  return pose;
}

} // namespace subfeed::post

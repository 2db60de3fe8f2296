#include "xyzac_head_kinematics.hpp"

#include "angles.hpp"

#include <algorithm>
#include <cmath>

namespace subfeed::post {

namespace {

std::array<double, 3> axis_of(double p, double q, double a_deg, double c_deg) {
  const double sa = std::sin(a_deg * radians_per_degree);
  return {p * q * sa * std::sin(c_deg * radians_per_degree),
          -p * sa * std::cos(c_deg * radians_per_degree), std::cos(a_deg * radians_per_degree)};
}

} // namespace

XyzacHeadKinematics::XyzacHeadKinematics(const RotaryGeometry& geometry)
    : p_(geometry.tilt_direction), q_(geometry.c_direction),
      length_(geometry.pivot_length + geometry.tool_length) {}

JointPosition XyzacHeadKinematics::joints_for(const ToolPose& pose, double a_deg,
                                              double c_deg) const {
  // The pivot from the axis the joints produce (not the requested one), so forward() of
  // the result gives back the tip exactly even where the axis was rounded.
  const auto k = axis_of(p_, q_, a_deg, c_deg);
  JointPosition j{};
  for (std::size_t i = 0; i < 3; ++i) {
    j[i] = pose.tip[i] + length_ * k[i];
  }
  j[3] = a_deg;
  j[5] = c_deg;
  return j;
}

std::vector<JointPosition> XyzacHeadKinematics::inverse(const ToolPose& pose,
                                                        const JointPosition& near) const {
  const auto& k = pose.axis;
  const double a = std::acos(std::clamp(k[2], -1.0, 1.0)) / radians_per_degree;
  if (std::hypot(k[0], k[1]) < rotary_pole_sine) {
    return {joints_for(pose, a, near[5])};
  }
  const double c = std::atan2(p_ * q_ * k[0], -p_ * k[1]) / radians_per_degree;
  return {joints_for(pose, a, c), joints_for(pose, -a, wrap_degrees(c + 180.0))};
}

ToolPose XyzacHeadKinematics::forward(const JointPosition& j) const {
  ToolPose pose;
  pose.axis = axis_of(p_, q_, j[3], j[5]);
  for (std::size_t i = 0; i < 3; ++i) {
    pose.tip[i] = j[i] - length_ * pose.axis[i];
  }
  return pose;
}

} // namespace subfeed::post

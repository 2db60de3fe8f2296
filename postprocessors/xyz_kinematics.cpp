#include "xyz_kinematics.hpp"

#include <cmath>

namespace subfeed::post {

namespace {

// A 3-axis machine takes a tool axis within this of +Z (1e-9 rad) as vertical.
constexpr double vertical_tolerance = 1e-9;

} // namespace

std::vector<JointPosition> XyzKinematics::inverse(const ToolPose& pose,
                                                  const JointPosition& /*near*/) const {
  const auto& k = pose.axis;
  if (std::hypot(k[0], k[1]) > vertical_tolerance || k[2] <= 0.0) {
    return {};
  }
  return {JointPosition{pose.tip[0], pose.tip[1], pose.tip[2], 0.0, 0.0, 0.0}};
}

ToolPose XyzKinematics::forward(const JointPosition& j) const {
  return {{j[0], j[1], j[2]}, {0.0, 0.0, 1.0}};
}

} // namespace subfeed::post

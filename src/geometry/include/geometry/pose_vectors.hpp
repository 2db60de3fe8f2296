#pragma once
// A CL pose's tip and tool axis as vectors, for the geometry that moves the tool.

#include "cl/cl_pose.hpp"

#include <Eigen/Core>

namespace subfeed::geometry {

// mm, workpiece frame.
[[nodiscard]] inline Eigen::Vector3d tip_of(const cl::ClPose& p) {
  return {p.tip[0], p.tip[1], p.tip[2]};
}

// Unit; +Z for a pose that carries no axis (a three-axis path's records).
[[nodiscard]] inline Eigen::Vector3d axis_of(const cl::ClPose& p) {
  const Eigen::Vector3d a{p.axis[0], p.axis[1], p.axis[2]};
  return a.norm() > 0.0 ? a.normalized() : Eigen::Vector3d::UnitZ();
}

} // namespace subfeed::geometry

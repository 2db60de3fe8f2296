#pragma once
// Small vector helpers the post and the replay both need: directions in the work frame and
// joint interpolation as a control does it. Internal to the postprocessors.

#include "angles.hpp"
#include "post/kinematics.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace subfeed::post {

using Vec3 = std::array<double, 3>;

[[nodiscard]] inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

[[nodiscard]] inline double distance(const Vec3& a, const Vec3& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

[[nodiscard]] inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Angle between two directions, radians; accurate for tiny angles too (acos is not).
[[nodiscard]] inline double angle_rad(const Vec3& a, const Vec3& b) {
  const Vec3 c = cross(a, b);
  return std::atan2(std::sqrt(dot(c, c)), dot(a, b));
}

[[nodiscard]] inline double angle_deg(const Vec3& a, const Vec3& b) {
  return angle_rad(a, b) / radians_per_degree;
}

// Great-circle interpolation of unit vectors.
[[nodiscard]] inline Vec3 slerp(const Vec3& a, const Vec3& b, double t) {
  const double omega = angle_rad(a, b);
  if (omega < 1e-12) {
    return a;
  }
  const double wa = std::sin((1.0 - t) * omega) / std::sin(omega);
  const double wb = std::sin(t * omega) / std::sin(omega);
  return {wa * a[0] + wb * b[0], wa * a[1] + wb * b[1], wa * a[2] + wb * b[2]};
}

// Every joint moved linearly, as a control interpolates a block.
[[nodiscard]] inline JointPosition lerp(const JointPosition& a, const JointPosition& b, double t) {
  JointPosition out{};
  for (std::size_t i = 0; i < a.size(); ++i) {
    out[i] = a[i] + t * (b[i] - a[i]);
  }
  return out;
}

} // namespace subfeed::post

#pragma once
// Angle helpers shared by the kinematics and the rotary solution choice. Degrees outside,
// radians only inside the trigonometry.

#include <cmath>
#include <numbers>

namespace subfeed::post {

inline constexpr double radians_per_degree = std::numbers::pi / 180.0;

// The tool axis leans from the rotary axis by less than this (its sine): it lies along it, and
// the rotary angle is free. Round-off only: any real lean fixes the angle.
inline constexpr double rotary_pole_sine = 1e-12;

// A joint that moves less than this (mm or degrees) has not moved.
inline constexpr double no_motion = 1e-9;

// Into (-180, 180].
[[nodiscard]] inline double wrap_degrees(double angle) {
  double a = std::fmod(angle, 360.0);
  if (a <= -180.0) {
    a += 360.0;
  } else if (a > 180.0) {
    a -= 360.0;
  }
  return a;
}

} // namespace subfeed::post

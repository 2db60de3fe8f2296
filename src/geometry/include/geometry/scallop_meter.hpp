#pragma once
// The independent scallop meter (docs/METHOD.md §5). It shares nothing with the step-over code:
// it measures what a tool path leaves, from the swept volume alone. The ball swept along a
// segment of ball centres is a capsule of the ball's radius. For a design-surface point p
// with unit normal n (toward the tool), the material left there is the least t >= 0 at which
// p + t n enters a capsule, over all capsules: that is the scallop height at p. A capsule
// that already contains p cuts below the surface: a gouge, as deep as p lies inside it.

#include <Eigen/Core>
#include <limits>
#include <span>

namespace subfeed::geometry {

struct Capsule {
  Eigen::Vector3d a; // ball centre at the start of the move, mm
  Eigen::Vector3d b; // ball centre at its end, mm
  double radius = 0.0;
};

struct ScallopSample {
  double height =
      std::numeric_limits<double>::infinity(); // mm; infinite: not cut within max_height
  double gouge_depth = 0.0;                    // mm; > 0 when the tool cut below the surface here
};

// Material left at p along n, looked for up to max_height above the surface.
[[nodiscard]] ScallopSample measure_scallop(const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                                            std::span<const Capsule> capsules, double max_height);

} // namespace subfeed::geometry

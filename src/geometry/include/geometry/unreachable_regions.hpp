#pragma once
// Where the ball cannot reach: the surface vertices a concave radius below the ball's
// forbids (pass_intervals.hpp), grouped into regions that share triangle edges, so that a
// user is told where material will be left (and can choose a smaller ball there), not only
// how much.

#include "geometry/surface_mesh.hpp"

#include <Eigen/Core>
#include <vector>

namespace subfeed::geometry {

struct UnreachableRegion {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(); // mm, the mean of its vertices
  Eigen::Vector3d low = Eigen::Vector3d::Zero();      // bounding box, mm
  Eigen::Vector3d high = Eigen::Vector3d::Zero();
  long vertices = 0;
  double material_mm = 0.0; // the most material the ball leaves there, at its deepest vertex
};

// `reachable[i]` is 0 where vertex i cannot be reached; `material[i]`, when given, how much
// the ball leaves on it. Largest region first.
[[nodiscard]] std::vector<UnreachableRegion>
unreachable_regions(const SurfaceMesh& mesh, const std::vector<char>& reachable,
                    const std::vector<double>& material = {});

} // namespace subfeed::geometry

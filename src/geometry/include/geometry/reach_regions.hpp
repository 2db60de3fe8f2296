#pragma once
// What the tool leaves uncut because it cannot reach it (tool_reach.hpp), as a user needs
// it: each connected region's place, size and area, and why. A triangle is left when any of
// its vertices is out of reach (the planner slices only the others); regions join left
// triangles that share a vertex.

#include "geometry/surface_mesh.hpp"
#include "geometry/tool_reach.hpp"

#include <Eigen/Core>
#include <vector>

namespace subfeed::geometry {

struct ReachRegion {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(); // mm, area-weighted
  Eigen::Vector3d low = Eigen::Vector3d::Zero();      // bounding box, mm
  Eigen::Vector3d high = Eigen::Vector3d::Zero();
  double area_mm2 = 0.0;
  double steepest_deg = 0.0; // the largest angle of a normal there from +Z
  long tilted = 0;           // vertices beyond the tilt limit
  long hidden = 0;           // vertices the withdrawing ball cannot leave
  long collides = 0;         // vertices no tool axis keeps the whole tool clear at
  long below_floor = 0;      // vertices the ball would reach only under the floor
};

// Largest area first.
[[nodiscard]] std::vector<ReachRegion> reach_regions(const SurfaceMesh& mesh,
                                                     const std::vector<ReachLimit>& reach);

} // namespace subfeed::geometry

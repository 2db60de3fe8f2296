#pragma once
// What spacing each CL vertex needs for the scallop target (docs/METHOD.md §2): the radius of
// normal curvature across the passes (the slicing normal projected into the tangent
// plane), the spacing between ball centres that leaves scallop h, and the distance between
// slicing planes that gives it at the local slope.

#include "geometry/surface_mesh.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace subfeed::geometry {

struct PassIntervals {
  std::vector<double> cl_spacing;     // mm between neighbouring ball centres across passes
  std::vector<double> plane_interval; // mm between slicing planes
  std::vector<char> reachable;        // 0 where a concave radius below the ball's forbids it
  // 0 where the tool cannot get to the vertex at all (tool_reach.hpp): never cut, so its
  // need sets nothing. Empty: every vertex.
  std::vector<char> in_reach;
  double min_interval = 0.0; // over the vertices cut
  double max_interval = 0.0;

  // Whether passes are planned over vertex v: the ball fits and the tool gets there.
  [[nodiscard]] bool cuts(std::size_t v) const {
    return reachable[v] != 0 && (in_reach.empty() || in_reach[v] != 0);
  }
};

// `slicing_normal` is the unit normal s of the planes. Where the surface faces along s (a
// wall the planes meet edge-on) the interval is kept at least `min_fraction` of the CL
// spacing so the pass count stays finite.
// `in_reach`, when not empty, is kept in the result (PassIntervals::in_reach).
[[nodiscard]] PassIntervals pass_intervals(const SurfaceMesh& mesh, double ball_radius,
                                           double scallop, const Eigen::Vector3d& slicing_normal,
                                           const std::vector<char>& in_reach = {},
                                           double min_fraction = 0.05);

// The CL spacing each vertex needs across passes whose spacing runs along `across` (a
// direction per vertex, projected into the tangent plane there): passes that bend run
// across the surface in other directions than the planes, and the curvature across them
// is what sets the step. Where `across` is zero or normal to the surface, `fallback`.
[[nodiscard]] std::vector<double> cl_spacing_across(const SurfaceMesh& mesh, double ball_radius,
                                                    double scallop,
                                                    const std::vector<Eigen::Vector3d>& across,
                                                    const std::vector<double>& fallback);

// mm of cutting a pattern that met every vertex's need exactly would take: the CL surface's
// cut area over the spacing its vertices need (a lower bound no pattern of passes beats by
// much, whatever their shape), to tell a pattern that fights the part from one that fits.
[[nodiscard]] double ideal_cutting_length(const std::vector<Eigen::Vector3d>& cl_points,
                                          const std::vector<std::array<int, 3>>& triangles,
                                          const PassIntervals& intervals);

} // namespace subfeed::geometry

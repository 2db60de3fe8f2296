#pragma once
// Concentric passes: the level lines of the arrival time of a front that leaves the
// highest point of each piece of the surface and crosses the CL surface at the spacing
// each vertex needs across it (front_arrival.hpp). Level lines one reference apart then
// lie exactly that spacing apart in whatever direction they run, so on a dome or a boss,
// where parallel passes must bend and crowd to follow the need, rings follow it as
// they are. The need depends on the direction across the passes (the curvature there),
// and that direction on the front: each round marches again with the need across the
// last round's level lines (the first round: across rings of equal spacing).
//
// A single source has no shock where the front meets itself, except behind what it must
// go round (a hollow the ball cannot reach); there, and wherever the rings still lie too
// far apart, spacing_ratios measures them and passes are inserted as for the planes
// (pass_insertion.hpp), and the result is priced the same way, so the planner can set
// rings against parallel passes.

#include "geometry/deformation.hpp"
#include "geometry/pass_intervals.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace subfeed::geometry {

struct ConcentricSettings {
  double reference = 0.0; // the level spacing, mm of deformed coordinate
  int rounds = 3;         // marches with the need across the last one's level lines
  double insertion_margin = 0.0;
  double spacing_allowance = 0.01;
};

// The highest reachable vertex (by `path_points` z) of each connected piece of the mesh.
[[nodiscard]] std::vector<int> highest_points(const std::vector<Eigen::Vector3d>& path_points,
                                              const std::vector<std::array<int, 3>>& triangles,
                                              const std::vector<char>& reachable);

// Levels half a reference above the least arrival time (the source sits in the middle of
// the first ring), then one reference apart up to the greatest.
[[nodiscard]] PlaneSpacing ring_levels(const std::vector<double>& arrival, double reference);

// The rings' deformation: `deformed` is the arrival time in mm of deformed coordinate,
// `insertion` where passes between the rings are needed, priced by `path_points` as for
// deform_cl_mesh. `need_across` as there.
[[nodiscard]] Deformation concentric_deformation(const std::vector<Eigen::Vector3d>& cl_points,
                                                 const std::vector<Eigen::Vector3d>& path_points,
                                                 const std::vector<std::array<int, 3>>& triangles,
                                                 const PassIntervals& intervals,
                                                 const NeedAcross& need_across,
                                                 const ConcentricSettings& settings);

} // namespace subfeed::geometry

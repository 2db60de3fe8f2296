#pragma once
// The feed direction with the shortest path. The passes of one direction cannot follow
// the ideal iso-scallop spacing everywhere, and how far they fall short depends on the
// part: a seat whose width needs more passes than its length is cut shorter along its
// length. Each candidate is priced by a short deformation (the first few solves, which on
// the sample parts already hold the solve that is kept) and its predicted cutting length
// (the co-area formula of pass_insertion.hpp): 0, 45, 90 and 135 degrees, then the two
// halfway to the neighbours of the cheapest. X or Y (the cheaper) is kept unless another
// direction is predicted shorter by more than `axis_preference`: the prediction is good to
// about 2 %, and a raster along a machine axis is what a machinist expects otherwise.
// Where that leaves a direction off the axes, the few solves may not have settled (a part
// whose passes must bend far takes dozens), so the direction and the axis are both solved
// in full and priced again, with the same preference; the winner's deformation is kept
// for the plan. Directions are in the XY plane, from +X.

#include "base/error.hpp"
#include "geometry/coarse_deformation.hpp"
#include "geometry/deformation.hpp"
#include "geometry/surface_mesh.hpp"

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace subfeed::geometry {

struct DirectionPrice {
  double direction_deg = 0.0;
  double predicted_length = 0.0; // mm of cutting
  bool full = false;             // priced by the full deformation, not the first solves
};

struct DirectionChoice {
  double direction_deg = 0.0;         // the cheapest
  std::vector<DirectionPrice> prices; // in the order tried
  bool solved_in_full = false;        // then `deformation` is the chosen direction's
  Deformation deformation;
};

struct DirectionPricing {
  double ball_radius = 3.0; // mm
  double scallop = 0.01;    // mm
  int solves = 4;           // deformation solves per candidate
  int full_solves = 60;     // the most solves of a full deformation
  double spacing_allowance = 0.01;
  std::optional<double> insertion_margin; // mm; default the widest CL spacing
  double axis_preference = 0.02;          // fraction of the length
  std::vector<char> in_reach;             // PassIntervals::in_reach
  // When given, each candidate is solved on the coarse mesh and priced on the fine one,
  // after `fine_rounds` solves measured there at most.
  const CoarseSolver* coarse = nullptr;
  int fine_rounds = 8;
};

// The slicing normal of a feed direction: horizontal, across the feed.
[[nodiscard]] Eigen::Vector3d slicing_normal_for(double direction_deg);

// `path_points`: where the tool's path runs (deformation.hpp).
[[nodiscard]] Expected<DirectionChoice>
choose_feed_direction(const SurfaceMesh& mesh, const std::vector<Eigen::Vector3d>& cl_points,
                      const std::vector<Eigen::Vector3d>& path_points,
                      const DirectionPricing& pricing, const SolveProgress& on_solve = {});

} // namespace subfeed::geometry

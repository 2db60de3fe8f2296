#pragma once
// Tool axes turned clear of collisions (assembly_clearance.hpp), per mesh vertex, before
// any pass is sliced. Beyond the paper, which leaves interference open.
//
// At each vertex in reach the ball's centre is fixed by the surface (contact + r normal,
// lifted clear where a hollow is narrower than the ball, as the pass will be); only the axis
// can change. Where the planner's axis (the averaged normal) keeps every rule
// with `extra_mm` to spare, it stays. Elsewhere the nearest clear axis is searched: axes
// turned from it by growing angles (`step_deg`), in `azimuths` directions round it, kept
// within `max_tilt_deg` of +Z and at most 80 degrees from the normal (the contact well
// below the ball's equator, where the flutes begin); at the first
// angle that has clear axes, the one with the most slack wins (first on a coarse grid of
// turns, then finer below and round the first found). Neighbouring vertices share a search
// (`search_cell_mm`). A vertex with none is
// ReachLimit::collision; one whose ball alone goes under the stock, ReachLimit::floor:
// neither is cut, both are reported as out of reach.
//
// Smoothness: a turn is spread over the mesh round the vertices that need it, fading by
// `ramp_deg_per_mm` with the distance along the mesh's edges (the largest turn that reaches
// a vertex wins), so neighbouring passes turn together and the rotary axes do not jump where
// the search starts; then each turned axis is averaged with its neighbours' a few rounds
// (the search's whole steps and few directions leave seams). Every vertex whose axis was
// turned is checked again: an average that no longer clears falls back to the turn before
// it, and a vertex no turn clears is marked collision.

#include "geometry/assembly_clearance.hpp"
#include "geometry/stage_share.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/tool_reach.hpp"

#include <Eigen/Core>
#include <vector>

namespace subfeed::geometry {

struct ClearAxesOptions {
  double max_tilt_deg = 90.0;
  bool fixed_axis = false;     // three axes: nothing to turn; a collision is only reported
  double extra_mm = 0.2;       // asked beyond clearance_min, so blends between vertices hold
  double step_deg = 3.0;       // of the search's turn
  double most_turn_deg = 75.0; // from the planner's axis
  int azimuths = 16;
  double ramp_deg_per_mm = 2.0;
  // mm: vertices whose ball centres share a cell of this size share one search (its turn
  // checked at each of them); a cell with no clear axis is left uncut whole.
  double search_cell_mm = 0.4;
  // Rounds of averaging each turned axis with its neighbours', after the ramp.
  int smoothing_rounds = 24;
};

struct ClearAxesReport {
  long turned = 0;   // vertices whose axis the search turned
  long spread = 0;   // further vertices turned by the ramp round them
  long collided = 0; // vertices with no clear axis
  long under_floor = 0;
  double largest_turn_deg = 0.0;
};

// `centres`: the ball centre at each vertex (lifted clear); `axes` the planner's axes (unit),
// turned in place; `reach` updated where a vertex in reach has no clear axis.
ClearAxesReport clear_axes(const SurfaceMesh& mesh, const std::vector<Eigen::Vector3d>& centres,
                           std::vector<Eigen::Vector3d>& axes, std::vector<ReachLimit>& reach,
                           const AssemblyClearance& clearance, const ClearAxesOptions& options,
                           StageShare* share = nullptr);

} // namespace subfeed::geometry

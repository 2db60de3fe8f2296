#pragma once
// Which points of the surface the tool can reach from above, before any pass is sliced.
// Two limits, each a property of the machine and the part, not of the ball's size:
//  - tilt: with the tool along the surface normal, a point whose normal leans more than
//    `max_tilt_deg` from +Z would need the tool tilted past what the machine turns (a
//    closed model's underside leans 180 degrees: the tool would point up from below). A
//    vertical tool (fixed axis) touches with any point of its lower half, so for it the
//    limit is 90 degrees: the ball's equator on a vertical wall.
//  - hidden: the ball must leave the part as a link leaves it, without touching it: drawn
//    back along the tool axis by the clearance, then straight up until it is above the
//    part's top (an overhang above, the far wall of a slot the axis points into, a neck
//    under a bulb). Tested from the ball already lifted clear: hollows narrower than the
//    ball are ridden over, not left out.
// A point out of reach is never cut: the planner slices only triangles whose every vertex
// is in reach, and reports what it leaves (reach_regions.hpp).

#include "geometry/stage_share.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/triangle_tree.hpp"

#include <Eigen/Core>
#include <vector>

namespace subfeed::geometry {

// collision: no tool axis within the limits keeps the holder, shank and flutes clear of the
// part and the floor (clear_axes.hpp); floor: the ball itself would go under the stock.
enum class ReachLimit : char { reached = 0, tilt = 1, hidden = 2, collision = 3, floor = 4 };

struct ReachOptions {
  double ball_radius = 3.0;   // mm
  double max_tilt_deg = 90.0; // the tool axis's largest angle from +Z
  bool fixed_axis = false;    // the tool stays vertical
  // mm the retracting ball may come nearer the mesh than its radius (the gate's tolerance
  // for a cut), and the rising one must keep beyond it (a rapid may not touch at all).
  double margin = 1e-3;
  double clearance_mm = 2.0; // the retract along the axis before the rise
};

// The normal's angle from +Z beyond which a point is out of reach, degrees.
[[nodiscard]] double reach_angle_deg(const ReachOptions& options);

// Per vertex of `mesh`: reached, or the first limit it fails. `clear_balls` are the ball
// centres set on each vertex along its normal and lifted clear of `design` (the same
// mesh's triangle tree); `axes` the tool axis the planner gives each vertex (unit), which
// the ball withdraws along; `top_z` the mesh's highest point, mm.
[[nodiscard]] std::vector<ReachLimit>
surface_reach(const SurfaceMesh& mesh, const std::vector<Eigen::Vector3d>& clear_balls,
              const std::vector<Eigen::Vector3d>& axes, const TriangleTree& design, double top_z,
              const ReachOptions& options, StageShare* share = nullptr);

// Whether the ball centred at `centre` withdraws as above along `axis` (unit) to over
// `top_z` (the part's highest point, mm) without coming within the margin of `design`.
[[nodiscard]] bool withdraws(const TriangleTree& design, const Eigen::Vector3d& centre,
                             const Eigen::Vector3d& axis, double top_z,
                             const ReachOptions& options);

// 1 where a vertex is reached, for masks.
[[nodiscard]] std::vector<char> reached_mask(const std::vector<ReachLimit>& reach);

// `axis` turned toward +Z, in its vertical plane, until it leans at most `max_tilt_deg`
// (unit in, unit out). A straight-down axis turns about X.
[[nodiscard]] Eigen::Vector3d within_tilt(const Eigen::Vector3d& axis, double max_tilt_deg);

} // namespace subfeed::geometry

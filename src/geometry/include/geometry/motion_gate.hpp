#pragma once
// The last check between a tool path and a machine: every move, not only every pose, is
// measured against the part before it may go on. `plan` and `run` pass every pose the
// planner makes through it, `post --cage` and `run PART.cl --cage` every pose they read.
//
// What it measures: the ball (radius r, centre tip + r axis) swept from one pose to the
// next, the tip moving straight and the axis turning evenly, against the limit surface
// itself (limit_distance.hpp: its own guide mesh finds the patches near, Newton on them
// finds the distance):
//  - feed, plunge and retract moves may touch the part, not cut deeper than `tolerance`;
//  - rapids may not touch it at all.
// The first pose is checked where it stands.
//
// Sampling bound: each move is split into pieces along which the axis turns at most 0.5
// degrees and the tip moves at most r; each piece's ball sweep is the capsule round the
// straight line between its centres, measured against the surface. The true sweep lies
// within r (1 - cos 0.25 deg) = 1e-5 r of that capsule, so a reported depth is within
// 1e-5 r of the true one: a cut deeper than tolerance + 1e-5 r is always refused, one
// shallower than tolerance - 1e-5 r never is. No mesh of the part decides it, so nothing
// grows with how tightly the surface bends beside a crease.
//
// With a tool assembly (assembly_clearance.hpp) it also holds every move to the fixture's
// rules: each body above the ball keeps clearance_min from the part, nothing goes under the
// floor (the ball and flutes under the stock), measured along the move as assembly_sweep.hpp
// says, with steps of at least `least_step_mm`, against a mesh of its own within 5 um of
// the surface: a move is refused when a measured pose breaks a rule, and one that breaks a
// rule by more than least_step_mm / 2 + AssemblyClearance::resolution_mm + 5 um between
// measured poses is always refused.

#include "base/error.hpp"
#include "cl/cl_pose.hpp"
#include "geometry/assembly_clearance.hpp"
#include "geometry/cage.hpp"
#include "geometry/limit_distance.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/stage_share.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/triangle_tree.hpp"

#include <Eigen/Core>
#include <memory>
#include <optional>

namespace subfeed::geometry {

// mm a feed, plunge or retract may cut below the surface unless told otherwise.
inline constexpr double default_gate_tolerance = 1e-3;

struct GateOptions {
  double ball_radius = 3.0;                  // mm
  double tolerance = default_gate_tolerance; // mm
  // The whole tool and the fixture; without whole_tool, the ball alone against the part.
  bool whole_tool = false;
  ToolAssembly tool;
  Fixture fixture;
};

struct GateReport {
  long moves = 0;         // poses accepted, each with the move that reaches it
  long rapids = 0;        // of them rapids
  double chord = 0.0;     // mm to which its distances to the surface are exact
  double tolerance = 0.0; // mm: GateOptions::tolerance
  // With a tool assembly: each body's least clearance to the part and to the floor over
  // every move accepted (AssemblyClearance::blank() order; a distance to the part is
  // searched only within `clearance_searched` mm: infinity when farther).
  std::vector<BodyClearance> clearance;
  double clearance_searched = 0.0;
};

class MotionGate {
public:
  [[nodiscard]] static Expected<MotionGate> build(const Cage& cage, const LimitSurface& surface,
                                                  const GateOptions& options,
                                                  StageShare* share = nullptr);

  // The move from the last pose accepted to `pose`: accepted, or an error (bad_input) that
  // names the pose's CL line (when it has one), the move, where it reaches into the part and
  // how deep. A refused pose is not remembered: the gate stays at the last accepted one.
  [[nodiscard]] Expected<void> check(const cl::ClPose& pose);

  [[nodiscard]] const GateReport& report() const { return report_; }
  [[nodiscard]] const GateOptions& options() const { return options_; }
  // The whole tool against the gate's own mesh, when it has one.
  [[nodiscard]] const AssemblyClearance* assembly() const { return assembly_.get(); }
  // A gate for another stream of moves (a posted program's, as the machine makes them) on
  // the same part, meshes shared, under the same rules but `tolerance_mm` for cuts: none of
  // this gate's moves, its own report. The two may check on two threads at once.
  [[nodiscard]] MotionGate sibling(double tolerance_mm) const;

  static constexpr double least_step_mm = 0.02;

private:
  // The part as the gate measures it, shared by siblings; the trees point into the meshes.
  struct Part {
    std::unique_ptr<LimitDistance> surface;
    // The whole tool is measured on a coarser mesh of its own (chord 5 um).
    std::unique_ptr<SurfaceMesh> tool_mesh;
    std::unique_ptr<TriangleTree> tool_tree;
  };
  MotionGate(GateOptions options, std::shared_ptr<const Part> part, double chord);
  // The least distance from the mesh to the ball centre's sweep over the move, if under
  // `limit`; with where it is.
  [[nodiscard]] std::optional<LimitNearest> nearest(const cl::ClPose& from, const cl::ClPose& to,
                                                    double limit) const;
  // The first measured pose of the move at which the tool assembly breaks a rule.
  [[nodiscard]] std::optional<ClearanceViolation> sweep_assembly(const cl::ClPose& from,
                                                                 const cl::ClPose& to);
  [[nodiscard]] std::unexpected<Error> assembly_refusal(const cl::ClPose& pose,
                                                        const ClearanceViolation& v) const;
  // "the rapid from (x, y, z) to (x, y, z)", or the first pose's.
  [[nodiscard]] std::string move_text(const cl::ClPose& pose) const;
  // The error for the move from the last pose to `pose`, which reaches `found`.
  [[nodiscard]] std::unexpected<Error> refusal(const cl::ClPose& pose,
                                               const LimitNearest& found) const;

  GateOptions options_;
  std::shared_ptr<const Part> part_;
  std::unique_ptr<AssemblyClearance> assembly_; // refers to part_->tool_tree
  std::optional<cl::ClPose> last_;
  GateReport report_;
};

} // namespace subfeed::geometry

#pragma once
// Constant-scallop tool paths on a limit surface by CL-surface deformation (Yuan & Shao
// 2012, docs/METHOD.md §1-4), produced one pass at a time:
//  1. the limit surface meshed within a chordal tolerance well under the scallop target,
//     each cage face at its own rate;
//  2. the CL surface: ball centres c = p + r n on that mesh;
//  3. per CL vertex the plane interval that leaves exactly the target scallop;
//  4. the deformation along the slicing normal (sparse least squares, then measured and
//     refined; of all solves the one whose path is shortest is kept: deformation.hpp);
//  5. equally spaced planes in the deformed space, each slice mapped back exactly, and
//     passes at fractions of a plane step where the kept solve still leaves them too far
//     apart (pass_insertion.hpp);
//  6. the tool axis from area-weighted triangle normals within a radius, smoothed along
//     the pass (or fixed vertical for three axes);
//  7. every pass point lifted along the surface normal until the ball clears the design
//     mesh (hollows narrower than the ball, concave creases: the ball rides over them), and
//     cleared midpoints inserted where the pass turns so sharply that the ball between two
//     clear points would cut in;
//  8. points along a pass reduced to half the chordal tolerance; passes zig-zag or one way, linked
//     by a retract along the tool axis, a rapid and a plunge; last, one pass along every
//     boundary of the surface, which the slicing planes meet at an angle.
// With PassPattern::concentric, steps 4 and 5 are rings about the highest point instead
// (concentric_field.hpp), their inserted pieces cut after them nearest first.
// Every pose passes the motion gate (motion_gate.hpp) before it reaches the sink: a move
// that would cut deeper than `gate_tolerance` or a rapid that touches the part ends the
// run with an error, and rejected() holds the pose.
// With `baseline` the planes are spaced evenly at the smallest interval instead (plain
// iso-planar passes with the same worst-case scallop), for comparison.

#include "base/bounded_queue.hpp"
#include "base/error.hpp"
#include "cl/cl_pose.hpp"
#include "geometry/assembly_clearance.hpp"
#include "geometry/axis_lean.hpp"
#include "geometry/clear_axes.hpp"
#include "geometry/coarse_deformation.hpp"
#include "geometry/deformation.hpp"
#include "geometry/feed_direction.hpp"
#include "geometry/lifted_regions.hpp"
#include "geometry/limit_distance.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/link_clearance.hpp"
#include "geometry/mesh_slicer.hpp"
#include "geometry/motion_gate.hpp"
#include "geometry/pass_insertion.hpp"
#include "geometry/pass_intervals.hpp"
#include "geometry/plan_stages.hpp"
#include "geometry/planning_cage.hpp"
#include "geometry/point_grid.hpp"
#include "geometry/reach_regions.hpp"
#include "geometry/stage_share.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/triangle_tree.hpp"
#include "geometry/unreachable_regions.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace subfeed::geometry {

class VectorSumTree;

// Parallel passes follow a feed direction; concentric ones are rings about the highest
// point (concentric_field.hpp). With choose_direction, rings are set against the chosen
// direction's passes and cut where predicted shorter.
enum class PassPattern { parallel, concentric };

struct PlanOptions {
  PassPattern pattern = PassPattern::parallel;
  double ball_radius = 3.0;   // mm
  double scallop = 0.01;      // mm
  double direction_deg = 0.0; // feed direction in the XY plane, from +X
  // Instead of direction_deg, the direction whose path is predicted shortest
  // (feed_direction.hpp); --baseline then cuts that direction too.
  bool choose_direction = false;
  // Parallel passes at direction_deg, but rings where those are predicted to cut more than
  // parallel_excess times the ideal length (planes meeting walls edge-on: a body of
  // revolution, a box) and rings are predicted shorter.
  bool rings_where_parallel_fails = false;
  bool baseline = false;
  std::optional<double> axis_radius; // zeta, mm; default: the ball radius
  bool fixed_axis = false;           // vertical tool (three axes)
  // The tool axis's largest angle from +Z, degrees: surface beyond it (or hidden under
  // other parts of the surface) is left uncut (tool_reach.hpp), and no axis leans further.
  double max_tilt_deg = 90.0;
  // Lead and tilt from the feed direction (axis_lean.hpp); none with fixed_axis.
  AxisLean lean;
  bool zigzag = true;
  std::optional<double> tolerance; // mm along a pass; default min(h/10, 0.4 um)
  // mm the planner's mesh keeps to the limit surface: it decides where the slices run and
  // what is reached, not where a pose is (each is placed on the surface itself); default
  // min(h/4, 2 um) for parallel passes (rings marched over a coarser mesh scatter their
  // spacing: the dome's at H 0.03 cut 4 % longer at 7.5 um), the tolerance for rings and
  // --direction auto (mesh_chord()). No cell is cut shorter than min_cell_mm for its chord
  // (rates_for_tolerance).
  std::optional<double> mesh_chord;
  std::optional<double> min_cell_mm; // default 0.1 mm; 0 for rings and auto (min_cell())
  double feed = 1000.0;            // mm/min
  double plunge_feed = 300.0;      // mm/min
  double clearance = 2.0;          // mm, retract along the tool axis between passes
  // mm: a pass that starts within this of where the last one ended is reached by feed
  // along the surface (tip straight, axis turned), where the ball clears the design mesh
  // all the way, riding over what it would cut into, instead of retract, rapid and
  // plunge: a neighbouring pass, or the far side of a sharp convex crease, where the
  // ball rides over the edge (the tear between the two CL sheets, about r times the
  // normals' difference). Default the ball's diameter; 0: always retract.
  std::optional<double> stay_down;
  int refine_iterations = 60;
  // mm an inserted pass runs past where it is needed; default the widest CL spacing.
  std::optional<double> insertion_margin;
  // Passes are inserted where the spacing exceeds the need by more than this fraction
  // (pass_insertion.hpp); the scallop there may exceed the target by about twice as much.
  double spacing_allowance = 0.01;
  int max_rate = 96; // tessellation segments per cage face edge
  // Uniform subdivision steps the planner may take on the cage before meshing, where they
  // mesh the same surface with fewer vertices (planning_cage.hpp); 0: the cage as given.
  int max_cage_levels = 3;
  // mm a move may cut below the surface (motion_gate.hpp); default 1 um, or 2.5 times the
  // tolerance where that is coarser (the mesh chord, the reduction and the lifts together
  // were measured to cut up to that deep).
  std::optional<double> gate_tolerance;
  // From this many mesh vertices, the parallel passes' deformation is solved on a mesh cut
  // `coarse_factor` times more coarsely and carried to the fine one (coarse_mesh.hpp). At 4
  // the dome's passes along 45 degrees cut 14 % longer than the fine solve's; at 2, 5 %.
  int coarse_solve_from = 150'000;
  int coarse_factor = 2;
  // The whole tool and the fixture (assembly_clearance.hpp): axes are turned clear of the
  // part and the floor (clear_axes.hpp), what no axis clears is left uncut, and the gate
  // holds every move to the same rules. Without whole_tool: the ball alone, no floor.
  bool whole_tool = false;
  ToolAssembly tool;
  Fixture fixture;
  bool floor_at_lowest = false; // the floor is the limit surface's lowest point (its mesh's)
};

// The options' tolerances as planned, mm (their defaults filled in).
[[nodiscard]] double path_tolerance(const PlanOptions& options);
[[nodiscard]] double mesh_chord(const PlanOptions& options);
[[nodiscard]] double min_cell(const PlanOptions& options);

// How the lead and tilt were kept along the passes (axis_lean.hpp).
struct LeanReport {
  long points = 0;             // pass points leaned
  long full = 0;               // of them with the whole lean
  long reduced = 0;            // with part of it, or none, to keep the rules
  double least_fraction = 1.0; // the smallest part kept
};

// How much the tool axis turns between neighbouring poses along the passes: what the
// rotary axes must follow while cutting.
struct AxisSteps {
  long steps = 0;
  double largest_deg = 0.0;
  Eigen::Vector3d largest_at = Eigen::Vector3d::Zero(); // the tip after it, mm
  double mean_deg = 0.0;
};

struct PlanSummary {
  double scallop = 0.0;       // H asked for, mm: material thinner than this is within it
  double ball_radius = 0.0;   // mm
  double direction_deg = 0.0; // the feed direction cut
  std::vector<DirectionPrice> direction_prices; // the candidates, when it was chosen
  std::vector<Eigen::Vector3d> ring_centres;    // of concentric passes (one per piece), mm
  double ring_price = 0.0;     // predicted cutting of rings when set against parallel, mm
  double parallel_price = 0.0; // the parallel passes' predicted cutting, mm
  double ideal_length = 0.0;   // mm, what passes meeting the need exactly would cut
  bool rings_instead = false;  // rings_where_parallel_fails took rings
  int rate = 0;
  int cage_levels = 0; // subdivision steps taken before meshing
  long cage_faces = 0; // faces of the cage meshed
  long mesh_vertices = 0;
  long mesh_triangles = 0;
  long unreachable_vertices = 0;
  std::vector<UnreachableRegion> unreachable_regions; // where they are, largest first
  // Left uncut because the tool cannot get there (tilt or hidden), largest first; and the
  // normal's angle from +Z beyond which a point is out of reach.
  std::vector<ReachRegion> out_of_reach;
  double reach_angle_deg = 0.0;
  ClearAxesReport clear_axes; // axes turned for the whole tool, and vertices it cannot clear
  Fixture fixture;            // as planned: the floor found where it was the part's lowest point
  double min_interval = 0.0;  // mm between planes, over the surface
  double max_interval = 0.0;
  double reference = 0.0; // plane spacing in deformed space
  int solves = 0;
  int chosen_solve = 0;             // the solve whose planes are cut (the shortest path)
  long solve_vertices = 0;          // of the mesh the deformation was solved on
  double worst_spacing_ratio = 0.0; // measured/needed of the planes, before insertion
  int inserted_depth = 0;           // passes inserted down to step / 2^depth
  long planes = 0;
  long passes = 0;                          // polylines cut
  long points = 0;                          // feed points written
  long lifted_points = 0;                   // CL points lifted clear of the part, leaving material
  std::vector<LiftedRegion> lifted_regions; // where, thickest first (once run() has finished)
  double cut_length = 0.0;                  // mm of feed moves along passes
  double link_length = 0.0;                 // mm of retracts, rapids and plunges
  long stay_down_links = 0;                 // links made by feed along the surface
  double stay_down_length = 0.0;            // mm of them (counted in cut_length)
  // Pass points left uncut at pass ends no climb out of clears the tool (an overhang above),
  // and the contacts of the first of each such stretch, mm.
  long unclimbable_points = 0;
  std::vector<Eigen::Vector3d> unclimbable_at;
  // Moves the motion gate refused that the planner left uncut, retracting past each, and
  // where (a pass's contact, or a link's tip), mm: a planner defect, reported, never hidden.
  long refused_moves = 0;
  std::vector<Eigen::Vector3d> refused_at;
  std::string first_refusal; // the gate's words for the first of them
  LeanReport lean;                          // with a lead or tilt (once run() has finished)
  AxisSteps axis_steps;                     // along passes (once run() has finished)
  GateReport gate;                          // what the motion gate checked, once run() has finished
  PlanTimes times;                          // where the time went (slicing once run() has finished)

  [[nodiscard]] bool rings() const { return !ring_centres.empty(); } // concentric passes cut
};

class ToolpathPlanner {
public:
  using Sink = std::function<Expected<void>(const cl::ClPose&)>;
  using Progress = std::function<void(long plane, long planes)>;

  // Meshes, offsets, computes intervals and solves the deformation (`observer`: each stage
  // as it starts, each solve).
  [[nodiscard]] static Expected<ToolpathPlanner> prepare(const Cage& cage,
                                                         const LimitSurface& surface,
                                                         const PlanOptions& options,
                                                         const PlanObserver& observer = {});
  // Slices plane after plane and hands every pose to `sink` as soon as its pass is done.
  [[nodiscard]] Expected<void> run(const Sink& sink, const Progress& progress = {});

  [[nodiscard]] const PlanSummary& summary() const { return summary_; }
  // The gate every pose passes (for a sibling that checks what is made of the poses).
  [[nodiscard]] const MotionGate& gate() const { return gate_; }
  [[nodiscard]] const SurfaceMesh& mesh() const { return mesh_; }
  [[nodiscard]] Eigen::Vector3d slicing_normal() const { return s_; }
  // The pose the motion gate refused, when run() failed there.
  [[nodiscard]] const std::optional<cl::ClPose>& rejected() const { return rejected_; }

private:
  struct PassPoint {
    Eigen::Vector3d centre, contact, normal, axis;
  };
  // One level cut, handed from the cutting thread to the linking one in run().
  struct CutLevel {
    long plane = -1; // the plane's number, or -1 for a level inserted between planes
    std::vector<std::vector<PassPoint>> passes;   // to cut now, in order
    std::vector<std::vector<PassPoint>> inserted; // between rings: cut after them
  };
  static constexpr std::size_t levels_ahead = 8; // the most levels cut before they are linked
  ToolpathPlanner(PlanOptions options, SurfaceMesh mesh, MotionGate gate);
  // The steps of prepare(), in order.
  void place_cl_points(); // the ball centres over the mesh's vertices
  void index_triangles();
  // The clear balls, then which vertices the tool reaches and which triangles are cut.
  void find_reach(double margin_mm, StageShare& share);
  // Prices the feed directions (--direction auto); the cheapest, maybe solved in full.
  [[nodiscard]] Expected<DirectionChoice> price_directions(const SolveProgress& progress);
  void face(double direction_deg); // the feed direction and the slicing normal
  // The deformation the passes are sliced from: iso-planar, rings, or solved (or the
  // direction pricing's own solve), and rings instead where auto finds them shorter.
  [[nodiscard]] Expected<void> deform(const PassIntervals& intervals, DirectionChoice choice,
                                      const SolveProgress& progress);
  void summarise(const PassIntervals& intervals); // also lifts the clear balls
  void set_link_limits(double widest_spacing);
  // Where the tool tip runs: the design surface, or the ball centres for a fixed axis.
  [[nodiscard]] const std::vector<Eigen::Vector3d>& path_points() const;
  // The triangles sliced: those in reach (cut_triangles_) and the smooth limits' band.
  [[nodiscard]] std::vector<int> sliced_triangles() const;
  // Mesh triangles by index, and the insertion depth of each.
  [[nodiscard]] std::vector<std::array<int, 3>> triangles_of(const std::vector<int>& ids) const;
  [[nodiscard]] std::vector<unsigned char> depth_of(const std::vector<int>& ids) const;
  [[nodiscard]] std::vector<std::vector<PassPoint>>
  boundary_passes(const std::vector<std::array<int, 3>>& triangles);
  // The limits of the tool's reach that vary smoothly over the surface, so that a pass can
  // end exactly on them: the ball's bottom over the floor (less the stock margin), and the
  // normal's tilt within the machine's.
  enum class SmoothLimit { floor, tilt };
  // Whether the limit leaves some vertex out of reach.
  [[nodiscard]] bool limited_by(SmoothLimit limit) const;
  // How far within the limit a ball centred at `centre` touching where the normal is
  // `normal` stands (mm over the floor's limit; the tilt's cosine over the limit's): < 0
  // beyond it.
  [[nodiscard]] double margin(SmoothLimit limit, const Eigen::Vector3d& centre,
                              const Eigen::Vector3d& normal) const;
  [[nodiscard]] double vertex_margin(SmoothLimit limit, int v) const;
  // In reach, or out of it only by a smooth limit.
  [[nodiscard]] bool smoothly_limited(int v) const;
  // The triangles with a corner in reach and one out of it only by a smooth limit: sliced
  // with the rest, their passes ended on the limit.
  [[nodiscard]] std::vector<int> limit_band() const;
  // The pieces of the passes within `limit`, each ended on it.
  [[nodiscard]] std::vector<std::vector<PassPoint>>
  clipped_at(std::vector<std::vector<PassPoint>> pieces, SmoothLimit limit) const;
  // The pieces of `pass` within every smooth limit but `except`.
  [[nodiscard]] std::vector<std::vector<PassPoint>>
  within_limits(std::vector<PassPoint> pass, std::optional<SmoothLimit> except = {}) const;
  // Passes along each smooth limit's edge (the passes meet it at an angle and leave a strip
  // beside it), within the others; none where no limit leaves a vertex out.
  [[nodiscard]] std::vector<std::vector<PassPoint>> limit_passes();
  // The pieces of `pass` whose every point the ball can be withdrawn from (tool_reach.hpp).
  [[nodiscard]] std::vector<std::vector<PassPoint>> within_reach(std::vector<PassPoint> pass,
                                                                 const TriangleTree& design) const;
  // Every level in order, sliced, cleared, given axes and split where out of reach, into `out`,
  // which it closes at the end; it stops early when the reader closes it.
  void cut_levels(BoundedQueue<CutLevel>& out, const std::vector<int>& sliced,
                  const TriangleTree& design);
  [[nodiscard]] std::vector<std::vector<PassPoint>>
  cut_level(MeshSlicer& slicer, const std::vector<unsigned char>& inserted, double level,
            int depth);
  // The design mesh's triangle tree: what is decided per vertex is decided on it.
  [[nodiscard]] TriangleTree design_tree() const;
  // How far the ball centre must move along `dir` until no point of the design mesh lies
  // inside the ball, mm (a vertex's clear ball).
  [[nodiscard]] double mesh_lift(const TriangleTree& design, const Eigen::Vector3d& centre,
                                 const Eigen::Vector3d& dir) const;
  // A pass point's ball set on the limit surface itself: moved the shorter way clear of the
  // surface (out from its nearest point, or along its normal), or, where it floats off it
  // (a chord of the CL mesh over a hollow), lowered onto it. Returns how far it moved clear,
  // mm (0 where it was lowered or already touching).
  double place_on_surface(PassPoint& p) const;
  // The feed pose whose ball centre and axis are the point's.
  [[nodiscard]] cl::ClPose feed_pose(const PassPoint& p) const;
  // The point a fraction `t` of the way from `a` to `b` (axis within the tilt), not placed.
  [[nodiscard]] PassPoint between(const PassPoint& a, const PassPoint& b, double t) const;
  // Whether placing left the ball more than a radius past touching its own contact: thrown
  // out of a gap, not riding over a hollow.
  [[nodiscard]] bool thrown_off(const PassPoint& p) const;
  // Clears every point of the pass on the limit surface and inserts cleared midpoints where
  // the straight sweep between two would cut in.
  void clear_pass(std::vector<PassPoint>& pass);
  // A ball set on each design vertex along its normal and lifted clear of the part: the
  // places a ball can be, against which what a hollow keeps is measured.
  void set_clear_balls(const TriangleTree& design, StageShare& share);
  // The gap between p and the nearest ball centred on `centres` (gridded in `balls`), or
  // `bound` where none is nearer, mm.
  [[nodiscard]] double gap_to_ball(const std::vector<Eigen::Vector3d>& centres,
                                   const PointGrid& balls, const Eigen::Vector3d& p,
                                   double bound) const;
  // For each vertex the ball cannot reach, how much material it leaves there: its gap to
  // the nearest clear ball (0 where reachable), mm.
  [[nodiscard]] std::vector<double> material_left(const std::vector<char>& reachable) const;
  // The tool axis at a contact: the area-weighted normals of the triangles within zeta
  // (`triangles`: their centroids and area normals), leaning at most max_tilt_deg.
  [[nodiscard]] Eigen::Vector3d vertex_axis(const Eigen::Vector3d& contact,
                                            const Eigen::Vector3d& normal,
                                            const VectorSumTree& triangles) const;
  void smooth_axes(std::vector<PassPoint>& pass) const; // along the pass, within the tilt
  [[nodiscard]] std::vector<std::size_t> reduce(const std::vector<PassPoint>& pass) const;
  // The pass's axes leaned by the options' lead and tilt, as far as the rules allow.
  void lean_axes(std::vector<PassPoint>& pass, const TriangleTree& design);
  [[nodiscard]] Expected<void> emit_pass(const std::vector<PassPoint>& pass, const Sink& sink,
                                         const TriangleTree& design);
  // Each pass in turn the one that starts (or, zig-zag, ends) nearest the tool.
  [[nodiscard]] Expected<void> emit_nearest_first(std::vector<std::vector<PassPoint>> passes,
                                                  const Sink& sink, const TriangleTree& design);
  [[nodiscard]] bool works_round_refusals() const;
  // Counts a move the gate refused that the planner worked round, keeping the first words.
  void note_refusal(const Error& refusal, const Eigen::Vector3d& near);
  // Cuts on after the gate refused the move from pass[from] to pass[to]; the pass point it
  // reached (`end`, the last to cut, where it left the rest uncut).
  [[nodiscard]] Expected<std::size_t> recover_move(const std::vector<PassPoint>& pass,
                                                   std::size_t from, std::size_t to,
                                                   std::size_t end, const Sink& sink,
                                                   const TriangleTree& design);
  // The feed move from pass point `a` (where the tool is) to `b`, halved up to `depth` times
  // where the gate refuses it; a refusal left standing returns its error with rejected() set.
  [[nodiscard]] Expected<void> put_split(const PassPoint& a, const PassPoint& b, int depth,
                                         const Sink& sink);
  [[nodiscard]] Expected<void> link_to(const cl::ClPose& start, const Sink& sink,
                                       const TriangleTree& design, const LinkClearance& links);
  // A link's rapids after its retract, up to where it comes down to the start's clearance
  // (none: straight across at the clearance).
  [[nodiscard]] std::vector<cl::ClPose>
  rapid_route(const LinkClearance& links, const Eigen::Vector3d& above_end,
              const Eigen::Vector3d& end_axis, const Eigen::Vector3d& above_start,
              const Eigen::Vector3d& start_axis) const;
  [[nodiscard]] std::vector<Eigen::Vector3d> climb_to_safe(const LinkClearance& links,
                                                           const Eigen::Vector3d& above,
                                                           const Eigen::Vector3d& axis) const;
  [[nodiscard]] std::vector<cl::ClPose> descent_from_safe(const LinkClearance& links,
                                                          const Eigen::Vector3d& above,
                                                          const Eigen::Vector3d& axis) const;
  // The feed poses between `end` and `start` (both excluded) of a link that stays down, or
  // none where the ball would have to rise more than the link is long.
  [[nodiscard]] std::optional<std::vector<cl::ClPose>>
  stay_down_link(const cl::ClPose& end, const cl::ClPose& start, const TriangleTree& design,
                 const LinkClearance& links) const;
  [[nodiscard]] Expected<void> put(const cl::ClPose& pose, const Sink& sink);

  PlanOptions options_;
  SurfaceMesh mesh_;
  Eigen::Vector3d s_, feed_dir_;
  std::vector<Eigen::Vector3d> cl_points_;
  std::vector<Eigen::Vector3d> centroids_, area_normals_;
  std::vector<Eigen::Vector3d> vertex_axes_;
  // Large meshes are deformed on a coarse one (coarse_deformation.hpp); none on small ones.
  std::unique_ptr<CoarseSolver> coarse_; // the tool axis at each mesh vertex (+Z: fixed)
  double longest_edge_ = 0.0;            // of the design mesh, mm
  std::vector<LiftedPoint> lifted_;
  std::vector<Eigen::Vector3d> clear_balls_; // one per design vertex, mm
  std::vector<ReachLimit> tool_reach_;       // per design vertex
  std::vector<int> cut_triangles_;           // indices of the triangles in reach
  ReachOptions reach_options_;
  bool any_hidden_ = false;                 // some vertex the withdrawing ball cannot leave
  // What limited_by() answers, set once the reach is known: it is asked for every pass.
  bool floor_limited_ = false, tilt_limited_ = false;
  double tilt_cos_ = 0.0; // of the reach angle
  double top_z_ = 0.0;                      // the design mesh's highest point, mm
  std::vector<Eigen::Vector3d> path_balls_; // the ball centres of every cleared pass, mm
  Deformation deformation_;
  double path_tolerance_ = 0.0; // mm, along a pass (PlanOptions::tolerance)
  double mesh_chord_ = 0.0;     // mm, the planner's mesh from the limit surface
  double safe_z_ = 0.0;
  double link_distance_ = 0.0;
  double stay_down_ = 0.0; // mm
  std::optional<cl::ClPose> last_;
  MotionGate gate_;
  // The limit surface the poses are placed on (its own, not the gate's: the gate stays the
  // independent check of what is placed).
  std::unique_ptr<LimitDistance> exact_;
  std::unique_ptr<LinkClearance> links_; // over the design mesh, while run() emits
  std::optional<cl::ClPose> rejected_;
  PlanSummary summary_;
};

} // namespace subfeed::geometry

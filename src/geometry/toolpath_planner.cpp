#include "geometry/toolpath_planner.hpp"

#include "geometry/ball_lift.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/coarse_deformation.hpp"
#include "geometry/link_clearance.hpp"
#include "geometry/concentric_field.hpp"
#include "geometry/mesh_edges.hpp"
#include "geometry/mesh_slicer.hpp"
#include "geometry/point_grid.hpp"
#include "geometry/pose_vectors.hpp"
#include "geometry/split_work.hpp"
#include "geometry/step_over.hpp"
#include "geometry/vector_sum_tree.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <ranges>
#include <thread>
#include <unordered_map>

namespace subfeed::geometry {

namespace {

constexpr double axis_tolerance_rad = 0.25 * std::numbers::pi / 180.0; // along a pass
// mm a pass point keeps beyond the fixture's clearance_min: the move to the next point blends
// the two poses, and the gate holds the blend to clearance_min.
constexpr double pass_clearance_extra = 0.05;
// Halvings of a move between two pass points the gate refused, before it is left uncut.
constexpr int split_depth = 3;
// Of the ball radius, either way, a pass's feed direction is taken over when leaning the
// axis: a pass sliced across coarse triangles (the floor band's edge) wanders sideways by a
// few tenths of a mm, and over 0.25 mm either way that turned the lean 7 degrees between
// poses on the dome's foot.
constexpr double lean_feed_span_radii = 0.5;
// cos 80 deg: a leaned axis keeps the contact within 80 degrees of the tip, on the ball.
constexpr double max_contact_cos = 0.17364817766693033;
// mm the ball's bottom keeps over the lowest it may go on the pass along the floor band's
// edge: twice the floor's tolerance, against rounding.
constexpr double floor_limit_above_mm = 2e-3;
// The longest mesh cell, in flat step-overs (see prepare).
constexpr double reach_cells = 2.0;
// The front's marches after the first (concentric_field.hpp): the third settles the
// directions across the rings on the sample parts.
constexpr int ring_rounds = 3;
// Rings replace parallel passes only where predicted shorter by more than this fraction:
// both predictions leave out the links of inserted pieces, the rings' more of them.
constexpr double ring_preference = 0.02;
// Parallel passes predicted to cut more than this many times the ideal length fight the
// part (rings_where_parallel_fails): the sample parts' are predicted at 0.98 to 1.34 times
// it, OpenSubdiv's regression cages (walls facing the planes) at 15 to 100 times.
constexpr double parallel_excess = 2.0;
// The front's arrival times are first order: measured ring spacings scatter by 1 to 2 %
// about the need where the meter finds no scallop over 1.02 H (the dome), so rings take
// passes inserted only past 2 % (the scallop there may exceed the target by about 4 %).
// At 1 %, 3 % more cutting on the dome, and the same worst scallop.
constexpr double ring_allowance = 0.02;
// mm a rapid straight across between two passes keeps from the part, beyond the ball.
// Solves measured on the fine mesh after those on the coarse one (deform_on_coarse).
constexpr int fine_rounds = 8;

cl::ClPose pose_at(const Eigen::Vector3d& tip, const Eigen::Vector3d& axis, cl::MoveKind kind,
                   double feed) {
  return {{tip.x(), tip.y(), tip.z()}, {axis.x(), axis.y(), axis.z()}, kind, feed, 0};
}

} // namespace

double path_tolerance(const PlanOptions& options) {
  return options.tolerance.value_or(std::min(options.scallop / 10.0, 4e-4));
}

namespace {

bool rings_possible(const PlanOptions& options) {
  return options.pattern == PassPattern::concentric || options.choose_direction;
}

} // namespace

double mesh_chord(const PlanOptions& options) {
  // Rings bend across the mesh where parallel passes run nearly straight: sliced over
  // coarse cells they turn at every cell edge (the tool's tilt from their feed swung 2 to 3
  // degrees at 2 um on the lifted dome), so they keep the fine chord. Rings taken where
  // parallel passes fight the part (rings_where_parallel_fails) are sliced over the mesh
  // cut for those: on the dome that holds the scallop (1.0001 H) and the axis's turns
  // (1.43 degrees at most), but a lead of 15 degrees kept within 1.5 degrees of asked at
  // 90 % of the poses instead of over 95 %.
  if (rings_possible(options)) {
    return options.mesh_chord.value_or(path_tolerance(options));
  }
  return options.mesh_chord.value_or(std::min(options.scallop / 4.0, 2e-3));
}

double min_cell(const PlanOptions& options) {
  // The rings' mesh as it was cut before cells had a floor: at 0.1 mm the dome's rings at
  // H 0.01 took 3 links more by retract, 18 % more link length.
  return options.min_cell_mm.value_or(rings_possible(options) ? 0.0 : 0.1);
}

ToolpathPlanner::ToolpathPlanner(PlanOptions options, SurfaceMesh mesh, MotionGate gate)
    : options_(std::move(options)), mesh_(std::move(mesh)), gate_(std::move(gate)) {}

Expected<ToolpathPlanner> ToolpathPlanner::prepare(const Cage& cage, const LimitSurface& surface,
                                                   const PlanOptions& options,
                                                   const PlanObserver& observer) {
  PlanTimes times;
  const auto enter = [&](PlanStage stage) {
    if (observer.stage) {
      observer.stage(stage);
    }
    return StageClock(times[stage]);
  };
  const double tolerance = path_tolerance(options);
  const double chord = mesh_chord(options);
  std::optional<PlanningCage> finer;
  SUBFEED_TRY_ASSIGN(auto mesh, [&]() -> Expected<SurfaceMesh> {
    const auto clock = enter(PlanStage::meshing);
    if (options.max_cage_levels > 0) {
      SUBFEED_TRY_ASSIGN(finer, planning_cage(cage, surface, chord, options.max_cage_levels,
                                              min_cell(options)));
    }
    // Cells no longer than two flat step-overs: the tool's reach is decided per vertex, so
    // a pass ends within that of where the reach does even on a flat face. (One step-over
    // made steep coarse-tolerance parts cost as their area over the step-over squared: a
    // bowl 64 mm deep went from 12 k to 239 k vertices.)
    const auto& s = finer ? finer->surface : surface;
    StageShare share(observer.share);
    return mesh_surface(
        finer ? finer->cage : cage, s,
        rates_for_tolerance(s, chord, options.max_rate,
                            reach_cells * flat_step(options.ball_radius, options.scallop),
                            min_cell(options)),
        &share);
  }());
  SUBFEED_TRY_ASSIGN(auto exact, [&] {
    const auto clock = enter(PlanStage::gate_mesh);
    return LimitDistance::build(finer ? finer->cage : cage,
                                {.approx_level = surface.approx_level()});
  }());
  // Its own surface distance, apart from the planner's: what it passes does not rest on
  // the planner.
  const double gate_tolerance =
      options.gate_tolerance.value_or(std::max(default_gate_tolerance, 2.5 * tolerance));
  Fixture fixture = options.fixture;
  if (options.floor_at_lowest) {
    fixture.floor_z = exact.lowest_z_under(lowest_point(mesh));
  }
  const GateOptions gate_options{options.ball_radius, gate_tolerance, options.whole_tool,
                                 options.tool, fixture};
  SUBFEED_TRY_ASSIGN(auto gate, [&] {
    const auto clock = enter(PlanStage::gate_mesh);
    StageShare share(observer.share);
    return finer ? MotionGate::build(finer->cage, finer->surface, gate_options, &share)
                 : MotionGate::build(cage, surface, gate_options, &share);
  }());
  auto planned = options;
  planned.fixture = fixture;
  ToolpathPlanner planner(planned, std::move(mesh), std::move(gate));
  planner.exact_ = std::make_unique<LimitDistance>(std::move(exact));
  planner.summary_.fixture = fixture;
  planner.summary_.cage_levels = finer ? finer->levels : 0;
  planner.summary_.cage_faces = finer ? finer->cage.face_count() : cage.face_count();
  planner.path_tolerance_ = tolerance;
  planner.mesh_chord_ = chord;
  {
    const StageClock clock(times[PlanStage::meshing]); // the ball centres over the mesh
    planner.place_cl_points();
    planner.index_triangles();
  }
  {
    const auto clock = enter(PlanStage::reach);
    // balls, axes, reach, the tool's clearance
    StageShare share(observer.share, (options.fixed_axis ? 2 : 3) + (options.whole_tool ? 1 : 0));
    planner.find_reach(gate_tolerance, share);
  }
  if (planner.mesh_.vertex_count() >= options.coarse_solve_from) {
    const StageClock clock(times[PlanStage::deformation]);
    SUBFEED_TRY_ASSIGN(auto map,
                       coarse_mesh(finer ? finer->cage : cage, finer ? finer->surface : surface,
                                   planner.mesh_, options.coarse_factor));
    planner.coarse_ = std::make_unique<CoarseSolver>(std::move(map), options.ball_radius,
                                                     options.scallop, options.fixed_axis);
  }
  DirectionChoice choice; // may hold the chosen direction's deformation, solved in full
  if (options.choose_direction) {
    const auto clock = enter(PlanStage::directions);
    SUBFEED_TRY_ASSIGN(choice, planner.price_directions(observer.solve));
  }
  planner.face(options.choose_direction ? choice.direction_deg : options.direction_deg);
  const auto intervals = pass_intervals(planner.mesh_, options.ball_radius, options.scallop,
                                        planner.s_, reached_mask(planner.tool_reach_));
  {
    const auto clock = enter(PlanStage::deformation);
    SUBFEED_TRY(planner.deform(intervals, std::move(choice), observer.solve));
  }
  {
    const auto clock = enter(PlanStage::clearing);
    planner.summarise(intervals);
    planner.set_link_limits(std::ranges::max(intervals.cl_spacing));
  }
  planner.summary_.times = times;
  return planner;
}

void ToolpathPlanner::place_cl_points() {
  const double r = options_.ball_radius;
  for (int i = 0; i < mesh_.vertex_count(); ++i) {
    cl_points_.push_back(mesh_.points[static_cast<std::size_t>(i)] +
                         r * mesh_.normals[static_cast<std::size_t>(i)]);
  }
}

const std::vector<Eigen::Vector3d>& ToolpathPlanner::path_points() const {
  // A tool along the normal cuts with its tip on the design surface; a vertical one
  // follows the ball centres (shifted down by r).
  return options_.fixed_axis ? cl_points_ : mesh_.points;
}

Expected<DirectionChoice> ToolpathPlanner::price_directions(const SolveProgress& progress) {
  const auto& o = options_;
  const DirectionPricing pricing{.ball_radius = o.ball_radius,
                                 .scallop = o.scallop,
                                 .solves = std::min(o.refine_iterations, 4),
                                 .full_solves = o.refine_iterations,
                                 .spacing_allowance = o.spacing_allowance,
                                 .insertion_margin = o.insertion_margin,
                                 .in_reach = reached_mask(tool_reach_),
                                 .coarse = coarse_.get(),
                                 .fine_rounds = fine_rounds};
  SUBFEED_TRY_ASSIGN(auto choice,
                     choose_feed_direction(mesh_, cl_points_, path_points(), pricing, progress));
  summary_.direction_prices = choice.prices;
  return choice;
}

void ToolpathPlanner::face(double direction_deg) {
  summary_.direction_deg = direction_deg;
  const double a = direction_deg * std::numbers::pi / 180.0;
  feed_dir_ = {std::cos(a), std::sin(a), 0.0};
  s_ = slicing_normal_for(direction_deg);
}

Expected<void> ToolpathPlanner::deform(const PassIntervals& intervals, DirectionChoice choice,
                                       const SolveProgress& progress) {
  const auto& o = options_;
  const auto& m = mesh_;
  summary_.solve_vertices = m.vertex_count();
  const double r = o.ball_radius;
  const double widest = std::ranges::max(intervals.cl_spacing);
  const double insertion_margin = o.insertion_margin.value_or(widest);
  const auto need = [&](const std::vector<Eigen::Vector3d>& across) {
    return cl_spacing_across(m, r, o.scallop, across, intervals.cl_spacing);
  };
  // Inserted pieces between rings lie behind what the front goes round, short and far
  // from each other: each runs one narrowest spacing past where it is needed, not the
  // widest of the whole part (on the dome the two cut within 0.1 % of each other, the
  // scallop unchanged; 0.2 mm cut 1.3 % shorter, a margin below the need itself).
  double narrowest = widest;
  for (std::size_t v = 0; v < intervals.cl_spacing.size(); ++v) {
    if (intervals.cuts(v)) {
      narrowest = std::min(narrowest, intervals.cl_spacing[v]);
    }
  }
  const double ring_margin = o.insertion_margin.value_or(narrowest);
  const auto rings = [&] {
    return concentric_deformation(cl_points_, path_points(), m.triangles, intervals, need,
                                  {intervals.min_interval, ring_rounds, ring_margin,
                                   std::max(o.spacing_allowance, ring_allowance)});
  };
  if (o.baseline) {
    // The baseline is iso-planar whatever the pattern: what the deformation is measured by.
    deformation_ = iso_planar(cl_points_, s_, intervals);
    return {};
  }
  if (o.pattern == PassPattern::concentric) {
    deformation_ = rings();
    return {};
  }
  if (choice.solved_in_full) {
    summary_.solve_vertices = coarse_ ? coarse_->vertex_count() : m.vertex_count();
    deformation_ = std::move(choice.deformation);
  } else if (coarse_) {
    summary_.solve_vertices = coarse_->vertex_count();
    SUBFEED_TRY_ASSIGN(deformation_, coarse_->solve(m, cl_points_, path_points(), s_, intervals,
                                                    {.coarse_rounds = o.refine_iterations,
                                                     .fine_rounds = fine_rounds,
                                                     .insertion_margin = insertion_margin,
                                                     .allowance = o.spacing_allowance,
                                                     .on_solve = progress}));
  } else {
    SUBFEED_TRY_ASSIGN(deformation_,
                       deform_cl_mesh(cl_points_, path_points(), m.triangles, s_, intervals,
                                      o.refine_iterations, insertion_margin, o.spacing_allowance,
                                      progress, need));
  }
  summary_.ideal_length = ideal_cutting_length(cl_points_, m.triangles, intervals);
  summary_.parallel_price = deformation_.insertion.predicted_length;
  const bool failing = o.rings_where_parallel_fails &&
                       summary_.parallel_price > parallel_excess * summary_.ideal_length;
  if (o.choose_direction || failing) {
    auto candidate = rings();
    summary_.ring_price = candidate.insertion.predicted_length;
    if (summary_.ring_price < (1.0 - ring_preference) * summary_.parallel_price) {
      deformation_ = std::move(candidate);
      summary_.rings_instead = failing;
    }
  }
  return {};
}

void ToolpathPlanner::summarise(const PassIntervals& intervals) {
  const auto& m = mesh_;
  auto& s = summary_;
  for (const int v : deformation_.ring_centres) {
    s.ring_centres.push_back(m.points[static_cast<std::size_t>(v)]);
  }
  s.rate = m.rate;
  s.scallop = options_.scallop;
  s.ball_radius = options_.ball_radius;
  s.mesh_vertices = m.vertex_count();
  s.mesh_triangles = m.triangle_count();
  s.unreachable_vertices = std::ranges::count(intervals.reachable, 0);
  s.unreachable_regions =
      unreachable_regions(m, intervals.reachable, material_left(intervals.reachable));
  s.min_interval = intervals.min_interval;
  s.max_interval = intervals.max_interval;
  s.reference = deformation_.reference;
  s.solves = deformation_.iterations;
  s.chosen_solve = deformation_.chosen;
  s.worst_spacing_ratio = deformation_.worst_ratio;
  s.inserted_depth = deformation_.insertion.max_depth;
  s.planes = deformation_.planes.planes;
}

void ToolpathPlanner::set_link_limits(double widest_spacing) {
  const double r = options_.ball_radius;
  double top = -1e300;
  for (const auto& c : cl_points_) {
    top = std::max(top, c.z() + r);
  }
  safe_z_ = top + options_.clearance;
  link_distance_ = 2.0 * widest_spacing + options_.clearance;
  stay_down_ = options_.stay_down.value_or(2.0 * r);
}

// Centroids and area normals (for the tool axis) and the
// longest edge (how far a vertex search must reach).
void ToolpathPlanner::index_triangles() {
  for (const auto& t : mesh_.triangles) {
    const auto& p0 = mesh_.points[static_cast<std::size_t>(t[0])];
    const auto& p1 = mesh_.points[static_cast<std::size_t>(t[1])];
    const auto& p2 = mesh_.points[static_cast<std::size_t>(t[2])];
    centroids_.push_back((p0 + p1 + p2) / 3.0);
    area_normals_.push_back(0.5 * (p1 - p0).cross(p2 - p0));
    longest_edge_ = std::max({longest_edge_, (p1 - p0).norm(), (p2 - p1).norm(), (p0 - p2).norm()});
  }
}

void ToolpathPlanner::find_reach(double margin_mm, StageShare& share) {
  const TriangleTree design = design_tree();
  set_clear_balls(design, share);
  share.next_step();
  auto& axes = vertex_axes_;
  axes.assign(mesh_.points.size(), Eigen::Vector3d::UnitZ());
  if (!options_.fixed_axis) {
    const VectorSumTree triangles(centroids_, area_normals_);
    split_work(axes.size(), [&](std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        share.tell(begin, v, end);
        axes[v] = vertex_axis(mesh_.points[v], mesh_.normals[v], triangles);
      }
    });
    share.next_step();
  }
  reach_options_ = {.ball_radius = options_.ball_radius,
                    .max_tilt_deg = options_.max_tilt_deg,
                    .fixed_axis = options_.fixed_axis,
                    .margin = margin_mm,
                    .clearance_mm = options_.clearance};
  top_z_ = std::ranges::max(mesh_.points, {}, [](const Eigen::Vector3d& p) { return p.z(); }).z();
  tool_reach_ = surface_reach(mesh_, clear_balls_, axes, design, top_z_, reach_options_, &share);
  any_hidden_ = std::ranges::find(tool_reach_, ReachLimit::hidden) != tool_reach_.end();
  if (options_.whole_tool) {
    share.next_step();
    const AssemblyClearance clearance(options_.tool, options_.fixture, design);
    summary_.clear_axes = clear_axes(
        mesh_, cl_points_, axes, tool_reach_, clearance,
        {.max_tilt_deg = options_.max_tilt_deg, .fixed_axis = options_.fixed_axis}, &share);
  }
  for (int t = 0; t < mesh_.triangle_count(); ++t) {
    if (std::ranges::all_of(mesh_.triangles[static_cast<std::size_t>(t)], [&](int v) {
          return tool_reach_[static_cast<std::size_t>(v)] == ReachLimit::reached;
        })) {
      cut_triangles_.push_back(t);
    }
  }
  const auto any = [&](ReachLimit r) { return std::ranges::find(tool_reach_, r) != tool_reach_.end(); };
  floor_limited_ = options_.fixture.floor_z && any(ReachLimit::floor);
  tilt_limited_ = any(ReachLimit::tilt);
  tilt_cos_ = std::cos(reach_angle_deg(reach_options_) * std::numbers::pi / 180.0);
  summary_.out_of_reach = reach_regions(mesh_, tool_reach_);
  summary_.reach_angle_deg = reach_angle_deg(reach_options_);
}

Eigen::Vector3d ToolpathPlanner::vertex_axis(const Eigen::Vector3d& contact,
                                             const Eigen::Vector3d& normal,
                                             const VectorSumTree& triangles) const {
  const double zeta = options_.axis_radius.value_or(options_.ball_radius);
  const Eigen::Vector3d sum = triangles.sum_within(contact, zeta);
  return within_tilt(sum.norm() > 0.0 ? Eigen::Vector3d(sum.normalized()) : normal,
                     options_.max_tilt_deg);
}

std::vector<int> ToolpathPlanner::sliced_triangles() const {
  auto out = cut_triangles_;
  std::ranges::copy(limit_band(), std::back_inserter(out));
  return out;
}

std::vector<std::array<int, 3>> ToolpathPlanner::triangles_of(const std::vector<int>& ids) const {
  std::vector<std::array<int, 3>> out;
  out.reserve(ids.size());
  for (const int t : ids) {
    out.push_back(mesh_.triangles[static_cast<std::size_t>(t)]);
  }
  return out;
}

std::vector<unsigned char> ToolpathPlanner::depth_of(const std::vector<int>& ids) const {
  const auto& depth = deformation_.insertion.depth;
  std::vector<unsigned char> out;
  if (!depth.empty()) {
    out.reserve(ids.size());
    for (const int t : ids) {
      out.push_back(depth[static_cast<std::size_t>(t)]);
    }
  }
  return out;
}

void ToolpathPlanner::smooth_axes(std::vector<PassPoint>& pass) const {
  if (options_.fixed_axis) {
    return;
  }
  // [1 2 1] twice, so the rotary axes move calmly.
  for (int round = 0; round < 2 && pass.size() > 2; ++round) {
    std::vector<Eigen::Vector3d> next(pass.size());
    next.front() = pass.front().axis;
    next.back() = pass.back().axis;
    for (std::size_t i = 1; i + 1 < pass.size(); ++i) {
      next[i] = (pass[i - 1].axis + 2.0 * pass[i].axis + pass[i + 1].axis).normalized();
    }
    for (std::size_t i = 0; i < pass.size(); ++i) {
      pass[i].axis = within_tilt(next[i], options_.max_tilt_deg);
    }
  }
}

std::vector<std::size_t> ToolpathPlanner::reduce(const std::vector<PassPoint>& pass) const {
  // Half the path tolerance: this reduction and the cleared midpoints (clear_pass) together
  // stay under 1 um of gouge at the default tolerance.
  const double tol = 0.5 * path_tolerance_;
  std::vector<std::size_t> kept{0};
  std::size_t anchor = 0;
  for (std::size_t j = 2; j < pass.size(); ++j) {
    bool fits = true;
    for (std::size_t k = anchor + 1; k < j && fits; ++k) {
      // Ball centres, not tips: the centre path is what decides the cut.
      fits =
          (closest_on_segment(pass[k].centre, pass[anchor].centre, pass[j].centre) - pass[k].centre)
              .norm() <= tol;
      const double t = static_cast<double>(k - anchor) / static_cast<double>(j - anchor);
      const Eigen::Vector3d mid = ((1 - t) * pass[anchor].axis + t * pass[j].axis).normalized();
      fits = fits && std::acos(std::clamp(mid.dot(pass[k].axis), -1.0, 1.0)) <= axis_tolerance_rad;
    }
    if (!fits) {
      anchor = j - 1;
      kept.push_back(anchor);
    }
  }
  if (pass.size() > 1) {
    kept.push_back(pass.size() - 1);
  }
  return kept;
}

Expected<void> ToolpathPlanner::put(const cl::ClPose& pose, const Sink& sink) {
  rejected_.reset(); // set only while the last pose put is one the gate refused
  if (auto checked =
          [&] {
            const StageClock clock(summary_.times.gate_checks_s);
            return gate_.check(pose);
          }();
      !checked) {
    rejected_ = pose;
    return checked;
  }
  if (last_) {
    const double d = (tip_of(pose) - tip_of(*last_)).norm();
    (pose.kind == cl::MoveKind::feed ? summary_.cut_length : summary_.link_length) += d;
  }
  last_ = pose;
  const StageClock clock(summary_.times.sink_s);
  return sink(pose);
}

std::optional<std::vector<cl::ClPose>>
ToolpathPlanner::stay_down_link(const cl::ClPose& end, const cl::ClPose& start,
                                const TriangleTree& design, const LinkClearance& links) const {
  const Eigen::Vector3d e = tip_of(end), s = tip_of(start);
  const Eigen::Vector3d ae = axis_of(end), as = axis_of(start);
  const double length = (s - e).norm();
  const double turn = std::acos(std::clamp(ae.dot(as), -1.0, 1.0));
  // Steps of at most 0.05 mm and 2 degrees: between them the ball's sweep stays within a
  // fraction of the mesh tolerance of the poses checked.
  const int steps =
      std::max(1, static_cast<int>(
                      std::ceil(std::max(length / 0.05, turn / (2.0 * std::numbers::pi / 180.0)))));
  std::vector<cl::ClPose> poses;
  double rise = 0.0;
  // The ball centre at t along the link, lifted clear of the design mesh.
  const auto cleared = [&](double t) {
    const Eigen::Vector3d axis = ((1.0 - t) * ae + t * as).normalized();
    Eigen::Vector3d centre = (1.0 - t) * e + t * s + options_.ball_radius * axis;
    const double lift = exact_->lift(centre, axis, options_.ball_radius);
    if (lift > 1e-9) {
      centre += (lift + path_tolerance_) * axis;
      rise = std::max(rise, lift);
    }
    return pose_at(centre - options_.ball_radius * axis, axis, cl::MoveKind::feed, options_.feed);
  };
  // Over a tight convex bend (a seat's nose) the ball between two cleared poses still dips
  // by the bend's sagitta over the step: a cleared pose halfway where the straight sweep
  // would cut in.
  cl::ClPose previous = end;
  for (int i = 1; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const auto next = i < steps ? cleared(t) : start;
    const auto mid = cleared((static_cast<double>(i) - 0.5) / steps);
    const Eigen::Vector3d straight = 0.5 * (tip_of(previous) + tip_of(next));
    if ((tip_of(mid) - straight).dot(axis_of(mid)) > path_tolerance_) {
      poses.push_back(mid);
    }
    if (rise > length) {
      return std::nullopt; // a bump, not a step to the next pass
    }
    // Where the part hides some of the surface, a link could pass under it: every pose of
    // the link must withdraw as the passes' own points do.
    if (any_hidden_ && i < steps &&
        !withdraws(design, tip_of(next) + options_.ball_radius * axis_of(next), axis_of(next),
                   top_z_, reach_options_)) {
      return std::nullopt;
    }
    if (i < steps) {
      poses.push_back(next);
    }
    previous = next;
  }
  // The ball rides the surface; the rest of the tool, turning with the axis, must keep the
  // fixture's clearance over each move as the passes' own moves do.
  std::vector<Eigen::Vector3d> tips{e}, axes{ae};
  for (const auto& p : poses) {
    tips.push_back(tip_of(p));
    axes.push_back(axis_of(p));
  }
  tips.push_back(s);
  axes.push_back(as);
  if (!links.feed_clear(tips, axes)) {
    return std::nullopt;
  }
  return poses;
}

Expected<void> ToolpathPlanner::link_to(const cl::ClPose& start, const Sink& sink,
                                        const TriangleTree& design, const LinkClearance& links) {
  if (last_ && stay_down_ > 0.0 && (tip_of(start) - tip_of(*last_)).norm() <= stay_down_) {
    if (const auto poses = [&] {
          const StageClock clock(summary_.times.links_s);
          return stay_down_link(*last_, start, design, links);
        }()) {
      const double before = summary_.cut_length;
      // A pose the gate refuses ends the feed there; the link retracts from the last one.
      Expected<void> gated;
      const auto passes = [&](const cl::ClPose& p) { return (gated = put(p, sink)).has_value(); };
      if (std::ranges::all_of(*poses, passes) && passes(start)) {
        ++summary_.stay_down_links;
        summary_.stay_down_length += summary_.cut_length - before;
        return {};
      }
      if (!rejected_ || !works_round_refusals()) {
        return gated;
      }
      note_refusal(gated.error(), tip_of(*last_));
    }
  }
  const Eigen::Vector3d start_axis = axis_of(start);
  const Eigen::Vector3d above_start = tip_of(start) + options_.clearance * start_axis;
  std::vector<cl::ClPose> route;
  if (last_) {
    const Eigen::Vector3d end_axis = axis_of(*last_);
    const Eigen::Vector3d above_end = tip_of(*last_) + options_.clearance * end_axis;
    SUBFEED_TRY(put(pose_at(above_end, end_axis, cl::MoveKind::retract, options_.feed), sink));
    const StageClock clock(summary_.times.links_s);
    route = rapid_route(links, above_end, end_axis, above_start, start_axis);
  } else {
    const StageClock clock(summary_.times.links_s);
    route = descent_from_safe(links, above_start, start_axis);
  }
  for (const auto& p : route) {
    SUBFEED_TRY(put(p, sink));
  }
  SUBFEED_TRY(put(pose_at(above_start, start_axis, cl::MoveKind::rapid, 0.0), sink));
  auto plunge = start;
  plunge.kind = cl::MoveKind::plunge;
  plunge.feed = options_.plunge_feed;
  return put(plunge, sink);
}

std::vector<cl::ClPose> ToolpathPlanner::rapid_route(const LinkClearance& links,
                                                     const Eigen::Vector3d& above_end,
                                                     const Eigen::Vector3d& end_axis,
                                                     const Eigen::Vector3d& above_start,
                                                     const Eigen::Vector3d& start_axis) const {
  const auto joined = [&](const std::vector<Eigen::Vector3d>& up,
                          const std::vector<Eigen::Vector3d>& down) {
    std::vector<cl::ClPose> poses;
    for (const auto& p : up) {
      poses.push_back(pose_at(p, end_axis, cl::MoveKind::rapid, 0.0));
    }
    for (const auto& p : std::views::reverse(down)) {
      poses.push_back(pose_at(p, start_axis, cl::MoveKind::rapid, 0.0));
    }
    return poses;
  };
  // A short hop goes straight across at the clearance, or, where the part rises between
  // (a knob's crown, the far side of a ridge), over it a clearance above the higher end;
  // a long one at the safe height: a rapid may not touch the part.
  if ((above_end - above_start).norm() <= link_distance_) {
    if (links.clear(above_end, end_axis, above_start, start_axis)) {
      return {};
    }
    const double hop = std::max(above_end.z(), above_start.z()) + options_.clearance;
    if (hop < safe_z_) {
      const auto up = links.climb(above_end, end_axis, hop);
      const auto down = links.climb(above_start, start_axis, hop);
      if (up && down && links.clear(up->back(), end_axis, down->back(), start_axis)) {
        return joined(*up, *down);
      }
    }
  }
  return joined(climb_to_safe(links, above_end, end_axis),
                climb_to_safe(links, above_start, start_axis));
}

std::vector<Eigen::Vector3d> ToolpathPlanner::climb_to_safe(const LinkClearance& links,
                                                            const Eigen::Vector3d& above,
                                                            const Eigen::Vector3d& axis) const {
  // Every pass end climbs (emit_pass): straight up is only what a buried tool is left with,
  // and the gate then names what is in the way.
  return links.climb(above, axis, safe_z_)
      .value_or(std::vector{Eigen::Vector3d(above.x(), above.y(), safe_z_)});
}

std::vector<cl::ClPose> ToolpathPlanner::descent_from_safe(const LinkClearance& links,
                                                           const Eigen::Vector3d& above,
                                                           const Eigen::Vector3d& axis) const {
  std::vector<cl::ClPose> poses;
  for (const auto& p : std::views::reverse(climb_to_safe(links, above, axis))) {
    poses.push_back(pose_at(p, axis, cl::MoveKind::rapid, 0.0));
  }
  return poses;
}

void ToolpathPlanner::lean_axes(std::vector<PassPoint>& pass, const TriangleTree& design) {
  std::vector<Eigen::Vector3d> centres;
  for (const auto& p : pass) {
    centres.push_back(p.centre);
  }
  const double r = options_.ball_radius;
  const auto feeds = feed_directions(centres, lean_feed_span_radii * r);
  std::optional<AssemblyClearance> clearance;
  if (options_.whole_tool) {
    clearance.emplace(options_.tool, options_.fixture, design);
  }
  // The rules the unleaned axis was held to (within_reach), checked for a leaned one.
  const auto keeps = [&](std::size_t i, double fraction) {
    const auto& p = pass[i];
    const Eigen::Vector3d axis = leaned_axis(p.axis, feeds[i], options_.lean, fraction);
    const double tilt = std::acos(std::clamp(axis.z(), -1.0, 1.0)) * 180.0 / std::numbers::pi;
    // The contact stays on the ball, where it is modelled: as for turned axes (clear_axes).
    return tilt <= options_.max_tilt_deg && axis.dot(p.normal) >= max_contact_cos &&
           (!any_hidden_ || withdraws(design, p.centre, axis, top_z_, reach_options_)) &&
           (!clearance || clearance->clear(p.centre - r * axis, axis, pass_clearance_extra));
  };
  const auto fractions = lean_fractions(centres, options_.lean, keeps);
  auto& report = summary_.lean;
  for (std::size_t i = 0; i < pass.size(); ++i) {
    pass[i].axis = leaned_axis(pass[i].axis, feeds[i], options_.lean, fractions[i]);
    ++report.points;
    report.full += fractions[i] == 1.0 ? 1 : 0;
    report.reduced += fractions[i] < 1.0 ? 1 : 0;
    report.least_fraction = std::min(report.least_fraction, fractions[i]);
  }
}

namespace {

// From `from` toward `to` (excluded) by `step` (+1 or -1), a point `climbs` holds at, found
// in a few tries over a long stretch under an overhang (each try is a sweep tens of
// millimetres long): doubling strides until one holds, then halving back to where the
// stretch ends; `to` where none holds. Not always the first that holds (the predicate is
// not monotone): a point that holds, with the one before it failing.
template <typename Climbs>
std::size_t first_climbing(std::size_t from, std::size_t to, int step, const Climbs& climbs) {
  const auto at = [&](std::size_t i, std::size_t n) {
    return step > 0 ? i + n : i - n;
  };
  const std::size_t span = step > 0 ? to - from : from - to;
  if (span == 0 || climbs(from)) {
    return span == 0 ? to : from;
  }
  std::size_t failed = 0, held = 0; // offsets from `from`
  for (std::size_t stride = 1;; stride *= 2) {
    const std::size_t n = std::min(failed + stride, span);
    if (n == span) {
      // The far end is `to`, not tried: the last point before it decides.
      if (span - 1 == failed || !climbs(at(from, span - 1))) {
        return to;
      }
      held = span - 1;
      break;
    }
    if (climbs(at(from, n))) {
      held = n;
      break;
    }
    failed = n;
  }
  while (held - failed > 1) {
    const std::size_t mid = failed + (held - failed) / 2;
    (climbs(at(from, mid)) ? held : failed) = mid;
  }
  return at(from, held);
}

} // namespace

Expected<void> ToolpathPlanner::emit_pass(const std::vector<PassPoint>& given, const Sink& sink,
                                          const TriangleTree& design) {
  std::vector<PassPoint> leaned;
  if (options_.lean.any() && !options_.fixed_axis) {
    leaned = given;
    lean_axes(leaned, design);
  }
  const auto& pass = leaned.empty() ? given : leaned;
  const auto kept = reduce(pass);
  const auto pose = [&](std::size_t i) { return feed_pose(pass[kept[i]]); };
  // Each end of what is cut must be left and reached by a climb that clears: a stretch at
  // an end the tool cannot climb out of (under an overhang, past the holder's reach) is
  // left uncut, counted, and the named uncut areas hold it.
  const LinkClearance& links = *links_;
  const auto climbs = [&](std::size_t i) {
    const StageClock clock(summary_.times.links_s);
    const auto p = pose(i);
    return links.climb(tip_of(p) + options_.clearance * axis_of(p), axis_of(p), safe_z_)
        .has_value();
  };
  const std::size_t first = first_climbing(0, kept.size(), +1, climbs);
  if (first == kept.size()) {
    summary_.unclimbable_points += static_cast<long>(kept.size());
    summary_.unclimbable_at.push_back(pass[kept.front()].contact);
    return {};
  }
  const std::size_t last = first_climbing(kept.size() - 1, first, -1, climbs) + 1;
  if (last - first < kept.size()) {
    summary_.unclimbable_points += static_cast<long>(kept.size() - (last - first));
    summary_.unclimbable_at.push_back(pass[kept[first > 0 ? 0 : last]].contact);
  }
  if (last - first < 2) {
    return {};
  }
  SUBFEED_TRY(link_to(pose(first), sink, design, links));
  auto& steps = summary_.axis_steps;
  std::size_t at = kept[first]; // the pass point the tool is at
  for (std::size_t i = first + 1; i < last; ++i) {
    if (kept[i] <= at) {
      continue; // passed in a recovery
    }
    const auto& a = pass[at].axis;
    const auto& b = pass[kept[i]].axis;
    const double turn = std::acos(std::clamp(a.dot(b), -1.0, 1.0)) * 180.0 / std::numbers::pi;
    steps.mean_deg += (turn - steps.mean_deg) / static_cast<double>(++steps.steps);
    if (turn > steps.largest_deg) {
      steps.largest_deg = turn;
      steps.largest_at = pass[kept[i]].centre - options_.ball_radius * b;
    }
    if (at == kept[i - 1]) {
      if (auto put_it = put(pose(i), sink); put_it) {
        at = kept[i];
        continue;
      } else if (!rejected_ || !works_round_refusals()) {
        return put_it;
      }
    }
    // Refused, or on from where a recovery left the tool, between two kept points: the
    // reduced move from there was never checked, so the pass's own points are cut one by one.
    auto reached = recover_move(pass, at, kept[i], kept[last - 1], sink, design);
    if (!reached) {
      return std::unexpected(reached.error());
    }
    at = *reached;
  }
  summary_.points += static_cast<long>(last - first);
  ++summary_.passes;
  return {};
}

void ToolpathPlanner::note_refusal(const Error& refusal, const Eigen::Vector3d& near) {
  if (summary_.refused_moves++ == 0) {
    summary_.first_refusal = refusal.message;
  }
  summary_.refused_at.push_back(near);
}

bool ToolpathPlanner::works_round_refusals() const {
  // Only at the depth the planner places its poses to: a gate asked to hold them finer than
  // that (--gate-tolerance) refuses the plan, as asked, rather than leave most of it uncut.
  return gate_.options().tolerance >=
         std::max(default_gate_tolerance, 2.5 * path_tolerance_) - 1e-12;
}

Expected<std::size_t> ToolpathPlanner::recover_move(const std::vector<PassPoint>& pass,
                                                    std::size_t from, std::size_t to,
                                                    std::size_t end, const Sink& sink,
                                                    const TriangleTree& design) {
  // The gate refused the move from pass[from] (cut) to pass[to] (the planner's checks missed
  // something its own surface model does not see), or that move, from where an earlier
  // recovery left the tool, was never checked. The pass's own points between are cut one
  // by one; a move refused even between two neighbours is left uncut, the tool retracting
  // and coming down past it, on a pose that itself keeps the gate's depth (the plunge to it
  // runs along its axis). The summary counts each (a planner defect, reported).
  const double deepest = options_.ball_radius - 0.5 * gate_.options().tolerance;
  const auto sound = [&](std::size_t k) { return !exact_->nearest(pass[k].centre, deepest); };
  for (std::size_t k = from + 1; k <= to; ++k) {
    auto put_it = put_split(pass[k - 1], pass[k], split_depth, sink);
    if (put_it) {
      continue;
    }
    if (!rejected_ || !works_round_refusals()) {
      return std::unexpected(put_it.error());
    }
    note_refusal(put_it.error(), pass[k].contact);
    while (k <= end && !sound(k)) {
      ++k;
    }
    if (k > end) {
      return end; // the rest of the pass is left uncut
    }
    SUBFEED_TRY(link_to(feed_pose(pass[k]), sink, design, *links_));
    if (k >= to) {
      return k;
    }
  }
  return to;
}

Expected<void> ToolpathPlanner::put_split(const PassPoint& a, const PassPoint& b, int depth,
                                          const Sink& sink) {
  auto whole = put(feed_pose(b), sink);
  if (whole || !rejected_ || depth == 0) {
    return whole;
  }
  // Refused between two neighbours: halved, the middle placed on the surface (a long move's
  // straight sweep dips where the points' own check saw none), with the blended axis or one
  // held from either end (a blend can swing the flutes past a wall both ends clear). Every
  // move still goes to the gate from wherever the tool is.
  PassPoint mid = between(a, b, 0.5);
  place_on_surface(mid);
  if (thrown_off(mid)) {
    return whole; // no middle on the surface near the move
  }
  const cl::ClPose refused = *rejected_;
  for (const Eigen::Vector3d& axis : {mid.axis, a.axis, b.axis}) {
    PassPoint held = mid;
    held.axis = axis;
    if (auto first = put_split(a, held, depth - 1, sink); first) {
      return put_split(held, b, depth - 1, sink);
    } else if (!rejected_) {
      return first;
    }
  }
  rejected_ = refused;
  return whole;
}

Expected<void> ToolpathPlanner::emit_nearest_first(std::vector<std::vector<PassPoint>> passes,
                                                   const Sink& sink, const TriangleTree& design) {
  std::vector<char> done(passes.size(), 0);
  for (std::size_t n = 0; n < passes.size(); ++n) {
    const Eigen::Vector3d from = last_ ? tip_of(*last_) : passes.front().front().contact;
    std::size_t best = 0;
    bool reversed = false;
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < passes.size(); ++i) {
      if (done[i] != 0) {
        continue;
      }
      const double ahead = (passes[i].front().contact - from).norm();
      const double behind = (passes[i].back().contact - from).norm();
      if (ahead < nearest) {
        nearest = ahead;
        best = i;
        reversed = false;
      }
      if (options_.zigzag && behind < nearest) {
        nearest = behind;
        best = i;
        reversed = true;
      }
    }
    done[best] = 1;
    if (reversed) {
      std::ranges::reverse(passes[best]);
    }
    SUBFEED_TRY(emit_pass(passes[best], sink, design));
  }
  return {};
}

TriangleTree ToolpathPlanner::design_tree() const {
  return {mesh_.points, mesh_.triangles};
}

double ToolpathPlanner::mesh_lift(const TriangleTree& design, const Eigen::Vector3d& centre,
                                  const Eigen::Vector3d& dir) const {
  return lift_ball(
      [&design](const Eigen::Vector3d& at, double limit) -> std::optional<Eigen::Vector3d> {
        if (const auto found = design.nearest(at, at, limit)) {
          return found->on_mesh;
        }
        return std::nullopt;
      },
      centre, dir, options_.ball_radius, 1e-9);
}

cl::ClPose ToolpathPlanner::feed_pose(const PassPoint& p) const {
  return pose_at(p.centre - options_.ball_radius * p.axis, p.axis, cl::MoveKind::feed,
                 options_.feed);
}

ToolpathPlanner::PassPoint ToolpathPlanner::between(const PassPoint& a, const PassPoint& b,
                                                    double t) const {
  return {(1 - t) * a.centre + t * b.centre, (1 - t) * a.contact + t * b.contact,
          ((1 - t) * a.normal + t * b.normal).normalized(),
          within_tilt(((1 - t) * a.axis + t * b.axis).normalized(), options_.max_tilt_deg)};
}

bool ToolpathPlanner::thrown_off(const PassPoint& p) const {
  return (p.centre - p.contact).norm() > 2.0 * options_.ball_radius;
}

double ToolpathPlanner::place_on_surface(PassPoint& p) const {
  const double r = options_.ball_radius;
  const double lift = exact_->lift(p.centre, p.normal, r);
  if (lift > 0.0) {
    // Along the point's normal is far round a crease, where the normal is one side's and the
    // ball touches the edge (0.19 mm for a 9 um cut on the rook's crown): the shorter push
    // out from the surface is taken where it clears. (Not held to the point's normal: in a
    // concave corner the normal is one wall's and the push runs square to it; a guard on
    // that left 328 refusals on the rook, where this leaves 11.)
    if (const auto pushed = exact_->pushed_clear(p.centre, r);
        pushed && (*pushed - p.centre).norm() < lift) {
      const double moved = (*pushed - p.centre).norm();
      p.centre = *pushed;
      return moved;
    }
    p.centre += lift * p.normal;
    return lift;
  }
  // Off the surface by no more than the CL mesh's chord could leave it: lowered along the
  // surface's own normal there, onto the CL surface.
  const double band = 8.0 * mesh_chord_ + 1e-6;
  if (const auto near = exact_->nearest(p.centre, r + band)) {
    const Eigen::Vector3d out = p.centre - near->on_surface;
    if (out.norm() > 0.0) {
      p.centre = near->on_surface + r * out.normalized();
    }
  }
  return 0.0;
}

void ToolpathPlanner::set_clear_balls(const TriangleTree& design, StageShare& share) {
  const double r = options_.ball_radius;
  clear_balls_.resize(mesh_.points.size());
  split_work(clear_balls_.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      share.tell(begin, v, end);
      const Eigen::Vector3d& n = mesh_.normals[v];
      clear_balls_[v] = mesh_.points[v] + r * n;
      clear_balls_[v] += mesh_lift(design, clear_balls_[v], n) * n;
    }
  });
}

double ToolpathPlanner::gap_to_ball(const std::vector<Eigen::Vector3d>& centres,
                                    const PointGrid& balls, const Eigen::Vector3d& p,
                                    double bound) const {
  // Searched in widening rings until no ball further out could be nearer.
  const double r = options_.ball_radius;
  for (double ring = longest_edge_; ring > 0.0; ring *= 2.0) {
    balls.within(p, r + std::min(ring, bound), [&](int u) {
      bound = std::min(bound, (centres[static_cast<std::size_t>(u)] - p).norm() - r);
    });
    if (bound <= ring) {
      break;
    }
  }
  return std::max(0.0, bound);
}

std::vector<double> ToolpathPlanner::material_left(const std::vector<char>& reachable) const {
  // Lifted along its own normal, a ball set off the middle of a pocket crosses it and climbs
  // the far wall, so a vertex's material is its gap to the nearest of all the clear balls
  // (the one set on the pocket's middle, for most), not to its own.
  std::vector<double> material(reachable.size(), 0.0);
  const PointGrid balls(clear_balls_, options_.ball_radius + longest_edge_);
  for (std::size_t v = 0; v < reachable.size(); ++v) {
    if (reachable[v] == 0) {
      const double own = (clear_balls_[v] - mesh_.points[v]).norm() - options_.ball_radius;
      material[v] = gap_to_ball(clear_balls_, balls, mesh_.points[v], own);
    }
  }
  return material;
}

void ToolpathPlanner::clear_pass(std::vector<PassPoint>& pass) {
  // A lift beyond this is a hollow the ball rides over, not the rounding of a point
  // interpolated on a CL mesh edge.
  const double hollow = 2.0 * mesh_chord_;
  const auto lift_clear = [&](PassPoint& p) { return place_on_surface(p); };
  for (auto& p : pass) {
    if (const double lift = lift_clear(p); lift > hollow) {
      lifted_.push_back({p.contact, lift});
    }
  }
  // Between two placed points the ball can still cut in (where the pass turns over a hollow
  // or a crease, or the surface bends one way then the other between them), or float off a
  // concave stretch by the chord's sagitta (on the planner's mesh, cells run to two
  // step-overs: up to 7 um on the bowl, most of the scallop). A placed point goes in where
  // the straight sweep comes nearest, or halfway where it floats, recursively, wherever
  // the sweep is off the surface by more than a quarter of the tolerance.
  std::vector<PassPoint> out;
  out.reserve(pass.size());
  const double r = options_.ball_radius;
  const double off = 0.25 * path_tolerance_;
  const auto refine = [&](auto& self, const PassPoint& a, const PassPoint& b, int depth) -> void {
    if (depth >= 8) {
      return;
    }
    double t = 0.5;
    const Eigen::Vector3d ab = b.centre - a.centre;
    if (const auto near = exact_->nearest(a.centre, b.centre, r - off)) {
      t = std::clamp(ab.squaredNorm() > 0.0
                         ? (near->on_segment - a.centre).dot(ab) / ab.squaredNorm()
                         : 0.5,
                     0.05, 0.95);
    } else if (exact_->nearest(a.centre + 0.5 * ab, r + off)) {
      return; // touching within the tolerance
    }
    PassPoint mid = between(a, b, t);
    const Eigen::Vector3d straight = mid.centre;
    lift_clear(mid);
    if ((mid.centre - straight).norm() <= off) {
      return; // over a hollow the ball rides over, it stays off the surface
    }
    self(self, a, mid, depth + 1);
    out.push_back(mid);
    self(self, mid, b, depth + 1);
  };
  for (std::size_t i = 0; i < pass.size(); ++i) {
    if (i > 0) {
      refine(refine, pass[i - 1], pass[i], 0);
    }
    out.push_back(pass[i]);
  }
  pass = std::move(out);
  for (const auto& p : pass) {
    path_balls_.push_back(p.centre);
  }
}

std::vector<std::vector<ToolpathPlanner::PassPoint>>
ToolpathPlanner::boundary_passes(const std::vector<std::array<int, 3>>& triangles) {
  // Edges of one triangle only, in that triangle's winding, chained end to start: where the
  // surface ends and where the tool's reach does.
  const auto edges = mesh_edges(triangles);
  std::unordered_map<int, int> next;
  for (const auto& t : triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (triangles_on_edge(edges, t[k], t[(k + 1) % 3]) == 1) {
        next[t[k]] = t[(k + 1) % 3];
      }
    }
  }
  std::vector<std::vector<PassPoint>> passes;
  while (!next.empty()) {
    int v = next.begin()->first;
    std::vector<int> chain{v};
    while (true) {
      const auto it = next.find(v);
      if (it == next.end()) {
        break;
      }
      v = it->second;
      next.erase(it);
      chain.push_back(v);
    }
    std::vector<PassPoint> run;
    for (const int i : chain) {
      const auto u = static_cast<std::size_t>(i);
      run.push_back({cl_points_[u], mesh_.points[u], mesh_.normals[u], vertex_axes_[u]});
    }
    if (run.size() >= 2) {
      clear_pass(run);
      passes.push_back(std::move(run));
    }
  }
  return passes;
}

bool ToolpathPlanner::limited_by(SmoothLimit limit) const {
  return limit == SmoothLimit::floor ? floor_limited_ : tilt_limited_;
}

double ToolpathPlanner::margin(SmoothLimit limit, const Eigen::Vector3d& centre,
                               const Eigen::Vector3d& normal) const {
  if (limit == SmoothLimit::floor) {
    // A ball on a face lying on the floor touches it, as the reach allows (within the
    // floor's tolerance): cut there, not clipped off.
    return centre.z() - options_.ball_radius -
           (*options_.fixture.floor_z - options_.fixture.stock_margin) +
           0.5 * AssemblyClearance::floor_tolerance_mm;
  }
  return normal.z() - tilt_cos_;
}

double ToolpathPlanner::vertex_margin(SmoothLimit limit, int v) const {
  return margin(limit, cl_points_[static_cast<std::size_t>(v)],
                mesh_.normals[static_cast<std::size_t>(v)]);
}

bool ToolpathPlanner::smoothly_limited(int v) const {
  const auto r = tool_reach_[static_cast<std::size_t>(v)];
  return r == ReachLimit::reached || r == ReachLimit::floor || r == ReachLimit::tilt;
}

std::vector<int> ToolpathPlanner::limit_band() const {
  std::vector<int> band;
  if (!limited_by(SmoothLimit::floor) && !limited_by(SmoothLimit::tilt)) {
    return band;
  }
  for (int i = 0; i < mesh_.triangle_count(); ++i) {
    const auto& t = mesh_.triangles[static_cast<std::size_t>(i)];
    const auto reached = [&](int v) {
      return tool_reach_[static_cast<std::size_t>(v)] == ReachLimit::reached;
    };
    if (std::ranges::all_of(t, [&](int v) { return smoothly_limited(v); }) &&
        std::ranges::any_of(t, reached) && !std::ranges::all_of(t, reached)) {
      band.push_back(i);
    }
  }
  return band;
}

std::vector<std::vector<ToolpathPlanner::PassPoint>>
ToolpathPlanner::clipped_at(std::vector<std::vector<PassPoint>> pieces, SmoothLimit limit) const {
  if (!limited_by(limit)) {
    return pieces;
  }
  // Between two pass points the ball centres and normals are linear, as on the mesh: a
  // piece ends where the margin crosses zero, to within the cell's curvature.
  std::vector<std::vector<PassPoint>> out;
  for (auto& pass : pieces) {
    out.emplace_back();
    double before = 0.0;
    for (std::size_t i = 0; i < pass.size(); ++i) {
      const double here = margin(limit, pass[i].centre, pass[i].normal);
      if (i > 0 && (before >= 0.0) != (here >= 0.0)) {
        const double t = before / (before - here);
        const auto& a = pass[i - 1];
        const auto& b = pass[i];
        out.back().push_back({(1 - t) * a.centre + t * b.centre,
                              (1 - t) * a.contact + t * b.contact,
                              ((1 - t) * a.normal + t * b.normal).normalized(),
                              (here >= 0.0 ? b : a).axis});
        if (here < 0.0) {
          out.emplace_back();
        }
      }
      if (here >= 0.0) {
        out.back().push_back(std::move(pass[i]));
      }
      before = here;
    }
  }
  std::erase_if(out, [](const auto& piece) { return piece.size() < 2; });
  return out;
}

std::vector<std::vector<ToolpathPlanner::PassPoint>>
ToolpathPlanner::within_limits(std::vector<PassPoint> pass,
                               std::optional<SmoothLimit> except) const {
  std::vector<std::vector<PassPoint>> pieces;
  pieces.push_back(std::move(pass));
  for (const auto limit : {SmoothLimit::floor, SmoothLimit::tilt}) {
    if (limit != except) {
      pieces = clipped_at(std::move(pieces), limit);
    }
  }
  return pieces;
}

std::vector<std::vector<ToolpathPlanner::PassPoint>> ToolpathPlanner::limit_passes() {
  std::vector<std::vector<PassPoint>> passes;
  for (const auto limit : {SmoothLimit::floor, SmoothLimit::tilt}) {
    if (!limited_by(limit)) {
      continue;
    }
    // The margin per vertex is linear along every edge, as the ball centres are, so its
    // level set is the limit's edge on the mesh.
    // The floor's edge pass keeps the ball's bottom a little over it, against rounding.
    const double level = limit == SmoothLimit::floor
                             ? floor_limit_above_mm + 0.5 * AssemblyClearance::floor_tolerance_mm
                             : 0.0;
    std::vector<double> field(mesh_.points.size());
    for (int v = 0; v < mesh_.vertex_count(); ++v) {
      field[static_cast<std::size_t>(v)] = vertex_margin(limit, v);
    }
    std::vector<std::array<int, 3>> crossed;
    for (const auto& t : mesh_.triangles) {
      const auto value = [&](int k) { return field[std::size_t(t[std::size_t(k)])] - level; };
      if (std::min({value(0), value(1), value(2)}) < 0.0 &&
          std::max({value(0), value(1), value(2)}) > 0.0 &&
          std::ranges::all_of(t, [&](int v) { return smoothly_limited(v); })) {
        crossed.push_back(t);
      }
    }
    MeshSlicer slicer(crossed, field);
    for (const auto& line : slicer.slice(level)) {
      std::vector<PassPoint> pass;
      for (const auto& e : line) {
        const auto a = static_cast<std::size_t>(e.a), b = static_cast<std::size_t>(e.b);
        // The axis of the end in reach: the other end's was never cleared for the whole tool.
        const auto kept = tool_reach_[a] == ReachLimit::reached ? a : b;
        pass.push_back({(1 - e.t) * cl_points_[a] + e.t * cl_points_[b],
                        (1 - e.t) * mesh_.points[a] + e.t * mesh_.points[b],
                        ((1 - e.t) * mesh_.normals[a] + e.t * mesh_.normals[b]).normalized(),
                        vertex_axes_[kept]});
      }
      for (auto& piece : within_limits(std::move(pass), limit)) {
        clear_pass(piece);
        passes.push_back(std::move(piece));
      }
    }
  }
  return passes;
}

std::vector<std::vector<ToolpathPlanner::PassPoint>>
ToolpathPlanner::within_reach(std::vector<PassPoint> pass, const TriangleTree& design) const {
  std::vector<std::vector<PassPoint>> pieces;
  const double r = options_.ball_radius;
  // A ball whose placing left its centre more than two radii from its own contact (a radius
  // past touching it) has not ridden over a hollow but been thrown out of one: lifted along
  // a wall's normal out of a gap between two of the rook's merlons it landed 10 mm away, and
  // the moves to it cut 1-3 um where the pass runs. It ends the pass as a point out of
  // reach does.
  const auto placed_near = [&](const PassPoint& p) { return !thrown_off(p); };
  if (!any_hidden_ && !options_.whole_tool && std::ranges::all_of(pass, placed_near)) {
    pieces.push_back(std::move(pass));
    return pieces;
  }
  // Between two vertices in reach an edge can still pass under the part (round the corner
  // of a shadow): each point must withdraw, since any may end a piece and start a link. The
  // whole tool is held to the fixture's rules at every point, with a little to spare for the
  // move between two points (the motion gate holds it to them along the move).
  std::optional<AssemblyClearance> clearance;
  if (options_.whole_tool) {
    clearance.emplace(options_.tool, options_.fixture, design);
  }
  std::vector<PassPoint> piece;
  const auto close = [&] {
    if (piece.size() >= 2) {
      pieces.push_back(std::move(piece));
    }
    piece.clear();
  };
  const auto tool_clear = [&](const Eigen::Vector3d& centre, const Eigen::Vector3d& axis) {
    return !clearance || clearance->clear(centre - r * axis, axis, pass_clearance_extra);
  };
  // Between two points far apart (a CL mesh cell across a flat) the tool passes walls its
  // ends do not see: on the rook's crown a 5.4 mm move whose ends kept 0.55 mm brought the
  // flutes within 0.492 mm. The move is sampled; where a sample fails, the piece ends there.
  const double sample_mm = 0.25 * r;
  const auto move_clear = [&](const PassPoint& a, const PassPoint& b) {
    const int samples = static_cast<int>((b.centre - a.centre).norm() / sample_mm);
    for (int k = 1; k <= samples; ++k) {
      const double t = static_cast<double>(k) / (samples + 1);
      if (!tool_clear((1 - t) * a.centre + t * b.centre,
                      ((1 - t) * a.axis + t * b.axis).normalized())) {
        return false;
      }
    }
    return true;
  };
  for (auto& p : pass) {
    if (placed_near(p) &&
        (!any_hidden_ || withdraws(design, p.centre, p.axis, top_z_, reach_options_)) &&
        tool_clear(p.centre, p.axis)) {
      if (clearance && !piece.empty() && !move_clear(piece.back(), p)) {
        close();
      }
      piece.push_back(std::move(p));
    } else {
      close();
    }
  }
  close();
  return pieces;
}

std::vector<std::vector<ToolpathPlanner::PassPoint>>
ToolpathPlanner::cut_level(MeshSlicer& slicer, const std::vector<unsigned char>& inserted,
                           double level, int depth) {
  auto lines = slicer.slice(level, inserted.empty() ? nullptr : &inserted, depth);
  std::vector<std::vector<PassPoint>> passes;
  for (const auto& line : lines) {
    std::vector<PassPoint> pass;
    for (const auto& e : line) {
      const auto a = static_cast<std::size_t>(e.a), b = static_cast<std::size_t>(e.b);
      PassPoint p;
      p.centre = (1 - e.t) * cl_points_[a] + e.t * cl_points_[b];
      p.contact = (1 - e.t) * mesh_.points[a] + e.t * mesh_.points[b];
      p.normal = ((1 - e.t) * mesh_.normals[a] + e.t * mesh_.normals[b]).normalized();
      // The axis averages normals over zeta, many cells: between two vertices it is their
      // axes' blend, within 0.1 to 0.22 degrees of the average taken at the point on the
      // sample parts, 0.46 beside the ridge's sharp crease (less than the smoothing below
      // moves it), at a fraction of the cost.
      p.axis = within_tilt(((1 - e.t) * vertex_axes_[a] + e.t * vertex_axes_[b]).normalized(),
                           options_.max_tilt_deg);
      pass.push_back(p);
    }
    for (auto& piece : within_limits(std::move(pass))) {
      clear_pass(piece);
      passes.push_back(std::move(piece));
    }
  }
  // Along the feed direction, sorted across it.
  for (auto& pass : passes) {
    if ((pass.back().centre - pass.front().centre).dot(feed_dir_) < 0.0) {
      std::ranges::reverse(pass);
    }
  }
  std::ranges::sort(passes, [&](const auto& x, const auto& y) {
    return x.front().centre.dot(feed_dir_) < y.front().centre.dot(feed_dir_);
  });
  return passes;
}

void ToolpathPlanner::cut_levels(BoundedQueue<CutLevel>& out, const std::vector<int>& sliced,
                                 const TriangleTree& design) {
  const auto inserted_depth = depth_of(sliced);
  const auto triangles = triangles_of(sliced); // the slicer keeps a view of them
  MeshSlicer slicer(triangles, deformation_.deformed);
  const auto [first, step, planes] = deformation_.planes;
  const int deepest = deformation_.insertion.max_depth;
  const long per_plane = 1L << max_insertion_depth;
  const bool rings = !deformation_.ring_centres.empty();
  long cut_count = 0;
  for (long index = 0; index <= (planes - 1) * per_plane; ++index) {
    const int depth = level_depth(index);
    if (depth > deepest) {
      continue;
    }
    CutLevel level;
    level.plane = depth == 0 ? index / per_plane : -1;
    const double at = first + static_cast<double>(index) * step / static_cast<double>(per_plane);
    auto passes = cut_level(slicer, inserted_depth, at, depth);
    // Every other level the other way round for zig-zag.
    if (!passes.empty() && options_.zigzag && cut_count % 2 == 1) {
      std::ranges::reverse(passes);
      for (auto& pass : passes) {
        std::ranges::reverse(pass);
      }
    }
    cut_count += passes.empty() ? 0 : 1;
    for (auto& whole : passes) {
      smooth_axes(whole);
      for (auto& pass : within_reach(std::move(whole), design)) {
        (rings && depth > 0 ? level.inserted : level.passes).push_back(std::move(pass));
      }
    }
    if ((level.plane >= 0 || !level.passes.empty() || !level.inserted.empty()) &&
        !out.push(std::move(level))) {
      return; // the linking side has stopped
    }
  }
  out.close();
}

Expected<void> ToolpathPlanner::run(const Sink& sink, const Progress& progress) {
  const StageClock clock(summary_.times[PlanStage::slicing]);
  // Only the triangles in reach, and those across the smooth limits' edges, where the
  // passes end exactly on them (within_limits): a pass ends where the tool's reach does.
  const auto sliced = sliced_triangles();
  const auto cut = triangles_of(cut_triangles_);
  const TriangleTree design = design_tree();
  links_ = std::make_unique<LinkClearance>(*exact_, options_.ball_radius, options_.whole_tool,
                                           options_.tool, options_.fixture, design);
  // Two cores: a thread cuts the levels into passes while this one links them, gates every
  // pose and hands it on, in the same order as one thread would. The cutting side writes only
  // the slicer, the lifted points and the path's balls; this side only the last pose, the
  // gate and the summary.
  BoundedQueue<CutLevel> levels(levels_ahead);
  std::jthread cutter([&] { cut_levels(levels, sliced, design); });
  // Between rings, inserted passes are short pieces spread round the part (behind each
  // hollow it must go round); cut ring by ring they would each cost a retract and a rapid
  // across it. They are cut after the rings instead, nearest first, mostly linked by feed.
  std::vector<std::vector<PassPoint>> inserted;
  while (auto level = levels.pop()) {
    if (progress && level->plane >= 0) {
      progress(level->plane, deformation_.planes.planes);
    }
    for (const auto& pass : level->passes) {
      if (auto emitted = emit_pass(pass, sink, design); !emitted) {
        levels.close(); // the cutter stops at its next level
        return emitted;
      }
    }
    std::ranges::move(level->inserted, std::back_inserter(inserted));
  }
  cutter.join();
  SUBFEED_TRY(emit_nearest_first(std::move(inserted), sink, design));
  // Last, one pass along every boundary of the surface: iso-planar passes meet a boundary
  // at an angle and leave a strip beside it that no neighbour pass covers.
  for (auto& whole : boundary_passes(cut)) {
    smooth_axes(whole);
    for (const auto& pass : within_reach(std::move(whole), design)) {
      SUBFEED_TRY(emit_pass(pass, sink, design));
    }
  }
  // And one along the exact edge of each smooth limit (the floor, the tilt), which the
  // passes meet at an angle.
  for (auto& whole : limit_passes()) {
    smooth_axes(whole);
    for (const auto& pass : within_reach(std::move(whole), design)) {
      SUBFEED_TRY(emit_pass(pass, sink, design));
    }
  }
  if (last_) {
    const Eigen::Vector3d above = tip_of(*last_) + options_.clearance * axis_of(*last_);
    SUBFEED_TRY(put(pose_at(above, axis_of(*last_), cl::MoveKind::retract, options_.feed), sink));
    for (const auto& p : climb_to_safe(*links_, above, axis_of(*last_))) {
      SUBFEED_TRY(put(pose_at(p, axis_of(*last_), cl::MoveKind::rapid, 0.0), sink));
    }
  }
  summary_.gate = gate_.report();
  summary_.lifted_points = static_cast<long>(lifted_.size());
  // A point lifted along a normal that crosses a pocket rises far more than the material
  // it leaves: what is left there is its gap to the nearest ball of the whole path.
  const PointGrid balls(path_balls_, options_.ball_radius + longest_edge_);
  for (auto& p : lifted_) {
    p.lift_mm = gap_to_ball(path_balls_, balls, p.contact, p.lift_mm);
  }
  summary_.lifted_regions = lifted_regions(lifted_, options_.ball_radius);
  return {};
}

} // namespace subfeed::geometry

#include "geometry/motion_gate.hpp"

#include "geometry/assembly_sweep.hpp"
#include "geometry/pose_vectors.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

namespace subfeed::geometry {

namespace {

constexpr double piece_turn_rad = 0.5 * std::numbers::pi / 180.0;
constexpr int most_segments = 256; // Bfr's largest tessellation rate
// mm between the limit surface and the mesh the tool assembly is measured against: half
// the assembly's own resolution. The cut's tolerance (a micrometre) would make the mesh
// tens of times larger and the search as much slower, for clearances of a tenth of a mm.
constexpr double tool_chord_mm = 0.5 * AssemblyClearance::resolution_mm;
// mm of slack searched for at each measured pose: a tool farther off steps on by this. The
// search costs as the part's area within it: at 10 mm the dome's gate took 6 minutes.
constexpr double slack_searched_mm = 1.0;

const char* move_name(cl::MoveKind kind) {
  switch (kind) {
  case cl::MoveKind::rapid:
    return "rapid";
  case cl::MoveKind::feed:
    return "cutting move";
  case cl::MoveKind::plunge:
    return "plunge";
  case cl::MoveKind::retract:
    return "retract";
  }
  return "move";
}

std::string point_text(const Eigen::Vector3d& p) {
  return fmt::format("({:.4f}, {:.4f}, {:.4f})", p.x(), p.y(), p.z());
}

} // namespace

MotionGate::MotionGate(GateOptions options, std::shared_ptr<const Part> part, double chord)
    : options_(std::move(options)), part_(std::move(part)) {
  report_.chord = chord;
  report_.tolerance = options_.tolerance;
  if (part_->tool_tree) {
    assembly_ =
        std::make_unique<AssemblyClearance>(options_.tool, options_.fixture, *part_->tool_tree);
    report_.clearance = assembly_->blank();
    report_.clearance_searched = options_.fixture.clearance_min + slack_searched_mm;
  }
}

MotionGate MotionGate::sibling(double tolerance_mm) const {
  auto options = options_;
  options.tolerance = tolerance_mm;
  return {options, part_, report_.chord};
}

Expected<MotionGate> MotionGate::build(const Cage& cage, const LimitSurface& surface,
                                       const GateOptions& options, StageShare* share) {
  if (!(options.ball_radius > 0.0) || !(options.tolerance > 0.0)) {
    return fail(ErrorCode::bad_input, "the gate needs a ball radius and tolerance above 0");
  }
  SUBFEED_TRY_ASSIGN(auto exact,
                     LimitDistance::build(cage, {.approx_level = surface.approx_level()}));
  auto part = std::make_shared<Part>();
  part->surface = std::make_unique<LimitDistance>(std::move(exact));
  if (options.whole_tool) {
    SUBFEED_TRY_ASSIGN(auto coarse,
                       mesh_surface(cage, surface,
                                    rates_for_tolerance(surface, tool_chord_mm, most_segments),
                                    share));
    part->tool_mesh = std::make_unique<SurfaceMesh>(std::move(coarse));
    part->tool_tree =
        std::make_unique<TriangleTree>(part->tool_mesh->points, part->tool_mesh->triangles);
  }
  return MotionGate(options, std::move(part), LimitDistance::precision_mm);
}

std::optional<LimitNearest> MotionGate::nearest(const cl::ClPose& from, const cl::ClPose& to,
                                                double limit) const {
  const double r = options_.ball_radius;
  const Eigen::Vector3d t0 = tip_of(from), t1 = tip_of(to);
  const Eigen::Vector3d a0 = axis_of(from), a1 = axis_of(to);
  const double turn = std::acos(std::clamp(a0.dot(a1), -1.0, 1.0));
  const int pieces = std::max(
      1, static_cast<int>(std::ceil(std::max(turn / piece_turn_rad, (t1 - t0).norm() / r))));
  const auto centre = [&](double t) {
    const Eigen::Vector3d axis = (1.0 - t) * a0 + t * a1;
    return Eigen::Vector3d((1.0 - t) * t0 + t * t1 +
                           r * (axis.norm() > 0.0 ? axis.normalized() : a1));
  };
  std::optional<LimitNearest> best;
  Eigen::Vector3d previous = centre(0.0);
  for (int i = 1; i <= pieces; ++i) {
    const Eigen::Vector3d next = centre(static_cast<double>(i) / pieces);
    if (auto found = part_->surface->nearest(previous, next, best ? best->distance : limit)) {
      best = found;
    }
    previous = next;
  }
  return best;
}

Expected<void> MotionGate::check(const cl::ClPose& pose) {
  const double r = options_.ball_radius;
  const bool rapid = pose.kind == cl::MoveKind::rapid;
  // Only what reaches past the limit is searched for (the nearest point under it, if any):
  // a move that touches the part where it should costs no more than the box tests round it.
  const double limit = rapid ? r + report_.chord : r - options_.tolerance;
  if (const auto found = nearest(last_ ? *last_ : pose, pose, limit)) {
    return refusal(pose, *found);
  }
  if (assembly_) {
    if (const auto broken = sweep_assembly(last_ ? *last_ : pose, pose)) {
      return assembly_refusal(pose, *broken);
    }
  }
  ++report_.moves;
  report_.rapids += rapid ? 1 : 0;
  last_ = pose;
  return {};
}

std::string MotionGate::move_text(const cl::ClPose& pose) const {
  return last_ ? fmt::format("the {} from {} to {}", move_name(pose.kind),
                             point_text(tip_of(*last_)), point_text(tip_of(pose)))
               : fmt::format("the first pose, a {} at {},", move_name(pose.kind),
                             point_text(tip_of(pose)));
}

std::optional<ClearanceViolation> MotionGate::sweep_assembly(const cl::ClPose& from,
                                                             const cl::ClPose& to) {
  return sweep_move(*assembly_, tip_of(from), axis_of(from), tip_of(to), axis_of(to),
                    {.cap_mm = slack_searched_mm, .least_step_mm = least_step_mm},
                    &report_.clearance)
      .first;
}

std::unexpected<Error> MotionGate::assembly_refusal(const cl::ClPose& pose,
                                                    const ClearanceViolation& v) const {
  const std::string what =
      v.floor
          ? fmt::format("takes the {} {:.4f} mm below the {} at {}", v.body, v.distance,
                        v.body == "ball" || v.body == "flutes" ? "stock's bottom" : "floor",
                        point_text(v.where))
          : fmt::format("brings the {} within {:.4f} mm of the part (at least {:g} mm) at {}",
                        v.body, v.distance, options_.fixture.clearance_min, point_text(v.where));
  const std::string move = move_text(pose);
  return fail(ErrorCode::bad_input, fmt::format("tool path refused: {} {}", move, what),
              {{}, static_cast<int>(pose.line), {}});
}

std::unexpected<Error> MotionGate::refusal(const cl::ClPose& pose,
                                           const LimitNearest& found) const {
  const double depth = options_.ball_radius - found.distance; // < 0: clear of the mesh by that
  const std::string what = pose.kind == cl::MoveKind::rapid
                               ? fmt::format("touches the part (the ball {:.4f} mm {})",
                                             std::abs(depth), depth >= 0.0 ? "deep" : "from it")
                               : fmt::format("cuts {:.4f} mm into the part (tolerance {:g} mm)",
                                             depth, options_.tolerance);
  const std::string move = move_text(pose);
  return fail(
      ErrorCode::bad_input,
      fmt::format("tool path refused: {} {} at {}", move, what, point_text(found.on_surface)),
      {{}, static_cast<int>(pose.line), {}});
}

} // namespace subfeed::geometry

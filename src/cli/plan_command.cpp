// `subfeed plan CAGE.obj --tool ball:D --scallop H -o PART.cl`: constant-scallop tool paths
// by CL-surface deformation (geometry/toolpath_planner.hpp), written pass by pass.

#include "command.hpp"
#include "tool_spec.hpp"

#include "cl/cl_writer.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/toolpath_planner.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <unistd.h>

namespace subfeed::cli {

namespace {

struct PlanCommandOptions {
  std::string cage;
  std::string tool;
  double scallop = 0.0;
  std::string direction = "x";
  bool baseline = false;
  double axis_radius = 0.0;
  std::string axis = "normal";
  bool one_way = false;
  double feed = 1000.0;
  double plunge_feed = 300.0;
  double clearance = 2.0;
  double tolerance = 0.0;
  int level = geometry::min_approx_level;
  int refine = 60;
  std::string output;
};

Expected<double> direction_deg(const std::string& text) {
  if (text == "x") {
    return 0.0;
  }
  if (text == "y") {
    return 90.0;
  }
  try {
    std::size_t used = 0;
    const double a = std::stod(text, &used);
    if (used == text.size()) {
      return a;
    }
  } catch (const std::exception&) {
  }
  return fail(ErrorCode::usage, "'" + text + "': expected x, y or an angle in degrees",
              {{}, 0, "--direction"});
}

Expected<void> run_plan(const PlanCommandOptions& o, Logger& log) {
  SUBFEED_TRY_ASSIGN(const double radius, parse_ball_tool(o.tool));
  if (o.scallop <= 0.0 || o.scallop >= radius) {
    return fail(ErrorCode::usage, "must be more than 0 and less than the ball radius",
                {{}, 0, "--scallop"});
  }
  geometry::PlanOptions options;
  options.ball_radius = radius;
  options.scallop = o.scallop;
  SUBFEED_TRY_ASSIGN(options.direction_deg, direction_deg(o.direction));
  options.baseline = o.baseline;
  if (o.axis_radius > 0.0) {
    options.axis_radius = o.axis_radius;
  }
  options.fixed_axis = o.axis == "fixed";
  options.zigzag = !o.one_way;
  options.feed = o.feed;
  options.plunge_feed = o.plunge_feed;
  options.clearance = o.clearance;
  options.refine_iterations = o.refine;
  if (o.tolerance > 0.0) {
    options.tolerance = o.tolerance;
  }
  SUBFEED_TRY_ASSIGN(const auto cage, geometry::read_obj(o.cage));
  SUBFEED_TRY_ASSIGN(const auto surface, geometry::LimitSurface::build(cage, o.level));
  SUBFEED_TRY_ASSIGN(auto planner, geometry::ToolpathPlanner::prepare(cage, surface, options));
  const std::string output =
      o.output.empty() ? std::filesystem::path(o.cage).replace_extension(".cl").string() : o.output;
  cl::ClHeader header{
      std::filesystem::path(o.cage).stem().string(), {2 * radius, radius}, !options.fixed_axis};
  SUBFEED_TRY_ASSIGN(auto writer, cl::ClWriter::create(output, header));
  const bool terminal = ::isatty(STDERR_FILENO) == 1 && log.verbosity() != Verbosity::quiet;
  SUBFEED_TRY(planner.run(
      [&writer](const cl::ClPose& pose) -> Expected<void> {
        writer.write(pose);
        return {};
      },
      [&](long plane, long planes) {
        if (terminal && plane % 16 == 0) {
          std::fprintf(stderr, "\rplanning: plane %ld of %ld", plane, planes);
        }
      }));
  if (terminal) {
    std::fprintf(stderr, "\r\033[K");
  }
  SUBFEED_TRY(writer.finish());
  const auto& s = planner.summary();
  log.info(fmt::format("{}: {} passes, {} points, cutting {:.1f} mm, links {:.1f} mm ({})", output,
                       s.passes, s.points, s.cut_length, s.link_length,
                       o.baseline ? "iso-planar baseline" : "deformed CL surface"));
  log.info(fmt::format("  mesh {} vertices, {} triangles (up to {} segments a cage edge); plane "
                       "interval {:.4f}..{:.4f} mm; {} planes {:.4f} mm apart{}",
                       s.mesh_vertices, s.mesh_triangles, s.rate, s.min_interval, s.max_interval,
                       s.planes, s.reference, o.baseline ? "" : " in deformed space"));
  if (!o.baseline) {
    log.info(fmt::format("  deformation: solve {} of {} kept (the shortest path), pass spacing up "
                         "to {:.3f} of the need{}",
                         s.chosen_solve, s.solves, s.worst_spacing_ratio,
                         s.inserted_depth > 0
                             ? fmt::format("; passes inserted there down to 1/{} of a plane step",
                                           1 << s.inserted_depth)
                             : std::string()));
  }
  if (s.unreachable_vertices > 0 || s.lifted_points > 0) {
    log.warning(
        fmt::format("  the ball cannot reach {} surface vertices (hollows narrower than the "
                    "ball); {} CL points lifted clear there, leaving material",
                    s.unreachable_vertices, s.lifted_points));
  }
  return {};
}

} // namespace

void add_plan_command(CLI::App& app, Action& chosen) {
  auto o = std::make_shared<PlanCommandOptions>();
  CLI::App* cmd = app.add_subcommand("plan", "Plan constant-scallop finishing passes on a cage");
  cmd->add_option("cage", o->cage, "Control cage (Wavefront OBJ, mm)")
      ->required()
      ->type_name("CAGE.obj");
  cmd->add_option("--tool", o->tool, "Cutter: ball:D (diameter D mm)")->required();
  cmd->add_option("--scallop", o->scallop, "Scallop height target, mm")->required();
  cmd->add_option("--direction", o->direction, "Feed direction: x, y or degrees from X");
  cmd->add_flag("--baseline", o->baseline, "Constant-interval iso-planar passes for comparison");
  cmd->add_option("--axis-radius", o->axis_radius,
                  "Tool axis averaging radius zeta, mm (default: ball radius)")
      ->check(CLI::Range(1e-3, 1000.0));
  cmd->add_option("--axis", o->axis,
                  "Tool axis: normal (five axes) or fixed (vertical, three axes)")
      ->check(CLI::IsMember({"normal", "fixed"}));
  cmd->add_flag("--one-way", o->one_way, "Cut every pass in the same direction (default zig-zag)");
  cmd->add_option("--feed", o->feed, "Cutting feed, mm/min")->check(CLI::Range(1.0, 100000.0));
  cmd->add_option("--plunge-feed", o->plunge_feed, "Plunge feed, mm/min")
      ->check(CLI::Range(1.0, 100000.0));
  cmd->add_option("--clearance", o->clearance, "Retract along the tool axis between passes, mm")
      ->check(CLI::Range(0.01, 1000.0));
  cmd->add_option("--tolerance", o->tolerance,
                  "Chordal tolerance of mesh and passes, mm (default min(H/10, 0.0004))")
      ->check(CLI::Range(1e-6, 1.0));
  cmd->add_option("--level", o->level, "Bfr approximation level near irregular features")
      ->check(CLI::Range(geometry::min_approx_level, geometry::max_approx_level));
  cmd->add_option("--refine", o->refine,
                  "Most deformation solves while measured spacing exceeds the need")
      ->check(CLI::Range(1, 100));
  cmd->add_option("-o,--output", o->output, "CL data to write (default: CAGE.cl)");
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return run_plan(*o, log); }; });
}

} // namespace subfeed::cli

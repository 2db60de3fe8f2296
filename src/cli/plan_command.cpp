// `subfeed plan CAGE.obj --tool ball:D --scallop H -o PART.cl`: constant-scallop tool paths
// by CL-surface deformation (geometry/toolpath_planner.hpp), written pass by pass.

#include "command.hpp"
#include "plan_flags.hpp"
#include "plan_progress.hpp"
#include "plan_report.hpp"
#include "setup_flags.hpp"

#include "cl/cl_writer.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/part_setup.hpp"
#include "geometry/toolpath_planner.hpp"
#include "job/plan_refusal.hpp"
#include "job/tool_spec.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <unistd.h>

namespace subfeed::cli {

using namespace subfeed::job; // NOLINT: the front wires the job library

namespace {

struct PlanCommandOptions {
  std::string cage;
  PlanSettings plan;
  SetupFlags setup;
  std::string output;
};

Expected<void> run_plan(PlanCommandOptions o, Logger& log) {
  SUBFEED_TRY(resolve_tool(o.plan, log));
  SUBFEED_TRY_ASSIGN(const auto options, plan_options_from(o.plan));
  const double radius = options.ball_radius;
  const auto setup = o.setup.with_defaults();
  SUBFEED_TRY_ASSIGN(const auto cage, geometry::read_part(o.cage, setup));
  SUBFEED_TRY_ASSIGN(const auto surface, geometry::LimitSurface::build(cage, o.plan.level));
  const bool terminal = ::isatty(STDERR_FILENO) == 1 && log.verbosity() != Verbosity::quiet;
  PlanProgress progress(terminal);
  SUBFEED_TRY_ASSIGN(auto planner, geometry::ToolpathPlanner::prepare(cage, surface, options,
                                                                      progress.observer()));
  const std::string output =
      o.output.empty() ? std::filesystem::path(o.cage).replace_extension(".cl").string() : o.output;
  cl::ClHeader header{std::filesystem::path(o.cage).stem().string(),
                      {2 * radius, radius},
                      !options.fixed_axis,
                      geometry::setup_text(setup),
                      {}};
  record_tool(header, options, planner.summary());
  SUBFEED_TRY_ASSIGN(auto writer, cl::ClWriter::create(output, header));
  const auto ran = planner.run(
      [&writer](const cl::ClPose& pose) -> Expected<void> {
        writer.write(pose);
        return {};
      },
      [&](long plane, long planes) { progress.plane(plane, planes); });
  progress.finish();
  if (!ran) {
    return std::unexpected(at_refused_pose(ran.error(), planner, writer, output));
  }
  SUBFEED_TRY(writer.finish());
  const auto& s = planner.summary();
  log.info(fmt::format("{}: {} passes, {} points, cutting {:.1f} mm, links {:.1f} mm ({})", output,
                       s.passes, s.points, s.cut_length, s.link_length,
                       o.plan.baseline ? "iso-planar baseline"
                                       : (s.rings() ? "concentric rings" : "deformed CL surface")));
  if (s.stay_down_links > 0) {
    log.info(fmt::format("  {} of the {} links stay down: {:.1f} mm by feed along the surface "
                         "(in the cutting length), the rest retract",
                         s.stay_down_links, s.passes - 1, s.stay_down_length));
  }
  if (s.passes == 0) {
    // An open sheet's up side is the side its faces wind counter-clockwise seen from: a
    // sheet modelled the other way round faces the table.
    log.warning("  nothing to cut: no surface faces the tool within reach; an open sheet whose "
                "faces wind the other way faces down: plan it with the opposite --up (-y for y)");
  }
  if (s.unclimbable_points > 0) {
    const auto& at = s.unclimbable_at.front();
    log.warning(fmt::format("  {} points at {} pass end(s) left uncut: no climb out of them clears "
                         "the tool (the part overhangs them), the first at ({:.3f}, {:.3f}, {:.3f})",
                         s.unclimbable_points, s.unclimbable_at.size(), at.x(), at.y(), at.z()));
  }
  if (s.refused_moves > 0) {
    const auto& at = s.refused_at.front();
    log.warning(fmt::format("  {} move(s) the motion gate refused left uncut, the tool retracting "
                            "past each (a planner defect: please report it), the first near "
                            "({:.3f}, {:.3f}, {:.3f})",
                            s.refused_moves, at.x(), at.y(), at.z()));
    log.warning(fmt::format("    the first: {}", s.first_refusal));
  }
  const std::string refined =
      s.cage_levels > 0
          ? fmt::format(" of the cage subdivided {} time(s), {} faces", s.cage_levels, s.cage_faces)
          : std::string();
  log.info(fmt::format("  mesh {} vertices, {} triangles (up to {} segments a cage edge{}); plane "
                       "interval {:.4f}..{:.4f} mm; {} planes {:.4f} mm apart{}",
                       s.mesh_vertices, s.mesh_triangles, s.rate, refined, s.min_interval,
                       s.max_interval, s.planes, s.reference,
                       o.plan.baseline ? "" : " in deformed space"));
  const std::string inserted =
      s.inserted_depth > 0 ? fmt::format("; passes inserted there down to 1/{} of a plane step",
                                         1 << s.inserted_depth)
                           : std::string();
  if (s.rings()) {
    std::string centres;
    for (const auto& c : s.ring_centres) {
      centres += fmt::format("{}({:.2f}, {:.2f}, {:.2f})", centres.empty() ? "" : ", ", c.x(),
                             c.y(), c.z());
    }
    log.info(fmt::format("  concentric rings about {}, {} marches of the front; ring spacing up "
                         "to {:.3f} of the need{}",
                         centres, s.solves, s.worst_spacing_ratio, inserted));
  } else if (!o.plan.baseline) {
    const std::string coarse =
        s.solve_vertices < s.mesh_vertices
            ? fmt::format(" (solved on a coarse mesh of {} vertices, measured on the fine one)",
                          s.solve_vertices)
            : std::string();
    log.info(fmt::format("  deformation: solve {} of {} kept (the shortest path){}, pass spacing "
                         "up to {:.3f} of the need{}",
                         s.chosen_solve, s.solves, coarse, s.worst_spacing_ratio, inserted));
  }
  if (!s.direction_prices.empty()) {
    std::string prices;
    bool full = false;
    for (const auto& c : s.direction_prices) {
      const char* separator = prices.empty() ? "" : (c.full && !full ? "; solved in full: " : ", ");
      full = full || c.full;
      prices += fmt::format("{}{:g} deg {:.0f} mm", separator, c.direction_deg, c.predicted_length);
    }
    log.info(fmt::format("  feed direction {:g} deg, chosen by predicted cutting: {}",
                         s.direction_deg, prices));
    log.info(fmt::format("  {} by predicted cutting: rings {:.0f} mm against {:.0f} mm of "
                         "parallel passes",
                         s.rings() ? "concentric rings cut" : "parallel passes kept", s.ring_price,
                         s.parallel_price));
  }
  if (!s.rings() && s.parallel_price > 0.0 && s.ideal_length > 0.0) {
    log.info(fmt::format("  predicted cutting {:.0f} mm, {:.2f} times the ideal {:.0f} mm",
                         s.parallel_price, s.parallel_price / s.ideal_length, s.ideal_length));
  }
  if (s.rings_instead) {
    log.info(fmt::format("  concentric rings instead of parallel passes: predicted {:.0f} mm "
                         "against {:.0f} mm, the ideal {:.0f} mm (--direction x keeps the "
                         "parallel passes)",
                         s.ring_price, s.parallel_price, s.ideal_length));
  }
  if (options.whole_tool) {
    log.info(tool_summary(options.tool, s));
  }
  if (const auto axis = axis_summary(options, s); !axis.empty()) {
    log.info(axis);
  }
  log.info(gate_summary(s.gate));
  log.detail(time_summary(s.times, s.solves));
  report_left_material(s, log);
  return {};
}

} // namespace

void add_plan_command(CLI::App& app, Action& chosen) {
  auto o = std::make_shared<PlanCommandOptions>();
  CLI::App* cmd = app.add_subcommand("plan", "Plan constant-scallop finishing passes on a cage");
  cmd->add_option("cage", o->cage,
                  "Control cage (Wavefront OBJ; units and orientation: --units, --up)")
      ->required()
      ->type_name("CAGE.obj");
  add_plan_flags(*cmd, o->plan);
  add_setup_flags(*cmd, o->setup);
  cmd->add_option("-o,--output", o->output, "CL data to write (default: CAGE.cl)");
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return run_plan(*o, log); }; });
}

} // namespace subfeed::cli

// `subfeed verify CAGE.obj PART.cl --tool ball:D [--svg out.svg] [--png out.png]`: the independent
// scallop measurement of a path on its surface (geometry/path_verifier.hpp), and the whole
// tool's clearance where the CL data records it (geometry/path_clearance.hpp).

#include "clearance_report.hpp"
#include "command.hpp"
#include "job/setup_flags.hpp"
#include "job/tool_spec.hpp"
#include "setup_flags.hpp"

#include "cl/cl_reader.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/path_clearance.hpp"
#include "geometry/path_verifier.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <fmt/format.h>

namespace subfeed::cli {

using namespace subfeed::job; // NOLINT: the front wires the job library

namespace {

struct VerifyCommandOptions {
  std::string cage;
  std::string cl;
  std::string tool;
  double scallop = 0.0;
  double spacing = 0.0;
  std::string svg;
  std::string png;
  int level = geometry::min_approx_level;
  SetupFlags setup;
  double max_tilt = 90.0;
};

// Where no ball came: the regions and their area, largest first.
void report_uncut(const std::vector<geometry::UncutRegion>& regions, Logger& log) {
  if (regions.empty()) {
    return;
  }
  double area = 0.0;
  for (const auto& r : regions) {
    area += r.area_mm2;
  }
  log.warning(
      fmt::format("  not cut: {:.1f} mm^2 in {} region(s) no ball reached", area, regions.size()));
  constexpr std::size_t shown = 8;
  for (std::size_t i = 0; i < std::min(shown, regions.size()); ++i) {
    const auto& r = regions[i];
    const Eigen::Vector3d size = r.high - r.low;
    log.warning(fmt::format("    near ({:.2f}, {:.2f}, {:.2f}) mm, over {:.2f} x {:.2f} x {:.2f} "
                            "mm: {:.1f} mm^2",
                            r.centroid.x(), r.centroid.y(), r.centroid.z(), size.x(), size.y(),
                            size.z(), r.area_mm2));
  }
  if (regions.size() > shown) {
    log.warning(fmt::format("    and {} smaller", regions.size() - shown));
  }
}

// The whole tool the CL data records (PPRINT TOOL and FIXTURE), measured over the path: each
// body's least clearance to the part and the floor. A broken rule is an error (exit 2),
// after the report.
Expected<void> report_whole_tool(const VerifyCommandOptions& o, const cl::ClHeader& header,
                                 const geometry::Cage& cage, const geometry::LimitSurface& surface,
                                 Logger& log) {
  SUBFEED_TRY_ASSIGN(const auto recorded, recorded_tool(header, o.cl));
  if (!recorded) {
    log.info("  whole tool: not recorded in the CL data (no PPRINT TOOL and FIXTURE): only the "
             "ball is measured");
    return {};
  }
  SUBFEED_TRY_ASSIGN(const auto c, geometry::path_clearance(cage, surface, o.cl, recorded->tool,
                                                            recorded->fixture));
  return report_clearance(c, recorded->tool, recorded->fixture, o.cl, log);
}

Expected<void> run_verify(const VerifyCommandOptions& o, Logger& log) {
  SUBFEED_TRY_ASSIGN(const double radius, parse_ball_tool(o.tool));
  SUBFEED_TRY_ASSIGN(const auto reader, cl::ClReader::open(o.cl));
  SUBFEED_TRY_ASSIGN(const auto cage,
                     read_part_agreed(o.cage, o.setup, reader.header().setup, o.cl));
  SUBFEED_TRY_ASSIGN(const auto surface, geometry::LimitSurface::build(cage, o.level));
  geometry::VerifyOptions options;
  options.ball_radius = radius;
  if (o.scallop > 0.0) {
    options.scallop_target = o.scallop;
  }
  options.sample_spacing = o.spacing;
  options.max_tilt_deg = o.max_tilt;
  const auto& records = reader.header().whole_tool;
  if (!records.fixture.empty()) {
    SUBFEED_TRY_ASSIGN(
        const auto fixture,
        parse_fixture_record(records.fixture, {o.cl, static_cast<int>(records.fixture_line), {}}));
    if (fixture.floor_z) {
      options.ball_floor_z = *fixture.floor_z - fixture.stock_margin;
    }
  }
  options.name = std::filesystem::path(o.cage).filename().string();
  if (!o.svg.empty()) {
    options.svg = o.svg;
  }
  if (!o.png.empty()) {
    options.png = o.png;
  }
  SUBFEED_TRY_ASSIGN(const auto r, geometry::verify_path(surface, o.cl, options));
  log.info(fmt::format("{} on {}: {} samples over {:.2f} mm^2 ({} not reached by the ball)", o.cl,
                       o.cage, r.samples, r.area, r.uncut_samples));
  if (r.out_of_reach_samples > 0) {
    log.info(fmt::format("  out of reach: {:.1f} mm^2 whose normals lean more than {:g} deg from "
                         "+Z ({} samples), not measured for scallop",
                         r.out_of_reach_area, r.reach_angle_deg, r.out_of_reach_samples));
  }
  if (r.below_floor_samples > 0) {
    log.info(fmt::format("  below the floor: {:.1f} mm^2 the ball would reach only under the "
                         "floor less the stock margin ({} samples), not measured for scallop",
                         r.below_floor_area, r.below_floor_samples));
  }
  report_uncut(r.uncut, log);
  log.info(fmt::format(
      "  scallop max {:.6f} mm (near {:.3f}, {:.3f}, {:.3f}), mean {:.6f} mm, 99th "
      "percentile {:.6f} mm",
      r.max_scallop, r.max_at.x(), r.max_at.y(), r.max_at.z(), r.mean_scallop, r.p99_scallop));
  log.info(fmt::format("  gouges {} samples deeper than 0.1 um, deepest {:.6f} mm{}", r.gouges,
                       r.max_gouge,
                       r.gouges > 0 ? fmt::format(" (near {:.3f}, {:.3f}, {:.3f})", r.gouge_at.x(),
                                                  r.gouge_at.y(), r.gouge_at.z())
                                    : std::string()));
  const auto touches = [](const char* what, const geometry::MoveTouches& t) {
    return t.samples == 0
               ? fmt::format("  {}: none reach into the part", what)
               : fmt::format("  {}: {} samples inside their sweep, deepest {:.6f} mm (near {:.3f}, "
                             "{:.3f}, {:.3f})",
                             what, t.samples, t.deepest, t.at.x(), t.at.y(), t.at.z());
  };
  log.info(touches("links (plunges and retracts)", r.links));
  log.info(touches("rapids", r.rapids));
  log.info(fmt::format("  path {:.1f} mm, cutting {:.1f} mm, {} passes, {} points; L* {:.1f} mm, "
                       "L/L* {:.3f}",
                       r.path_length, r.cutting_length, r.passes, r.points, r.ideal_length,
                       r.ideal_length > 0.0 ? r.cutting_length / r.ideal_length : 0.0));
  SUBFEED_TRY(report_whole_tool(o, reader.header(), cage, surface, log));
  // A rapid is not meant to touch the part at all; a micrometre is the CL data's rounding.
  if (r.rapids.deepest > 1e-3) {
    const auto& at = r.rapids.at;
    return fail(ErrorCode::bad_input,
                fmt::format("a rapid reaches {:.6f} mm into the part near ({:.3f}, {:.3f}, "
                            "{:.3f}): on a machine that is a crash",
                            r.rapids.deepest, at.x(), at.y(), at.z()),
                {o.cl, 0, {}});
  }
  for (const auto& picture : {o.svg, o.png}) {
    if (!picture.empty()) {
      log.info("  picture: " + picture +
               " (top view; scallop blue = 0 to red = max with its colour bar in mm, black = gouge "
               "over 1 um, white = passes; left uncut: dark grey = no ball came, light grey = "
               "over the tilt, tan = only under the floor; a scale bar in mm)");
    }
  }
  return {};
}

} // namespace

void add_verify_command(CLI::App& app, Action& chosen) {
  auto o = std::make_shared<VerifyCommandOptions>();
  CLI::App* cmd = app.add_subcommand("verify", "Measure the scallop and gouges a CL path leaves");
  cmd->add_option("cage", o->cage,
                  "Control cage (Wavefront OBJ; units and orientation: --units, --up)")
      ->required()
      ->type_name("CAGE.obj");
  cmd->add_option("cl", o->cl, "CL data")->required()->type_name("PART.cl");
  cmd->add_option("--tool", o->tool, "Cutter: ball:D (diameter D mm)")->required();
  cmd->add_option("--scallop", o->scallop,
                  "Target for the ideal length L* (default: the measured maximum)")
      ->check(CLI::Range(1e-6, 100.0));
  cmd->add_option("--spacing", o->spacing,
                  "Sample spacing on the surface, mm (default: ball radius / 30)")
      ->check(CLI::Range(1e-4, 100.0));
  cmd->add_option("--svg", o->svg, "Write a top view of the passes over a scallop heat map");
  cmd->add_option("--png", o->png, "Write the same picture as PNG");
  cmd->add_option("--level", o->level, "Bfr approximation level near irregular features")
      ->check(CLI::Range(geometry::min_approx_level, geometry::max_approx_level));
  cmd->add_option("--max-tilt", o->max_tilt,
                  "Largest tool tilt from vertical, degrees: steeper surface is out of reach and "
                  "not measured for scallop (a vertical tool: 90)")
      ->type_name("DEG")
      ->check(CLI::Range(0.0, 180.0));
  add_setup_flags(*cmd, o->setup);
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return run_verify(*o, log); }; });
}

} // namespace subfeed::cli

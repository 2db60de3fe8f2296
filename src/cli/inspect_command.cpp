// `subfeed inspect CAGE.obj`: validates a cage and reports its limit surface's extent and
// area, the first thing to look at before planning (does the stock fit, is the cage what
// the designer meant).

#include "command.hpp"
#include "setup_flags.hpp"

#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/part_setup.hpp"
#include "geometry/surface_summary.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace subfeed::cli {

namespace {

struct InspectOptions {
  std::string cage;
  int level = geometry::min_approx_level;
  int samples = 16;
  job::SetupFlags setup;
};

std::string_view boundary_name(geometry::BoundaryInterpolation b) {
  switch (b) {
  case geometry::BoundaryInterpolation::none:
    return "none (boundary faces are holes)";
  case geometry::BoundaryInterpolation::edge_only:
    return "edge only";
  case geometry::BoundaryInterpolation::edge_and_corner:
    return "edge and corner";
  }
  return "?";
}

Expected<void> inspect(const InspectOptions& options, Logger& log) {
  SUBFEED_TRY_ASSIGN(auto cage, geometry::read_obj(options.cage));
  const auto setup = options.setup.with_defaults();
  SUBFEED_TRY_ASSIGN(const auto placed, geometry::set_up_part(cage, setup));
  SUBFEED_TRY_ASSIGN(const auto surface, geometry::LimitSurface::build(cage, options.level));
  SUBFEED_TRY_ASSIGN(const auto s, geometry::summarize(cage, surface, options.samples));
  const auto& c = s.cage;
  log.info(fmt::format("cage {}: {} vertices, {} faces ({} quads), {} extraordinary vertices, "
                       "{} boundary edges, {} creases, {} corners, {} holes, boundary {}, "
                       "creasing {}, triangles {}",
                       options.cage, c.vertices, c.faces, c.quads, c.extraordinary_vertices,
                       c.boundary_edges, c.creases, c.corners, cage.holes.size(),
                       boundary_name(cage.boundary),
                       cage.creasing == geometry::CreasingMethod::chaikin ? "chaikin" : "normal",
                       cage.triangles == geometry::TriangleRule::smooth ? "smooth" : "catmark"));
  const auto& z = placed.zero_in_model;
  log.info(fmt::format("setup: {} (program zero at model point {:.4f}, {:.4f}, {:.4f} mm)",
                       geometry::describe_setup(setup), z.x(), z.y(), z.z()));
  log.info(fmt::format("limit surface: {} patches, area {:.3f} mm^2 (approximation level {}, "
                       "{} samples per face edge)",
                       s.patches, s.area, options.level, options.samples));
  for (int axis = 0; axis < 3; ++axis) {
    log.info(fmt::format("  {} {:10.4f} .. {:10.4f} mm  (size {:.4f} mm)", "XYZ"[axis], s.min[axis],
                         s.max[axis], s.max[axis] - s.min[axis]));
  }
  log.info(fmt::format("  steepest slope {:.1f} deg from horizontal (near {:.3f}, {:.3f}, {:.3f})",
                       s.steepest_deg, s.steepest_at.x(), s.steepest_at.y(), s.steepest_at.z()));
  return {};
}

} // namespace

void add_inspect_command(CLI::App& app, Action& chosen) {
  auto options = std::make_shared<InspectOptions>();
  CLI::App* cmd =
      app.add_subcommand("inspect", "Check a control cage and report its limit surface");
  cmd->add_option("cage", options->cage,
                  "Control cage (Wavefront OBJ; units and orientation: --units, --up)")
      ->required()
      ->type_name("CAGE.obj");
  cmd->add_option("--level", options->level, "Bfr approximation level near irregular features")
      ->check(CLI::Range(geometry::min_approx_level, geometry::max_approx_level));
  cmd->add_option("--samples", options->samples, "Samples per face edge for extent and area")
      ->check(CLI::Range(1, 256));
  add_setup_flags(*cmd, options->setup);
  cmd->callback(
      [&chosen, options] { chosen = [options](Logger& log) { return inspect(*options, log); }; });
}

} // namespace subfeed::cli

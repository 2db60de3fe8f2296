#include "job/cl_gate.hpp"

#include "geometry/limit_surface.hpp"
#include "job/tool_spec.hpp"

#include <cmath>
#include <fmt/format.h>

namespace subfeed::job {

Expected<geometry::MotionGate> gate_for_cl(const std::filesystem::path& cage_path,
                                           const cl::ClHeader& header, const std::string& cl_file,
                                           const SetupFlags& setup, int level,
                                           double tolerance_mm) {
  const auto& cutter = header.cutter;
  if (!(cutter.diameter > 0.0) || std::abs(cutter.corner_radius - cutter.diameter / 2) > 1e-9) {
    return fail(ErrorCode::bad_input,
                fmt::format("CUTTER/{:g},{:g}: the motion gate checks ball-end cutters only "
                            "(corner radius half the diameter)",
                            cutter.diameter, cutter.corner_radius),
                {});
  }
  SUBFEED_TRY_ASSIGN(auto cage, read_part_agreed(cage_path, setup, header.setup, cl_file));
  SUBFEED_TRY_ASSIGN(auto surface, geometry::LimitSurface::build(cage, level));
  geometry::GateOptions options{cutter.diameter / 2,
                                tolerance_mm > 0.0 ? tolerance_mm
                                                   : geometry::default_gate_tolerance,
                                false,
                                {},
                                {}};
  // The whole tool and the fixture, where the CL data records what it was planned for.
  SUBFEED_TRY_ASSIGN(const auto recorded, recorded_tool(header, cl_file));
  if (recorded) {
    options.whole_tool = true;
    options.tool = recorded->tool;
    options.fixture = recorded->fixture;
  }
  return geometry::MotionGate::build(cage, surface, options);
}

} // namespace subfeed::job

#include "job/cl_gate.hpp"

#include "geometry/limit_surface.hpp"

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
  return geometry::MotionGate::build(
      cage, surface,
      {cutter.diameter / 2, tolerance_mm > 0.0 ? tolerance_mm : geometry::default_gate_tolerance});
}

} // namespace subfeed::job

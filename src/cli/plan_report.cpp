#include "plan_report.hpp"

#include <cmath>
#include <fmt/format.h>

namespace subfeed::cli {

namespace {

// Rounded to the hundredth shown, and never "-0.00".
double shown_mm(double v) {
  return std::round(v * 100.0) / 100.0 + 0.0;
}

} // namespace

void report_unreachable(const geometry::PlanSummary& s, Logger& log) {
  if (s.unreachable_vertices == 0 && s.lifted_points == 0) {
    return;
  }
  log.warning(fmt::format("  the ball cannot reach {} surface vertices (hollows narrower than "
                          "the ball); {} CL points lifted clear there, leaving material",
                          s.unreachable_vertices, s.lifted_points));
  constexpr std::size_t shown = 8;
  const auto& regions = s.unreachable_regions;
  for (std::size_t i = 0; i < std::min(shown, regions.size()); ++i) {
    const auto& r = regions[i];
    const Eigen::Vector3d size = r.high - r.low;
    log.warning(
        fmt::format("    near ({:.2f}, {:.2f}, {:.2f}) mm: {} vertices over {:.2f} x {:.2f} "
                    "x {:.2f} mm",
                    shown_mm(r.centroid.x()), shown_mm(r.centroid.y()), shown_mm(r.centroid.z()),
                    r.vertices, size.x(), size.y(), size.z()));
  }
  if (regions.size() > shown) {
    log.warning(fmt::format("    and {} smaller regions", regions.size() - shown));
  }
}

std::string gate_summary(const geometry::GateReport& gate) {
  return fmt::format("  motion gate: {} moves ({} rapids) checked against the part (its mesh "
                     "within {:g} um): no cut deeper than {:g} um, no rapid touching it",
                     gate.moves, gate.rapids, gate.chord * 1000.0, gate.tolerance * 1000.0);
}

Error at_refused_pose(Error error, const geometry::ToolpathPlanner& planner,
                      const cl::ClWriter& writer, const std::filesystem::path& cl) {
  if (const auto& pose = planner.rejected()) {
    error.where.file = cl.string();
    error.where.line = static_cast<int>(writer.line_of(*pose));
    error.message += "; nothing written";
  }
  return error;
}

} // namespace subfeed::cli

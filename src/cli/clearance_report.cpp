#include "clearance_report.hpp"

#include <cmath>
#include <fmt/format.h>

namespace subfeed::cli {

namespace {

std::string clearance_point_text(const Eigen::Vector3d& p) {
  return fmt::format("({:.3f}, {:.3f}, {:.3f})", p.x(), p.y(), p.z());
}

std::string body_text(const geometry::BodyClearance& b, double searched_mm) {
  const std::string part = b.body == "ball" ? "cuts the part"
                           : std::isfinite(b.to_part)
                               ? fmt::format("{:.3f} mm from the part near {}", b.to_part,
                                             clearance_point_text(b.part_point))
                               : fmt::format("more than {:g} mm from the part", searched_mm);
  const std::string floor = std::isfinite(b.to_floor)
                                ? fmt::format("lowest {:.3f} mm above the floor (tip at {})",
                                              b.to_floor, clearance_point_text(b.floor_tip))
                                : std::string("no floor");
  return fmt::format("    {}: {}, {}", b.body, part, floor);
}

} // namespace

Expected<void> report_clearance(const geometry::PathClearance& c,
                                const geometry::ToolAssembly& tool,
                                const geometry::Fixture& fixture, const std::string& file,
                                job::Logger& log) {
  log.info(fmt::format("  whole tool: {}; floor {}, stock {:g} mm below it, clearance {:g} mm; "
                       "{} moves swept",
                       tool.text(),
                       fixture.floor_z ? fmt::format("z {:.3f} mm", *fixture.floor_z) : "none",
                       fixture.stock_margin, fixture.clearance_min, c.moves));
  for (const auto& b : c.bodies) {
    log.info(body_text(b, c.searched_mm));
  }
  if (c.first) {
    const auto& v = *c.first;
    return fail(ErrorCode::bad_input,
                fmt::format("the tool collides: {} measured poses break the fixture's rules, the "
                            "first in the move to line {}: the {} {} {:.4f} mm at {}",
                            c.broken, c.first_line, v.body,
                            v.floor ? "goes below its floor limit by" : "comes within", v.distance,
                            clearance_point_text(v.where)),
                {file, static_cast<int>(c.first_line), {}});
  }
  return {};
}

} // namespace subfeed::cli

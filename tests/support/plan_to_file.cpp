#include "support/plan_to_file.hpp"

#include "cl/cl_writer.hpp"

#include <catch2/catch.hpp>

namespace subfeed::testing {

PlannedPath plan_and_verify(const geometry::Cage& cage, const geometry::LimitSurface& surface,
                            const geometry::PlanOptions& plan,
                            const geometry::VerifyOptions& verify,
                            const std::filesystem::path& file) {
  auto planner = geometry::ToolpathPlanner::prepare(cage, surface, plan);
  REQUIRE(planner);
  auto writer =
      cl::ClWriter::create(file, {"PART", {2 * plan.ball_radius, plan.ball_radius}, true, {}, {}});
  REQUIRE(writer);
  REQUIRE(planner->run([&](const cl::ClPose& p) -> Expected<void> {
    writer->write(p);
    return {};
  }));
  REQUIRE(writer->finish());
  auto report = geometry::verify_path(surface, file, verify);
  REQUIRE(report);
  return {planner->summary(), *report};
}

geometry::PlanSummary plan_only(const geometry::Cage& cage, const geometry::LimitSurface& surface,
                                const geometry::PlanOptions& plan) {
  auto planner = geometry::ToolpathPlanner::prepare(cage, surface, plan);
  REQUIRE(planner);
  REQUIRE(planner->run([](const cl::ClPose&) -> Expected<void> { return {}; }));
  return planner->summary();
}

} // namespace subfeed::testing

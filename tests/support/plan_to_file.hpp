#pragma once
// Plans a cage into a CL file and measures it with the independent meter: what the geometry
// tests do to check a whole plan.

#include "geometry/path_verifier.hpp"
#include "geometry/toolpath_planner.hpp"

#include <filesystem>

namespace subfeed::testing {

struct PlannedPath {
  geometry::PlanSummary plan;
  geometry::VerifyReport report;
};

// Fails the running test (REQUIRE) if planning, writing or measuring fails.
[[nodiscard]] PlannedPath plan_and_verify(const geometry::Cage& cage,
                                          const geometry::LimitSurface& surface,
                                          const geometry::PlanOptions& plan,
                                          const geometry::VerifyOptions& verify,
                                          const std::filesystem::path& file);

// The plan's summary alone, nothing written (REQUIRE as above).
[[nodiscard]] geometry::PlanSummary plan_only(const geometry::Cage& cage,
                                              const geometry::LimitSurface& surface,
                                              const geometry::PlanOptions& plan);

} // namespace subfeed::testing

#pragma once
// What a plan tells the user beyond its totals: where the ball cannot reach, so that
// material will be left there (plan and run both say it).

#include "geometry/toolpath_planner.hpp"
#include "logger.hpp"

namespace subfeed::cli {

// Warns, with the regions located (largest first), when the ball cannot reach some of the
// surface or CL points were lifted clear of hollows; says nothing otherwise.
void report_unreachable(const geometry::PlanSummary& summary, Logger& log);

} // namespace subfeed::cli

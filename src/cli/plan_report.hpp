#pragma once
// What a plan tells the user beyond its totals: where the ball cannot reach, so that
// material will be left there, and what the motion gate checked or refused (plan and run
// both say it).

#include "cl/cl_writer.hpp"
#include "geometry/toolpath_planner.hpp"
#include "logger.hpp"

#include <filesystem>

namespace subfeed::cli {

// Warns, with the regions located (largest first), when the ball cannot reach some of the
// surface or CL points were lifted clear of hollows; says nothing otherwise.
void report_unreachable(const geometry::PlanSummary& summary, Logger& log);

// The motion gate's line of the summary: how many moves it checked, and against what.
[[nodiscard]] std::string gate_summary(const geometry::GateReport& gate);

// A refusal by the motion gate named by the CL line the refused pose would have had in
// `cl` (which is not written); any other error as it is.
[[nodiscard]] Error at_refused_pose(Error error, const geometry::ToolpathPlanner& planner,
                                    const cl::ClWriter& writer, const std::filesystem::path& cl);

} // namespace subfeed::cli

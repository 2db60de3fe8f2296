#pragma once
// What a plan tells the user beyond its totals: where the ball cannot reach, so that
// material will be left there, and what the motion gate checked or refused (plan and run
// both say it).

#include "cl/cl_writer.hpp"
#include "geometry/toolpath_planner.hpp"
#include "logger.hpp"

#include <filesystem>

namespace subfeed::cli {

// Where the ball leaves material thicker than the scallop height H (hollows narrower than
// the ball, CL points lifted clear of the part): a warning locating each place, thickest
// first. Otherwise one line saying none, with what stays under H.
void report_left_material(const geometry::PlanSummary& summary, Logger& log);

// The motion gate's line of the summary: how many moves it checked, and against what.
[[nodiscard]] std::string gate_summary(const geometry::GateReport& gate);

// A refusal by the motion gate named by the CL line the refused pose would have had in
// `cl` (which is not written); any other error as it is.
[[nodiscard]] Error at_refused_pose(Error error, const geometry::ToolpathPlanner& planner,
                                    const cl::ClWriter& writer, const std::filesystem::path& cl);

} // namespace subfeed::cli

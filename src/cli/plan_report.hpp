#pragma once
// What a plan tells the user beyond its totals: where the ball cannot reach, so that
// material will be left there, what the motion gate checked and where the time went (plan and run
// both say it).

#include "geometry/toolpath_planner.hpp"
#include "job/logger.hpp"

#include <string>

namespace subfeed::cli {

using job::Logger;

// Where the ball leaves material thicker than the scallop height H (hollows narrower than
// the ball, CL points lifted clear of the part): a warning locating each place, thickest
// first. Otherwise one line saying none, with what stays under H.
// (First, report_out_of_reach.)
void report_left_material(const geometry::PlanSummary& summary, Logger& log);

// What the tool cannot get to and so is never cut (too steep for the tilt, hidden under
// the part): a warning with the area and each region, largest first; else one line.
void report_out_of_reach(const geometry::PlanSummary& summary, Logger& log);

// Where the plan's time went, stage by stage ("time: meshing 0.41 s, ..."): for --verbose.
[[nodiscard]] std::string time_summary(const geometry::PlanTimes& times, int solves);

// The tool and fixture the plan kept clear, and where it turned the axis for them.
[[nodiscard]] std::string tool_summary(const geometry::ToolAssembly& tool,
                                       const geometry::PlanSummary& summary);

// The motion gate's line of the summary: how many moves it checked, and against what.
[[nodiscard]] std::string gate_summary(const geometry::GateReport& gate);
// The same gate on the posted program's blocks, as the machine moves (job/block_gate.hpp).
[[nodiscard]] std::string posted_gate_summary(const geometry::GateReport& gate);
// The tool axis along the passes: how far it turns between poses, and the lead and tilt
// kept; empty for a vertical tool.
[[nodiscard]] std::string axis_summary(const geometry::PlanOptions& options,
                                       const geometry::PlanSummary& s);

} // namespace subfeed::cli

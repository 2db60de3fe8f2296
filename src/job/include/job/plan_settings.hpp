#pragma once
// The planning settings `plan` and `run` share (tool, scallop, direction, axis, feeds, ...),
// as the user gives them and as a job record keeps them, and how they become the planner's
// geometry::PlanOptions.

#include "base/error.hpp"
#include "geometry/toolpath_planner.hpp"

#include <string>
#include <vector>

namespace subfeed::job {

struct PlanSettings {
  std::string tool; // "ball:D", or a tool's name in the tool table (job/tool_spec.hpp)
  // Where a tool's name is looked up. Not recorded: a job keeps the sizes it resolved to.
  std::string tool_table = "configs/tools.toml";
  double scallop = 0.0;
  std::string direction; // empty: along x, or rings where parallel passes fight the part
  bool baseline = false;
  double axis_radius = 0.0;
  std::string axis = "normal";
  bool one_way = false;
  double feed = 1000.0;
  double plunge_feed = 300.0;
  double clearance = 2.0;
  double stay_down = -1.0; // mm; 0: every link retracts; < 0: the ball's diameter
  double tolerance = 0.0;
  double mesh_chord = 0.0; // mm; 0: the planner's default
  // mm: the motion gate's deepest allowed cut; 0: the planner's default
  double gate_tolerance = 0.0;
  int level = geometry::min_approx_level;
  int refine = 60;
  // The tool axis's largest angle from +Z, degrees; < 0: the machine's tilt range when a
  // machine is known (run), else 90.
  double max_tilt = -1.0;
  // Degrees from the feed direction (geometry/axis_lean.hpp): lead > 0 leans the tool's
  // top ahead, tilt > 0 to the left.
  double lead = 0.0;
  double tilt = 0.0;
  // The tool above the ball (job/tool_spec.hpp): 0 or empty where not given.
  double flute = 0.0;              // mm from the tip
  double shank = 0.0;              // mm, diameter
  double stickout = 0.0;           // mm from the tip to the holder's face
  std::vector<std::string> holder; // "D:L" or "D1:D2:L" per stage, bottom first
  // The fixture: "none", a z in mm, or empty for the part's lowest point.
  std::string floor;
  double stock_margin = 0.0;                              // mm
  double clearance_min = geometry::default_clearance_min; // mm
  // False only for jobs recorded before the whole tool was checked: they re-plan as they
  // were planned, the ball alone and no floor.
  bool whole_tool = true;
};

// Checks what option parsing cannot (the scallop against the tool, the direction) and fills
// the planner's options.
[[nodiscard]] Expected<geometry::PlanOptions> plan_options_from(const PlanSettings& settings);

} // namespace subfeed::job

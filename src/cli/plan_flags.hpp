#pragma once
// The planning flags `plan` and `run` share (tool, scallop, direction, axis, feeds, ...),
// registered on a subcommand and turned into geometry::PlanOptions.

#include "base/error.hpp"
#include "geometry/toolpath_planner.hpp"

#include <string>

namespace CLI {
class App;
}

namespace subfeed::cli {

struct PlanFlags {
  std::string tool;
  double scallop = 0.0;
  std::string direction = "x";
  bool baseline = false;
  double axis_radius = 0.0;
  std::string axis = "normal";
  bool one_way = false;
  double feed = 1000.0;
  double plunge_feed = 300.0;
  double clearance = 2.0;
  double stay_down = -1.0; // mm; 0: every link retracts; < 0: the ball's diameter
  double tolerance = 0.0;
  // mm: the motion gate's deepest allowed cut; 0: the planner's default
  double gate_tolerance = 0.0;
  int level = geometry::min_approx_level;
  int refine = 60;
};

// `required`: --tool and --scallop must be given (run checks them itself: CL input has none).
void add_plan_flags(CLI::App& cmd, PlanFlags& flags, bool required = true);
// --gate-tolerance, which `post --cage` takes too.
void add_gate_tolerance_flag(CLI::App& cmd, double& tolerance_mm);
// Checks what CLI11 cannot (the scallop against the tool) and fills the planner's options.
[[nodiscard]] Expected<geometry::PlanOptions> plan_options_from(const PlanFlags& flags);

} // namespace subfeed::cli

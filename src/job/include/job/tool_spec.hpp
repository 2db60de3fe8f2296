#pragma once
// The tool and fixture on the command line and in CL headers:
//  - `--tool ball:D` a ball-end mill of diameter D mm, with `--flute L`, `--shank D`,
//    `--stickout L` and `--holder D:L` or `--holder D1:D2:L` (a cone, D1 at the bottom)
//    per stage, bottom first; defaults flute 3D, shank D, stick-out 4D (or the flutes),
//    no holder;
//  - `--floor Z|none`, `--stock-margin MM`, `--clearance-min MM`.
// A CL file keeps both as `PPRINT TOOL ...` and `PPRINT FIXTURE ...` records, so a gate
// built later holds the path to what it was planned for.

#include "base/error.hpp"
#include "cl/cl_pose.hpp"
#include "geometry/assembly_clearance.hpp"
#include "geometry/tool_assembly.hpp"
#include "geometry/toolpath_planner.hpp"
#include "job/plan_settings.hpp"

#include <optional>
#include <string>
#include <string_view>

namespace subfeed::job {

// `--tool NAME`: the tool of that name in the settings' tool table (post/tool_table.hpp)
// becomes "ball:D" and the flute, shank, stick-out and holder the command line left unset;
// the command line's own win. Returns the table's file when it looked a name up, nothing
// when the tool was spelt out (ball:D, anything with a colon) or not given.
[[nodiscard]] Expected<std::optional<std::string>> resolve_tool_name(PlanSettings& settings);

// Ball radius in mm from "ball:D"; an error naming --tool otherwise.
[[nodiscard]] Expected<double> parse_ball_tool(const std::string& spec);

// The assembly from --tool, --flute, --shank, --stickout and --holder.
[[nodiscard]] Expected<geometry::ToolAssembly> tool_assembly_from(const PlanSettings& settings);

// The fixture from --floor, --stock-margin and --clearance-min; floor_z is left empty for
// the part's lowest point when `floor_at_lowest` comes back true.
struct FixtureChoice {
  geometry::Fixture fixture;
  bool floor_at_lowest = false;
};
[[nodiscard]] Expected<FixtureChoice> fixture_from(const PlanSettings& settings);

// "flute=18 shank=6 stickout=24 holder=32:40,20:10:30", and back (with the ball's radius
// from the CUTTER record); errors name `where`.
[[nodiscard]] std::string tool_record(const geometry::ToolAssembly& tool);
[[nodiscard]] Expected<geometry::ToolAssembly>
parse_tool_record(double ball_radius, std::string_view text, const Where& where);

// "floor=-1.25 margin=0 clearance=0.5" ("floor=none" without one), and back.
[[nodiscard]] std::string fixture_record(const geometry::Fixture& fixture);
[[nodiscard]] Expected<geometry::Fixture> parse_fixture_record(std::string_view text,
                                                               const Where& where);

// The tool and fixture a CL header records (the ball from its CUTTER), or nothing when it
// records neither; errors name the record's line in `cl_file`.
struct RecordedTool {
  geometry::ToolAssembly tool;
  geometry::Fixture fixture;
};
[[nodiscard]] Expected<std::optional<RecordedTool>> recorded_tool(const cl::ClHeader& header,
                                                                  const std::string& cl_file);

// The TOOL and FIXTURE records of a path planned with `options` (the fixture as the
// planner settled it: `summary`), into `header`; nothing for a plan of the ball alone.
void record_tool(cl::ClHeader& header, const geometry::PlanOptions& options,
                 const geometry::PlanSummary& summary);

} // namespace subfeed::job

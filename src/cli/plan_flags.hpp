#pragma once
// The planning flags `plan` and `run` share, registered on a subcommand.

#include "base/error.hpp"
#include "job/plan_settings.hpp"

namespace subfeed::job {
class Logger;
}

namespace CLI {
class App;
}

namespace subfeed::cli {

// `required`: --tool and --scallop must be given (run checks them itself: CL input has none).
void add_plan_flags(CLI::App& cmd, job::PlanSettings& flags, bool required = true);
// The tool and the fixture alone: --tool, --tools, --flute, --shank, --stickout, --holder,
// --floor, --stock-margin, --clearance-min (part of the above; `check --cage` takes them).
void add_tool_flags(CLI::App& cmd, job::PlanSettings& flags, bool required);
// `--tool NAME` looked up in the tool table (job/tool_spec.hpp), and said where from.
[[nodiscard]] Expected<void> resolve_tool(job::PlanSettings& settings, job::Logger& log);
// --gate-tolerance, which `post --cage` takes too.
void add_gate_tolerance_flag(CLI::App& cmd, double& tolerance_mm);

} // namespace subfeed::cli

#pragma once
// The planning flags `plan` and `run` share, registered on a subcommand.

#include "job/plan_settings.hpp"

namespace CLI {
class App;
}

namespace subfeed::cli {

// `required`: --tool and --scallop must be given (run checks them itself: CL input has none).
void add_plan_flags(CLI::App& cmd, job::PlanSettings& flags, bool required = true);
// --gate-tolerance, which `post --cage` takes too.
void add_gate_tolerance_flag(CLI::App& cmd, double& tolerance_mm);

} // namespace subfeed::cli

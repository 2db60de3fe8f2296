#pragma once
// The verdict on a dry run against a simulated controller: did the machine execute exactly
// the program that was posted (every block once, in order: count and FNV-1a hash of what
// the simulator ran against the program file), and does that program, replayed through the
// machine's forward kinematics, keep the tool tip on the CL path and the joints inside
// their limits without rotary jumps (post::check_program).

#include "base/error.hpp"
#include "job/controller_link.hpp"
#include "job/logger.hpp"

#include <filesystem>

namespace subfeed::job {

struct DryRunFiles {
  std::filesystem::path cl, nc;
};

// An error (non-zero exit) when delivery or the replay fails; the report is logged either way.
[[nodiscard]] Expected<void> verify_dry_run(const Link& link, const DryRunFiles& files,
                                            const post::MachineConfig& machine, double tolerance_mm,
                                            Logger& log);

} // namespace subfeed::job

#pragma once
// --up, --units, --scale and --origin: how the part sits on the machine, the same flags on
// every command that reads a cage, CL data or a job.

#include "job/setup_flags.hpp"

namespace CLI {
class App;
}

namespace subfeed::cli {

void add_setup_flags(CLI::App& cmd, job::SetupFlags& flags);

} // namespace subfeed::cli

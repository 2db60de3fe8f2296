#pragma once
// The whole tool's clearance over a path (geometry/path_clearance.hpp), as `verify` and
// `check --cage` print it: the tool and fixture, one line per body with its least clearance
// to the part and to the floor and where, and an error (exit 2) naming the line of the
// first move that breaks a rule, after the report.

#include "base/error.hpp"
#include "geometry/path_clearance.hpp"
#include "geometry/tool_assembly.hpp"
#include "job/logger.hpp"

#include <string>

namespace subfeed::cli {

// `file` holds the moves the lines count (CL data or a program).
[[nodiscard]] Expected<void> report_clearance(const geometry::PathClearance& clearance,
                                              const geometry::ToolAssembly& tool,
                                              const geometry::Fixture& fixture,
                                              const std::string& file, job::Logger& log);

} // namespace subfeed::cli

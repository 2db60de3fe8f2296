#pragma once
// The cutter on the command line: `ball:D`, a ball-end mill of diameter D mm.

#include "base/error.hpp"

#include <string>

namespace subfeed::job {

// Ball radius in mm from "ball:D"; an error naming --tool otherwise.
[[nodiscard]] Expected<double> parse_ball_tool(const std::string& spec);

} // namespace subfeed::job

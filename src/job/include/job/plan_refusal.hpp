#pragma once
// A plan refused by the motion gate writes no CL file, but its error names the CL line the
// refused pose would have had, so that plan, run and a rerun of either point at one place.

#include "base/error.hpp"
#include "cl/cl_writer.hpp"
#include "geometry/toolpath_planner.hpp"

#include <filesystem>

namespace subfeed::job {

// The planner's refusal named by its line in `cl` (which is not written), with "; nothing
// written"; any other error as it is.
[[nodiscard]] Error at_refused_pose(Error error, const geometry::ToolpathPlanner& planner,
                                    const cl::ClWriter& writer, const std::filesystem::path& cl);

} // namespace subfeed::job

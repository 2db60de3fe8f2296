#include "job/plan_refusal.hpp"

namespace subfeed::job {

Error at_refused_pose(Error error, const geometry::ToolpathPlanner& planner,
                      const cl::ClWriter& writer, const std::filesystem::path& cl) {
  if (const auto& pose = planner.rejected()) {
    error.where.file = cl.string();
    error.where.line = static_cast<int>(writer.line_of(*pose));
    error.message += "; nothing written";
  }
  return error;
}

} // namespace subfeed::job

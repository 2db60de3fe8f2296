#include "job/tool_spec.hpp"

#include "base/number_text.hpp"

#include <charconv>
#include <cmath>

namespace subfeed::job {

Expected<double> parse_ball_tool(const std::string& spec) {
  const std::string prefix = "ball:";
  if (spec.starts_with(prefix)) {
    const auto diameter = parse_double(std::string_view(spec).substr(prefix.size()));
    if (diameter && *diameter > 0.0 && *diameter <= 100.0) {
      return *diameter / 2.0;
    }
  }
  return fail(ErrorCode::usage,
              "'" + spec + "': expected ball:D, a ball-end mill of diameter D mm (0 < D <= 100)",
              {{}, 0, "--tool"});
}

} // namespace subfeed::job

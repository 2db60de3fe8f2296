#include "tool_spec.hpp"

#include <charconv>
#include <cmath>

namespace subfeed::cli {

Expected<double> parse_ball_tool(const std::string& spec) {
  const std::string prefix = "ball:";
  double diameter = 0.0;
  if (spec.starts_with(prefix)) {
    const char* begin = spec.data() + prefix.size();
    const char* end = spec.data() + spec.size();
    const auto [ptr, ec] = std::from_chars(begin, end, diameter);
    if (ec == std::errc{} && ptr == end && std::isfinite(diameter) && diameter > 0.0 &&
        diameter <= 100.0) {
      return diameter / 2.0;
    }
  }
  return fail(ErrorCode::usage,
              "'" + spec + "': expected ball:D, a ball-end mill of diameter D mm (0 < D <= 100)",
              {{}, 0, "--tool"});
}

} // namespace subfeed::cli

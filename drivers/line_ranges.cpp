#include "drivers/line_ranges.hpp"

#include <algorithm>

namespace subfeed::drivers {

std::string describe_lines(std::vector<long> lines) {
  std::ranges::sort(lines);
  const auto [first, last] = std::ranges::unique(lines);
  lines.erase(first, last);
  if (lines.empty()) {
    return "";
  }
  std::string text = lines.size() == 1 ? "line " : "lines ";
  for (std::size_t i = 0; i < lines.size();) {
    std::size_t j = i;
    while (j + 1 < lines.size() && lines[j + 1] == lines[j] + 1) {
      ++j;
    }
    text += (i == 0 ? "" : ", ") + std::to_string(lines[i]);
    if (j > i) {
      text += "-" + std::to_string(lines[j]);
    }
    i = j + 1;
  }
  return text;
}

} // namespace subfeed::drivers

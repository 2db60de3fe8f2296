#include "progress_text.hpp"

#include <algorithm>
#include <fmt/format.h>

namespace subfeed::cli {

std::string clock_text(double seconds) {
  const auto s = static_cast<long>(seconds + 0.5);
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
                   : fmt::format("{:02}:{:02}", s / 60, s % 60);
}

std::string progress_bar(double fraction) {
  constexpr int width = 20;
  const int filled = std::clamp(static_cast<int>(fraction * width + 0.5), 0, width);
  return "[" + std::string(static_cast<std::size_t>(filled), '#') +
         std::string(static_cast<std::size_t>(width - filled), '.') + "]";
}

std::string eta_text(double spent, double done) {
  return done > 0.02 ? clock_text(spent * (1.0 - std::min(done, 1.0)) / done) : "--:--";
}

} // namespace subfeed::cli

#include "support/output_lines.hpp"

#include <regex>

namespace subfeed::testing {

std::vector<std::string> split_lines(std::string_view text) {
  std::vector<std::string> lines;
  while (!text.empty()) {
    const auto end = text.find('\n');
    lines.emplace_back(text.substr(0, end));
    text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
  }
  return lines;
}

bool has_line(std::string_view text, std::string_view line) {
  for (const auto& l : split_lines(text)) {
    if (l == line) {
      return true;
    }
  }
  return false;
}

bool has_line_matching(std::string_view text, const std::string& pattern) {
  const std::regex re(pattern);
  for (const auto& l : split_lines(text)) {
    if (std::regex_match(l, re)) {
      return true;
    }
  }
  return false;
}

std::vector<std::string> line_captures(std::string_view text, const std::string& pattern) {
  const std::regex re(pattern);
  for (const auto& l : split_lines(text)) {
    std::smatch m;
    if (std::regex_match(l, m, re)) {
      return {m.begin(), m.end()};
    }
  }
  return {};
}

std::string literal(std::string_view text) {
  static constexpr std::string_view special = R"(\^$.|?*+()[]{}/)";
  std::string out;
  for (const char c : text) {
    if (special.find(c) != std::string_view::npos) {
      out += '\\';
    }
    out += c;
  }
  return out;
}

} // namespace subfeed::testing

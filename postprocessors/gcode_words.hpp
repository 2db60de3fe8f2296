#pragma once
// Splits one line of G-code into letter/value words for the checker: comments in
// parentheses or after ';', '%' lines and spaces dropped. Internal to the postprocessors.

#include "base/error.hpp"

#include <string_view>
#include <vector>

namespace subfeed::post {

struct GcodeWord {
  char letter = 0;
  double value = 0.0;
};

// Error (message only; the caller adds file and line) on a letter without a number, a
// number without a letter, or an unclosed comment.
[[nodiscard]] Expected<std::vector<GcodeWord>> split_words(std::string_view line);

} // namespace subfeed::post

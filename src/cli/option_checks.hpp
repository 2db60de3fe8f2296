#pragma once
// CLI11 checks whose refusals read as one plain sentence ("'-3' is not a number above 0"),
// where CLI11's own PositiveNumber prints its range up to 1.8e308.

#include "base/number_text.hpp"

#include <CLI/CLI.hpp>

namespace subfeed::cli {

inline CLI::Validator positive_number() {
  return {[](std::string& text) { return positive_number_problem(text, false); }, "> 0"};
}

inline CLI::Validator non_negative_number() {
  return {[](std::string& text) { return positive_number_problem(text, true); }, ">= 0"};
}

} // namespace subfeed::cli

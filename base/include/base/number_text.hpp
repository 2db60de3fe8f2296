#pragma once
// Numbers read from text the same way in every locale. std::stod, strtod and atof follow
// LC_NUMERIC: under a comma-decimal locale "1.5" reads as 1 and stops at the point, so a
// feed, a coordinate or a crease sharpness would silently change with the machine's
// language. These read with std::from_chars, which never looks at the locale.
//
// Whole-text readers: the text must be the number and nothing else (no blanks, no trailing
// characters); one leading '+' is taken, as people type it; a value out of the type's range,
// infinities and NaN are refused (nullopt). Prefix readers take the longest number at the
// start of the text, for G-code words and lists, and say how many characters it used.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace subfeed {

[[nodiscard]] std::optional<double> parse_double(std::string_view text);
[[nodiscard]] std::optional<long> parse_long(std::string_view text);
[[nodiscard]] std::optional<int> parse_int(std::string_view text);

// For a command line's checks: "" when `text` is a number above 0 (at or above 0 with
// `zero_ok`), else what is wrong with it, as an error message says it.
[[nodiscard]] std::string positive_number_problem(std::string_view text, bool zero_ok);

struct PrefixNumber {
  double value = 0.0;
  std::size_t used = 0; // characters of the text that made the number
};
// The decimal number `text` starts with ("-12.5X3" gives -12.5, 5 used); nullopt if none.
[[nodiscard]] std::optional<PrefixNumber> parse_double_prefix(std::string_view text);

} // namespace subfeed

#include "base/number_text.hpp"

#include <charconv>
#include <cmath>
#include <limits>

namespace subfeed {

namespace {

// One leading '+' before a digit or a point; from_chars takes only '-'.
std::string_view without_plus(std::string_view text) {
  if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') {
    text.remove_prefix(1);
  }
  return text;
}

template <typename T> std::optional<T> parse_whole(std::string_view text) {
  text = without_plus(text);
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size()) {
    return std::nullopt;
  }
  return value;
}

} // namespace

std::optional<double> parse_double(std::string_view text) {
  const auto value = parse_whole<double>(text);
  if (!value || !std::isfinite(*value)) {
    return std::nullopt;
  }
  return value;
}

std::optional<long> parse_long(std::string_view text) {
  return parse_whole<long>(text);
}

std::optional<int> parse_int(std::string_view text) {
  return parse_whole<int>(text);
}

std::string positive_number_problem(std::string_view text, bool zero_ok) {
  const auto value = parse_double(text);
  if (value && (*value > 0.0 || (zero_ok && *value == 0.0))) {
    return "";
  }
  return "'" + std::string(text) + "' is not a number " + (zero_ok ? "0 or above" : "above 0");
}

std::optional<PrefixNumber> parse_double_prefix(std::string_view text) {
  const std::string_view digits = without_plus(text);
  const std::size_t skipped = text.size() - digits.size();
  // from_chars would take "inf", "nan" and exponents ("1E5"); a G-code word is plain digits,
  // a sign and a point, and "X1E5" is not a coordinate of 100000.
  std::size_t n = 0;
  if (n < digits.size() && digits[n] == '-') {
    ++n;
  }
  const std::size_t first_digit = n;
  bool point = false;
  while (n < digits.size() &&
         ((digits[n] >= '0' && digits[n] <= '9') || (digits[n] == '.' && !point))) {
    point = point || digits[n] == '.';
    ++n;
  }
  const std::string_view number = digits.substr(0, n);
  if (n == first_digit || number.substr(first_digit) == ".") {
    return std::nullopt;
  }
  double value = 0.0;
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
  if (ec != std::errc{} || end != number.data() + number.size()) {
    return std::nullopt;
  }
  return PrefixNumber{value, skipped + n};
}

} // namespace subfeed

#include "base/decimal_text.hpp"

#include <charconv>
#include <cmath>

namespace subfeed {

void append_fixed(std::string& out, double value, int decimals) {
  const double scale = std::pow(10.0, decimals);
  if (std::abs(std::round(value * scale)) == 0.0) {
    value = 0.0; // no "-0.000"
  }
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  out.append(buffer, result.ptr);
}

void append_decimal(std::string& out, double value, int decimals) {
  append_fixed(out, value, decimals);
  if (decimals == 0) {
    out.push_back('.');
    return;
  }
  while (out.back() == '0') {
    out.pop_back();
  }
}

} // namespace subfeed

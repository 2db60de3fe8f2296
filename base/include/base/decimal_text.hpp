#pragma once
// Locale-independent decimal text for coordinates and feeds, as CL data and G-code need it.

#include <string>

namespace subfeed {

// `value` rounded to `decimals` digits after the point, trailing zeros dropped but the
// point always kept ("12.", "-0.5", "3.125"): a Fanuc-style control reads a number without
// a point in least input increments (X1 = 0.001 mm), so every word carries one. Negative
// zero prints as "0.".
void append_decimal(std::string& out, double value, int decimals);

// Same with all `decimals` digits kept ("1.500000"), for CL data columns.
void append_fixed(std::string& out, double value, int decimals);

} // namespace subfeed

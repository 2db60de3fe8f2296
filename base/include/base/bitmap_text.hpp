#pragma once
// Labels drawn into an RgbImage with a built-in 5 x 7 pixel font, so that pictures carry
// their title, scale and units without a font library. The font has capitals, digits and
// the punctuation of numbers, units and file names (. , : - _ / ( ) = + %); lower case is
// drawn in capitals and any other character as '?'.

#include "base/png_file.hpp"

#include <array>
#include <cstdint>
#include <string_view>

namespace subfeed {

using Rgb = std::array<std::uint8_t, 3>;

// Each glyph cell is 6 x 8 font pixels (one of spacing), each font pixel `scale` image
// pixels square.
[[nodiscard]] constexpr int text_width(std::string_view text, int scale) {
  return static_cast<int>(text.size()) * 6 * scale;
}
[[nodiscard]] constexpr int text_height(int scale) {
  return 7 * scale;
}

// Draws `text` with its top-left corner at (x, y); pixels off the image are dropped.
void draw_text(RgbImage& image, int x, int y, std::string_view text, int scale, Rgb colour);

} // namespace subfeed

#include "base/bitmap_text.hpp"

#include <catch2/catch.hpp>

using subfeed::RgbImage;

namespace {

int black_pixels(const RgbImage& image) {
  int n = 0;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
    n += image.rgb[i] == 0 && image.rgb[i + 1] == 0 && image.rgb[i + 2] == 0 ? 1 : 0;
  }
  return n;
}

RgbImage drawn(std::string_view text, int scale, int x = 0, int y = 0) {
  RgbImage image(subfeed::text_width(text, scale) + 4, subfeed::text_height(scale) + 4, 255, 255,
                 255);
  subfeed::draw_text(image, x, y, text, scale, {0, 0, 0});
  return image;
}

} // namespace

TEST_CASE("bitmap text: glyphs are drawn pixel for pixel, scaled") {
  // '1' is ten pixels of the 5 x 7 grid; '8' seventeen.
  CHECK(black_pixels(drawn("1", 1)) == 10);
  CHECK(black_pixels(drawn("1", 3)) == 90);
  CHECK(black_pixels(drawn("8", 1)) == 17);
  CHECK(black_pixels(drawn("18", 2)) == 4 * 27);
  CHECK(black_pixels(drawn(" ", 2)) == 0);
  // The top-left pixel of '1' is blank, its top stroke one column right of centre's left.
  const auto one = drawn("1", 1);
  CHECK(one.rgb[0] == 255);
  CHECK(one.rgb[2 * 3] == 0); // row 0, column 2
}

TEST_CASE("bitmap text: lower case as capitals, unknown characters as '?'") {
  CHECK(drawn("mm", 2).rgb == drawn("MM", 2).rgb);
  CHECK(drawn("@", 1).rgb == drawn("?", 1).rgb);
  CHECK(drawn("~", 1).rgb == drawn("?", 1).rgb);
  CHECK(drawn("0", 1).rgb != drawn("O", 1).rgb); // the zero has its slash
}

TEST_CASE("bitmap text: widths and heights, and text off the image is clipped") {
  CHECK(subfeed::text_width("abc", 2) == 36);
  CHECK(subfeed::text_height(2) == 14);
  CHECK(black_pixels(drawn("1", 1, -100, -100)) == 0);
  CHECK(black_pixels(drawn("11", 1, -6, 0)) == 10); // the first glyph is off the left edge
}

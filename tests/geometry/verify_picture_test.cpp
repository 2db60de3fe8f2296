#include "geometry/verify_picture.hpp"

#include "support/png_reader.hpp"
#include "support/temp_dir.hpp"
#include "support/text_file.hpp"

#include <catch2/catch.hpp>

using namespace subfeed;
using namespace subfeed::geometry;

namespace {

// A 20 x 10 mm part whose scallop grows from 0 at x = 0 to 0.0123 mm at x = 20, one pass
// along y = 5: a 240-cell map is 723 x 363 pixels (3 a cell), 1/12 mm a cell.
VerifyPicture ramp() {
  VerifyPicture p;
  for (int i = 0; i <= 200; ++i) {
    for (int j = 0; j <= 100; ++j) {
      p.points.emplace_back(i * 0.1, j * 0.1, 0.0);
      p.heights.push_back(0.0123 * i / 200.0);
      p.gouged.push_back(0);
    }
  }
  p.max_height = 0.0123;
  p.name = "part.obj";
  p.target = 0.01;
  p.passes_xy.push_back({{0.0, 5.0}, {20.0, 5.0}});
  return p;
}

bool is(const RgbImage& image, int x, int y, std::array<int, 3> rgb) {
  const auto at = static_cast<std::size_t>((y * image.width + x) * 3);
  return image.rgb[at] == rgb[0] && image.rgb[at + 1] == rgb[1] && image.rgb[at + 2] == rgb[2];
}

// The picture written as PNG and read back.
RgbImage drawn(const VerifyPicture& p, const std::filesystem::path& file) {
  REQUIRE(write_png(file, p));
  return testing::read_png(file);
}

// Whether the map's pixel at (x, y) mm of a 20 x 10 mm part has colour `rgb`: 1/12 mm a
// cell, 3 pixels a cell, the map 8 pixels in and 30 down, y counted down from 10 mm.
bool map_pixel_is(const RgbImage& image, double x, double y, std::array<int, 3> rgb) {
  return is(image, 8 + static_cast<int>(x * 36), 30 + static_cast<int>((10.0 - y) * 36), rgb);
}

// The longest horizontal run of black pixels in rows [top, bottom).
int longest_black_run(const RgbImage& image, int top, int bottom) {
  int best = 0;
  for (int y = top; y < bottom; ++y) {
    int run = 0;
    for (int x = 0; x < image.width; ++x) {
      run = is(image, x, y, {0, 0, 0}) ? run + 1 : 0;
      best = std::max(best, run);
    }
  }
  return best;
}

} // namespace

TEST_CASE("verify picture, SVG: the title names the part, H and the max, the colour bar has "
          "ticks in mm, the scale bar a round length") {
  const testing::TempDir dir;
  const auto file = dir.path() / "p.svg";
  REQUIRE(write_svg(file, ramp()));
  const auto svg = testing::read_text(file);
  CHECK(svg.find(">part.obj   H 0.01 mm   max 0.0123 mm</text>") != std::string::npos);
  CHECK(svg.find(">scallop, mm</text>") != std::string::npos);
  for (const char* tick : {">0</text>", ">0.00308</text>", ">0.00615</text>", ">0.00923</text>",
                           ">0.0123</text>", ">gouge</text>"}) {
    CHECK(svg.find(tick) != std::string::npos);
  }
  CHECK(svg.find(R"(width="180" height="4" fill="#000"/>)") != std::string::npos); // 5 mm
  CHECK(svg.find(">5 mm</text>") != std::string::npos);
}

TEST_CASE("verify picture, PNG: title, colour bar from blue to red, and a scale bar of 5 mm") {
  const testing::TempDir dir;
  const auto file = dir.path() / "p.png";
  REQUIRE(write_png(file, ramp()));
  const auto image = testing::read_png(file);
  constexpr int map_right = 8 + 723, map_bottom = 30 + 363;
  CHECK(image.width > map_right + 100);  // the legend beside the map
  CHECK(image.height > map_bottom + 20); // the scale bar below it
  int title = 0;
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < image.width; ++x) {
      title += is(image, x, y, {0, 0, 0}) ? 1 : 0;
    }
  }
  CHECK(title > 300); // "PART.OBJ   H 0.01 MM   MAX 0.0123 MM" at 2 pixels a font pixel
  bool red = false, blue = false;
  for (int y = 30; y < map_bottom; ++y) {
    red = red || is(image, map_right + 20, y, {255, 0, 0});
    blue = blue || is(image, map_right + 20, y, {0, 80, 255});
  }
  CHECK(red);
  CHECK(blue);
  // 5 mm at 1/12 mm a cell and 3 pixels a cell.
  CHECK(longest_black_run(image, map_bottom, image.height) == 180);
}

TEST_CASE("verify picture, PNG and SVG: surface left uncut is marked by why, in the map and the "
          "legend, over cut surface in the same cell") {
  auto p = ramp();
  // A 2 x 2 mm square no ball came to, over measured samples (x 2..4, y 2..4); a strip
  // beyond the tilt (x 10..12) and one under the floor (x 16..18), each with no sample cut.
  const auto square = [&](double x0, double x1, LeftUncut why) {
    for (double x = x0; x <= x1; x += 0.05) {
      for (double y = 2.0; y <= 4.0; y += 0.05) {
        p.left.push_back({{x, y, 1.0}, why});
      }
    }
  };
  square(2.0, 4.0, LeftUncut::no_ball);
  square(10.0, 12.0, LeftUncut::beyond_tilt);
  square(16.0, 18.0, LeftUncut::below_floor);
  const testing::TempDir dir;
  const auto image = drawn(p, dir.path() / "p.png");
  const auto at = [&](double x, double y, std::array<int, 3> rgb) {
    return map_pixel_is(image, x, y, rgb);
  };
  CHECK(at(3.0, 3.0, {96, 96, 96}));
  CHECK_FALSE(at(11.0, 3.0, {200, 200, 200})); // cut surface there shows its scallop
  CHECK_FALSE(at(17.0, 3.0, {210, 180, 140}));
  CHECK_FALSE(at(3.0, 7.0, {96, 96, 96})); // cut, outside the square
  int swatches = 0;
  for (int y = 30; y < image.height; ++y) {
    swatches += is(image, 8 + 723 + 16 + 8, y, {96, 96, 96}) ? 1 : 0;
  }
  CHECK(swatches > 0);
  const auto svg_file = dir.path() / "p.svg";
  REQUIRE(write_svg(svg_file, p));
  const auto svg = testing::read_text(svg_file);
  for (const char* label : {">no ball</text>", ">over tilt</text>", ">under floor</text>"}) {
    CHECK(svg.find(label) != std::string::npos);
  }
  CHECK(svg.find("fill=\"rgb(96,96,96)\"") != std::string::npos);
}

TEST_CASE("verify picture: beyond-tilt and under-floor marks show where no cut sample lies") {
  VerifyPicture p;
  for (int i = 0; i <= 200; ++i) {
    for (int j = 0; j <= 100; ++j) {
      const Eigen::Vector3d at(i * 0.1, j * 0.1, 0.0);
      if (i < 100) {
        p.points.push_back(at);
        p.heights.push_back(0.01);
        p.gouged.push_back(0);
      } else {
        p.left.push_back({at, i < 150 ? LeftUncut::beyond_tilt : LeftUncut::below_floor});
      }
    }
  }
  p.max_height = 0.01;
  const testing::TempDir dir;
  const auto image = drawn(p, dir.path() / "p.png");
  const auto at = [&](double x, double y, std::array<int, 3> rgb) {
    return map_pixel_is(image, x, y, rgb);
  };
  CHECK(at(5.0, 5.0, {255, 0, 0}));
  CHECK(at(12.5, 5.0, {200, 200, 200}));
  CHECK(at(17.5, 5.0, {210, 180, 140}));
}

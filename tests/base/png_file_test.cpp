// The PNG writer checked by reading its file back the way a decoder does: signature, chunk
// lengths and CRCs, the header, and the pixels recovered from the stored deflate blocks
// with their Adler-32.

#include "base/png_file.hpp"
#include "support/png_reader.hpp"
#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using subfeed::RgbImage;
using subfeed::testing::TempDir;
using namespace subfeed::testing;

TEST_CASE("CRC-32 of the PNG standard's check value") {
  const std::string text = "123456789";
  CHECK(subfeed::png_crc32(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()) ==
        0xcbf43926U);
}

TEST_CASE("a PNG reads back pixel for pixel, across several deflate blocks") {
  TempDir dir;
  RgbImage image(200, 150, 10, 20, 30); // 90,150 bytes of scanlines: two stored blocks
  for (int y = 0; y < 150; ++y) {
    for (int x = 0; x < 200; ++x) {
      image.set(x, y, static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y),
                static_cast<std::uint8_t>(x ^ y));
    }
  }
  image.set(-1, 5, 0, 0, 0); // off the image: ignored
  image.set(200, 5, 0, 0, 0);
  const auto file = dir.path() / "out.png";
  REQUIRE(subfeed::write_png(file, image));
  std::ifstream in(file, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
  const auto chunks = read_chunks(bytes);
  REQUIRE(chunks.size() == 3);
  CHECK(chunks[0].type == "IHDR");
  CHECK(be32(chunks[0].data, 0) == 200);
  CHECK(be32(chunks[0].data, 4) == 150);
  CHECK(chunks[0].data[8] == 8); // bit depth
  CHECK(chunks[0].data[9] == 2); // truecolour
  CHECK(chunks[1].type == "IDAT");
  CHECK(chunks[2].type == "IEND");
  const auto raw = inflate_stored(chunks[1].data);
  REQUIRE(raw.size() == 150 * (1 + 200 * 3));
  for (std::size_t y = 0; y < 150; ++y) {
    const std::size_t row = y * (1 + 200 * 3);
    CHECK(raw[row] == 0); // filter None
    const std::vector<std::uint8_t> pixels(raw.begin() + static_cast<std::ptrdiff_t>(row + 1),
                                           raw.begin() + static_cast<std::ptrdiff_t>(row + 601));
    CHECK(pixels == std::vector<std::uint8_t>(
                        image.rgb.begin() + static_cast<std::ptrdiff_t>(y * 600),
                        image.rgb.begin() + static_cast<std::ptrdiff_t>((y + 1) * 600)));
  }
}

TEST_CASE("an empty picture is refused and leaves no file") {
  TempDir dir;
  const auto file = dir.path() / "none.png";
  CHECK_FALSE(subfeed::write_png(file, RgbImage(0, 10, 0, 0, 0)));
  CHECK_FALSE(std::filesystem::exists(file));
}

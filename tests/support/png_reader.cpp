#include "support/png_reader.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

namespace subfeed::testing {

std::uint32_t be32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) |
         (std::uint32_t{b[at + 2]} << 8) | std::uint32_t{b[at + 3]};
}

std::vector<Chunk> read_chunks(const std::vector<std::uint8_t>& file) {
  const std::vector<std::uint8_t> signature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  REQUIRE(std::vector<std::uint8_t>(file.begin(), file.begin() + 8) == signature);
  std::vector<Chunk> chunks;
  std::size_t at = 8;
  while (at < file.size()) {
    const std::uint32_t length = be32(file, at);
    REQUIRE(at + 12 + length <= file.size());
    const std::uint32_t crc = subfeed::png_crc32(file.data() + at + 4, length + 4);
    CHECK(crc == be32(file, at + 8 + length));
    chunks.push_back({std::string(file.begin() + static_cast<std::ptrdiff_t>(at + 4),
                                  file.begin() + static_cast<std::ptrdiff_t>(at + 8)),
                      {file.begin() + static_cast<std::ptrdiff_t>(at + 8),
                       file.begin() + static_cast<std::ptrdiff_t>(at + 8 + length)}});
    at += 12 + length;
  }
  return chunks;
}

std::vector<std::uint8_t> inflate_stored(const std::vector<std::uint8_t>& z) {
  REQUIRE(z.size() >= 6);
  CHECK((z[0] * 256 + z[1]) % 31 == 0); // the zlib header check
  std::vector<std::uint8_t> out;
  std::size_t at = 2;
  bool last = false;
  while (!last) {
    last = (z[at] & 1) != 0;
    REQUIRE((z[at] & 6) == 0); // BTYPE 00: stored
    const std::size_t n = z[at + 1] | (z[at + 2] << 8);
    const std::size_t complement = z[at + 3] | (z[at + 4] << 8);
    CHECK(n == (~complement & 0xffff));
    out.insert(out.end(), z.begin() + static_cast<std::ptrdiff_t>(at + 5),
               z.begin() + static_cast<std::ptrdiff_t>(at + 5 + n));
    at += 5 + n;
  }
  std::uint32_t a = 1, b = 0;
  for (const auto byte : out) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  CHECK(be32(z, at) == ((b << 16) | a));
  return out;
}

RgbImage read_png(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
  const auto chunks = read_chunks(bytes);
  REQUIRE(chunks.size() == 3);
  REQUIRE(chunks[0].type == "IHDR");
  const auto width = static_cast<int>(be32(chunks[0].data, 0));
  const auto height = static_cast<int>(be32(chunks[0].data, 4));
  const auto raw = inflate_stored(chunks[1].data);
  const auto row = static_cast<std::size_t>(1 + width * 3);
  REQUIRE(raw.size() == static_cast<std::size_t>(height) * row);
  RgbImage image(width, height, 0, 0, 0);
  for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y) {
    REQUIRE(raw[y * row] == 0); // filter None
    std::copy(raw.begin() + static_cast<std::ptrdiff_t>(y * row + 1),
              raw.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
              image.rgb.begin() + static_cast<std::ptrdiff_t>(y * (row - 1)));
  }
  return image;
}

} // namespace subfeed::testing

#pragma once
// Reads back the PNG files subfeed writes, the way a decoder does (signature, chunk lengths
// and CRCs, the header, stored deflate blocks with their Adler-32), checking each step with
// Catch, so that tests can look at the pixels of a picture.

#include "base/png_file.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace subfeed::testing {

[[nodiscard]] std::uint32_t be32(const std::vector<std::uint8_t>& b, std::size_t at);

struct Chunk {
  std::string type;
  std::vector<std::uint8_t> data;
};

[[nodiscard]] std::vector<Chunk> read_chunks(const std::vector<std::uint8_t>& file);

// Inflates a zlib stream made of stored blocks only.
[[nodiscard]] std::vector<std::uint8_t> inflate_stored(const std::vector<std::uint8_t>& z);

// The picture of an 8-bit truecolour PNG file, unfiltered.
[[nodiscard]] RgbImage read_png(const std::filesystem::path& path);

} // namespace subfeed::testing

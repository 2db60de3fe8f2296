#pragma once
// Writes an 8-bit RGB picture as a PNG file (ISO/IEC 15948), atomically (atomic_output_file.hpp).
// The image data goes in uncompressed deflate blocks: no compression library is needed and
// every PNG reader accepts it; pictures here are a few hundred pixels a side.

#include "base/error.hpp"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace subfeed {

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb; // row by row from the top, 3 bytes a pixel

  RgbImage(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b);
  // Pixels outside the image are ignored, so callers may draw lines that run off the edge.
  void set(int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b);
};

[[nodiscard]] Expected<void> write_png(const std::filesystem::path& file, const RgbImage& image);

// The CRC-32 PNG puts in every chunk (ISO 3309), exposed so tests can check chunks.
[[nodiscard]] std::uint32_t png_crc32(const std::uint8_t* data, std::size_t size,
                                      std::uint32_t crc = 0);

} // namespace subfeed

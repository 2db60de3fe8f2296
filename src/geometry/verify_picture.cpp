#include "geometry/verify_picture.hpp"

#include "base/atomic_output_file.hpp"
#include "base/png_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

namespace subfeed::geometry {

namespace {

constexpr int cells_across = 240; // heat-map cells along the longer side
constexpr int cell_pixels = 3;
constexpr double gouge_mark = -2.0;

// The heat map: the worst scallop of the samples that fall in each cell, -1 where none,
// gouge_mark where any of them was gouged.
struct Raster {
  Eigen::Vector2d lo;
  double cell = 1.0; // mm
  int width = 0, height = 0;
  std::vector<double> values;

  [[nodiscard]] Eigen::Vector2d pixel(const Eigen::Vector2d& p) const {
    return {(p.x() - lo.x()) / cell * cell_pixels,
            (height - (p.y() - lo.y()) / cell) * cell_pixels};
  }
};

Raster rasterise(const VerifyPicture& picture) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& p : picture.points) {
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  Raster r;
  r.lo = lo;
  r.cell = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-9}) / cells_across;
  r.width = static_cast<int>(std::ceil((hi.x() - lo.x()) / r.cell)) + 1;
  r.height = static_cast<int>(std::ceil((hi.y() - lo.y()) / r.cell)) + 1;
  r.values.assign(static_cast<std::size_t>(r.width * r.height), -1.0);
  for (std::size_t i = 0; i < picture.points.size(); ++i) {
    const int x = static_cast<int>((picture.points[i].x() - lo.x()) / r.cell);
    const int y = static_cast<int>((picture.points[i].y() - lo.y()) / r.cell);
    auto& v = r.values[static_cast<std::size_t>(y * r.width + x)];
    if (picture.gouged[i] != 0 || v == gouge_mark) {
      v = gouge_mark;
    } else {
      v = std::max(v, picture.heights[i]);
    }
  }
  // Where the samples lie sparser than the cells (flat faces), an empty cell takes the
  // worst of its measured neighbours instead of showing a hole.
  const auto measured = r.values;
  for (int y = 0; y < r.height; ++y) {
    for (int x = 0; x < r.width; ++x) {
      auto& v = r.values[static_cast<std::size_t>(y * r.width + x)];
      for (int dy = -1; dy <= 1 && v == -1.0; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < r.width && ny < r.height) {
            const double n = measured[static_cast<std::size_t>(ny * r.width + nx)];
            v = n >= 0.0 ? std::max(v, n) : v;
          }
        }
      }
    }
  }
  return r;
}

std::array<std::uint8_t, 3> colour(double v, double max_height) {
  if (v == gouge_mark) {
    return {0, 0, 0};
  }
  const double f = max_height > 0.0 ? std::clamp(v / max_height, 0.0, 1.0) : 0.0;
  return {static_cast<std::uint8_t>(255 * f), static_cast<std::uint8_t>(80 * (1 - f)),
          static_cast<std::uint8_t>(255 * (1 - f))};
}

std::string legend(double max_height) {
  return fmt::format("scallop 0 (blue) to {:.4f} mm (red); black: gouge over 1 um; white: passes",
                     max_height);
}

void draw_line(RgbImage& image, Eigen::Vector2d a, const Eigen::Vector2d& b) {
  const int steps = static_cast<int>(std::ceil((b - a).cwiseAbs().maxCoeff())) + 1;
  for (int i = 0; i <= steps; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / steps);
    image.set(static_cast<int>(p.x()), static_cast<int>(p.y()), 255, 255, 255);
  }
}

// Calls visit(x, y, colour) for every measured cell, y counted from the top of the picture.
template <class Visit> void for_each_cell(const Raster& r, double max_height, Visit&& visit) {
  for (int y = 0; y < r.height; ++y) {
    for (int x = 0; x < r.width; ++x) {
      const double v = r.values[static_cast<std::size_t>(y * r.width + x)];
      if (v != -1.0) {
        visit(x, r.height - 1 - y, colour(v, max_height));
      }
    }
  }
}

} // namespace

Expected<void> write_svg(const std::filesystem::path& file, const VerifyPicture& picture) {
  const Raster r = rasterise(picture);
  const int w = r.width * cell_pixels, h = r.height * cell_pixels;
  SUBFEED_TRY_ASSIGN(auto out, AtomicOutputFile::create(file));
  out.write(fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {0} {1}\" "
                        "width=\"{0}\" height=\"{1}\">\n<g shape-rendering=\"crispEdges\">\n",
                        w, h + 30));
  for_each_cell(r, picture.max_height, [&](int x, int y, const auto& c) {
    out.write(fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" "
                          "fill=\"rgb({},{},{})\"/>\n",
                          x * cell_pixels, y * cell_pixels, cell_pixels, cell_pixels, c[0], c[1],
                          c[2]));
  });
  out.write("</g>\n<g fill=\"none\" stroke=\"#fff\" stroke-width=\"0.6\">\n");
  for (const auto& pass : picture.passes_xy) {
    std::string pts;
    for (std::size_t i = 0; i < pass.size(); i += std::max<std::size_t>(1, pass.size() / 400)) {
      const auto p = r.pixel(pass[i]);
      pts += fmt::format("{:.1f},{:.1f} ", p.x(), p.y());
    }
    out.write("<polyline points=\"" + pts + "\"/>\n");
  }
  out.write(fmt::format("</g>\n<text x=\"4\" y=\"{}\" font-size=\"14\" "
                        "font-family=\"sans-serif\">{}</text>\n</svg>\n",
                        h + 20, legend(picture.max_height)));
  return out.commit();
}

Expected<void> write_png(const std::filesystem::path& file, const VerifyPicture& picture) {
  const Raster r = rasterise(picture);
  RgbImage image(r.width * cell_pixels, r.height * cell_pixels, 255, 255, 255);
  for_each_cell(r, picture.max_height, [&](int x, int y, const auto& c) {
    for (int dy = 0; dy < cell_pixels; ++dy) {
      for (int dx = 0; dx < cell_pixels; ++dx) {
        image.set(x * cell_pixels + dx, y * cell_pixels + dy, c[0], c[1], c[2]);
      }
    }
  });
  for (const auto& pass : picture.passes_xy) {
    for (std::size_t i = 1; i < pass.size(); ++i) {
      draw_line(image, r.pixel(pass[i - 1]), r.pixel(pass[i]));
    }
  }
  return write_png(file, image);
}

} // namespace subfeed::geometry

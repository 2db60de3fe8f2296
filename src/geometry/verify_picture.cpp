#include "geometry/verify_picture.hpp"

#include "base/atomic_output_file.hpp"
#include "base/bitmap_text.hpp"
#include "base/png_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <string>
#include <string_view>

namespace subfeed::geometry {

namespace {

constexpr int cells_across = 240; // heat-map cells along the longer side
constexpr int cell_pixels = 3;

// A cell's value is a scallop height (>= 0) or one of these marks.
constexpr double empty_mark = -1.0, gouge_mark = -2.0, no_ball_mark = -3.0, beyond_tilt_mark = -4.0,
                 below_floor_mark = -5.0;

double mark_of(LeftUncut why) {
  switch (why) {
  case LeftUncut::no_ball:
    return no_ball_mark;
  case LeftUncut::beyond_tilt:
    return beyond_tilt_mark;
  case LeftUncut::below_floor:
    return below_floor_mark;
  }
  return empty_mark;
}

// Which of two values a cell shows (verify_picture.hpp): the higher rank, and of two
// heights the worse.
int rank_of(double v) {
  return v >= 0.0                ? 3
         : v == gouge_mark       ? 5
         : v == no_ball_mark     ? 4
         : v == beyond_tilt_mark ? 2
         : v == below_floor_mark ? 1
                                 : 0;
}

double merged(double a, double b) {
  const int ra = rank_of(a), rb = rank_of(b);
  return ra != rb ? (ra > rb ? a : b) : std::max(a, b);
}

// The heat map: per cell, what the samples that fall in it show (merged), empty_mark where
// none fell.
struct Raster {
  Eigen::Vector2d lo;
  double cell = 1.0; // mm
  int width = 0, height = 0;
  std::vector<double> values;

  [[nodiscard]] Eigen::Vector2d pixel(const Eigen::Vector2d& p) const {
    return {(p.x() - lo.x()) / cell * cell_pixels,
            (height - (p.y() - lo.y()) / cell) * cell_pixels};
  }
  void add(const Eigen::Vector3d& p, double v) {
    const int x = static_cast<int>((p.x() - lo.x()) / cell);
    const int y = static_cast<int>((p.y() - lo.y()) / cell);
    auto& at = values[static_cast<std::size_t>(y * width + x)];
    at = merged(at, v);
  }
};

Raster rasterise(const VerifyPicture& picture) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& p : picture.points) {
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  for (const auto& l : picture.left) {
    lo = lo.cwiseMin(l.point.head<2>());
    hi = hi.cwiseMax(l.point.head<2>());
  }
  Raster r;
  r.lo = lo;
  r.cell = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-9}) / cells_across;
  r.width = static_cast<int>(std::ceil((hi.x() - lo.x()) / r.cell)) + 1;
  r.height = static_cast<int>(std::ceil((hi.y() - lo.y()) / r.cell)) + 1;
  r.values.assign(static_cast<std::size_t>(r.width * r.height), empty_mark);
  for (std::size_t i = 0; i < picture.points.size(); ++i) {
    r.add(picture.points[i], picture.gouged[i] != 0 ? gouge_mark : picture.heights[i]);
  }
  for (const auto& l : picture.left) {
    r.add(l.point, mark_of(l.why));
  }
  // Where the samples lie sparser than the cells (flat faces), an empty cell shows what its
  // neighbours show instead of a hole.
  const auto measured = r.values;
  for (int y = 0; y < r.height; ++y) {
    for (int x = 0; x < r.width; ++x) {
      auto& v = r.values[static_cast<std::size_t>(y * r.width + x)];
      if (v != empty_mark) {
        continue;
      }
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < r.width && ny < r.height) {
            v = merged(v, measured[static_cast<std::size_t>(ny * r.width + nx)]);
          }
        }
      }
    }
  }
  return r;
}

// The legend's swatches for the marks, in its order.
struct Swatch {
  double mark;
  std::string_view label;
};
constexpr std::array<Swatch, 4> swatches{{{gouge_mark, "gouge"},
                                          {no_ball_mark, "no ball"},
                                          {beyond_tilt_mark, "over tilt"},
                                          {below_floor_mark, "under floor"}}};

Rgb colour(double v, double max_height) {
  if (v == gouge_mark) {
    return {0, 0, 0};
  }
  if (v == no_ball_mark) {
    return {96, 96, 96};
  }
  if (v == beyond_tilt_mark) {
    return {200, 200, 200};
  }
  if (v == below_floor_mark) {
    return {210, 180, 140};
  }
  const double f = max_height > 0.0 ? std::clamp(v / max_height, 0.0, 1.0) : 0.0;
  return {static_cast<std::uint8_t>(255 * f), static_cast<std::uint8_t>(80 * (1 - f)),
          static_cast<std::uint8_t>(255 * (1 - f))};
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
      if (v != empty_mark) {
        visit(x, r.height - 1 - y, colour(v, max_height));
      }
    }
  }
}

// Where the title, the map, the colour bar and the scale bar go, in pixels. The map keeps
// its raster's size; the canvas grows around it so the legend always fits.
constexpr std::string_view bar_heading = "scallop, mm";

struct Layout {
  static constexpr int pad = 8, text_scale = 2, bar_width = 16, ticks = 5;
  int map_x = pad, map_y = 0, map_w = 0, map_h = 0;
  int bar_x = 0, bar_y = 0, bar_h = 0;
  int scale_y = 0, scale_px = 0;
  double scale_mm = 0.0;
  int width = 0, height = 0;
  std::string title;
  double max_height = 0.0;

  // The height a tick stands for, tick 0 at the bottom of the bar.
  [[nodiscard]] double tick_value(int tick) const { return max_height * tick / (ticks - 1); }
  [[nodiscard]] int tick_y(int tick) const { return bar_y + bar_h - bar_h * tick / (ticks - 1); }
  // The top of swatch `i`, below the bar.
  [[nodiscard]] int swatch_y(int i) const {
    return bar_y + bar_h + pad + i * (text_height(text_scale) + pad);
  }
};

// The longest 1, 2 or 5 times a power of ten that is at most a quarter of `span_mm`.
double nice_length(double span_mm) {
  const double target = std::max(span_mm / 4.0, 1e-6);
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  for (const double m : {5.0, 2.0, 1.0}) {
    if (m * decade <= target) {
      return m * decade;
    }
  }
  return decade;
}

std::string title_of(const VerifyPicture& picture) {
  std::string title = picture.name.empty() ? std::string("scallop") : picture.name;
  if (picture.target) {
    title += fmt::format("   H {:g} mm", *picture.target);
  }
  return title + fmt::format("   max {:.3g} mm", picture.max_height);
}

std::string tick_label(double value) {
  return fmt::format("{:.3g}", value);
}

Layout layout_of(const Raster& r, const VerifyPicture& picture) {
  Layout l;
  const int line = text_height(Layout::text_scale);
  l.title = title_of(picture);
  l.max_height = picture.max_height;
  l.map_y = line + 2 * Layout::pad;
  l.map_w = r.width * cell_pixels;
  l.map_h = r.height * cell_pixels;
  const int swatch_lines = static_cast<int>(swatches.size());
  const int body_h = std::max(l.map_h, 120 + swatch_lines * (line + Layout::pad));
  l.bar_x = l.map_x + l.map_w + 2 * Layout::pad;
  l.bar_y = l.map_y + line + 2 * Layout::pad; // below the bar's own heading
  l.bar_h = body_h - (line + 2 * Layout::pad) -
            swatch_lines * (line + Layout::pad); // and above the swatches
  l.scale_mm = nice_length(r.width * r.cell);
  l.scale_px = static_cast<int>(std::lround(l.scale_mm / r.cell * cell_pixels));
  l.scale_y = l.map_y + body_h + Layout::pad;
  int labels = 0; // the widest tick or swatch label
  for (int t = 0; t < Layout::ticks; ++t) {
    labels = std::max(labels, text_width(tick_label(l.tick_value(t)), Layout::text_scale));
  }
  for (const auto& s : swatches) {
    labels = std::max(labels, text_width(s.label, Layout::text_scale));
  }
  l.width = std::max({l.bar_x + Layout::bar_width + Layout::pad + labels + Layout::pad,
                      l.bar_x + text_width(bar_heading, Layout::text_scale) + Layout::pad,
                      text_width(l.title, Layout::text_scale) + 2 * Layout::pad});
  l.height = l.scale_y + line + 2 * Layout::pad;
  return l;
}

// `text` with XML's markup characters escaped, for the SVG.
std::string xml_text(std::string_view text) {
  std::string out;
  for (const char c : text) {
    out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  }
  return out;
}

} // namespace

Expected<void> write_svg(const std::filesystem::path& file, const VerifyPicture& picture) {
  const Raster r = rasterise(picture);
  const Layout l = layout_of(r, picture);
  SUBFEED_TRY_ASSIGN(auto out, AtomicOutputFile::create(file));
  out.write(fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {0} {1}\" "
                        "width=\"{0}\" height=\"{1}\" font-family=\"sans-serif\" "
                        "font-size=\"14\">\n<rect width=\"{0}\" height=\"{1}\" fill=\"#fff\"/>\n"
                        "<text x=\"{2}\" y=\"{3}\">{4}</text>\n"
                        "<g shape-rendering=\"crispEdges\" transform=\"translate({5},{6})\">\n",
                        l.width, l.height, Layout::pad, l.map_y - Layout::pad, xml_text(l.title),
                        l.map_x, l.map_y));
  for_each_cell(r, picture.max_height, [&](int x, int y, const auto& c) {
    out.write(fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" "
                          "fill=\"rgb({},{},{})\"/>\n",
                          x * cell_pixels, y * cell_pixels, cell_pixels, cell_pixels, c[0], c[1],
                          c[2]));
  });
  out.write(fmt::format("</g>\n<g fill=\"none\" stroke=\"#fff\" stroke-width=\"0.6\" "
                        "transform=\"translate({},{})\">\n",
                        l.map_x, l.map_y));
  for (const auto& pass : picture.passes_xy) {
    std::string pts;
    for (std::size_t i = 0; i < pass.size(); i += std::max<std::size_t>(1, pass.size() / 400)) {
      const auto p = r.pixel(pass[i]);
      pts += fmt::format("{:.1f},{:.1f} ", p.x(), p.y());
    }
    out.write("<polyline points=\"" + pts + "\"/>\n");
  }
  out.write("</g>\n");
  const auto top = colour(picture.max_height, picture.max_height), bottom = colour(0.0, 1.0);
  out.write(fmt::format(
      "<defs><linearGradient id=\"scale\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">"
      "<stop offset=\"0\" stop-color=\"rgb({},{},{})\"/><stop offset=\"1\" "
      "stop-color=\"rgb({},{},{})\"/></linearGradient></defs>\n"
      "<text x=\"{}\" y=\"{}\">{}</text>\n"
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"url(#scale)\" stroke=\"#000\"/>\n",
      bottom[0], bottom[1], bottom[2], top[0], top[1], top[2], l.bar_x, l.map_y + 14, bar_heading,
      l.bar_x, l.bar_y, Layout::bar_width, l.bar_h));
  for (int t = 0; t < Layout::ticks; ++t) {
    out.write(fmt::format("<text x=\"{}\" y=\"{}\">{}</text>\n",
                          l.bar_x + Layout::bar_width + Layout::pad, l.tick_y(t) + 5,
                          tick_label(l.tick_value(t))));
  }
  for (std::size_t i = 0; i < swatches.size(); ++i) {
    const int y = l.swatch_y(static_cast<int>(i));
    const auto c = colour(swatches[i].mark, 1.0);
    out.write(fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"10\" "
                          "fill=\"rgb({},{},{})\"/><text x=\"{}\" y=\"{}\">{}</text>\n",
                          l.bar_x, y, Layout::bar_width, c[0], c[1], c[2],
                          l.bar_x + Layout::bar_width + Layout::pad, y + 10, swatches[i].label));
  }
  out.write(fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"4\" fill=\"#000\"/>"
                        "<text x=\"{}\" y=\"{}\">{:g} mm</text>\n</svg>\n",
                        l.map_x, l.scale_y + 5, l.scale_px, l.map_x + l.scale_px + Layout::pad,
                        l.scale_y + 12, l.scale_mm));
  return out.commit();
}

namespace {

void fill(RgbImage& image, int x, int y, int w, int h, const Rgb& c) {
  for (int dy = 0; dy < h; ++dy) {
    for (int dx = 0; dx < w; ++dx) {
      image.set(x + dx, y + dy, c[0], c[1], c[2]);
    }
  }
}

// The colour bar with its ticks, the gouge swatch and the scale bar.
void draw_legend(RgbImage& image, const Layout& l) {
  constexpr Rgb black{0, 0, 0};
  constexpr int s = Layout::text_scale;
  draw_text(image, Layout::pad, Layout::pad, l.title, s, black);
  draw_text(image, l.bar_x, l.map_y, bar_heading, s, black);
  for (int y = 0; y < l.bar_h; ++y) {
    const double v = l.max_height * (l.bar_h - 1 - y) / std::max(1, l.bar_h - 1);
    fill(image, l.bar_x, l.bar_y + y, Layout::bar_width, 1, colour(v, l.max_height));
  }
  for (int t = 0; t < Layout::ticks; ++t) {
    const int y = std::min(l.tick_y(t), l.bar_y + l.bar_h - 1);
    fill(image, l.bar_x + Layout::bar_width, y, 4, 1, black);
    draw_text(image, l.bar_x + Layout::bar_width + Layout::pad, y - text_height(s) / 2,
              tick_label(l.tick_value(t)), s, black);
  }
  for (std::size_t i = 0; i < swatches.size(); ++i) {
    const int y = l.swatch_y(static_cast<int>(i));
    fill(image, l.bar_x, y, Layout::bar_width, text_height(s), colour(swatches[i].mark, 1.0));
    draw_text(image, l.bar_x + Layout::bar_width + Layout::pad, y, swatches[i].label, s, black);
  }
  fill(image, l.map_x, l.scale_y + text_height(s) / 2 - 2, l.scale_px, 4, black);
  draw_text(image, l.map_x + l.scale_px + Layout::pad, l.scale_y,
            fmt::format("{:g} mm", l.scale_mm), s, black);
}

} // namespace

Expected<void> write_png(const std::filesystem::path& file, const VerifyPicture& picture) {
  const Raster r = rasterise(picture);
  const Layout l = layout_of(r, picture);
  RgbImage image(l.width, l.height, 255, 255, 255);
  for_each_cell(r, picture.max_height, [&](int x, int y, const auto& c) {
    fill(image, l.map_x + x * cell_pixels, l.map_y + y * cell_pixels, cell_pixels, cell_pixels,
         {c[0], c[1], c[2]});
  });
  const Eigen::Vector2d offset(l.map_x, l.map_y);
  for (const auto& pass : picture.passes_xy) {
    for (std::size_t i = 1; i < pass.size(); ++i) {
      draw_line(image, r.pixel(pass[i - 1]) + offset, r.pixel(pass[i]) + offset);
    }
  }
  draw_legend(image, l);
  return write_png(file, image);
}

} // namespace subfeed::geometry

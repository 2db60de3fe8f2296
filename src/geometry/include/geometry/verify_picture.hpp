#pragma once
// The picture `subfeed verify` draws: a top view (XY, +Y up) of the measured scallop as a
// heat map, blue (none) to red (the worst), black where the ball cut more than 1 um below
// the surface, with the passes over it in white; a title naming the part, H and the worst
// scallop, a colour bar with ticks in mm, and a scale bar in mm. The same picture is
// written as SVG or PNG.

#include "base/error.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace subfeed::geometry {

struct VerifyPicture {
  std::vector<Eigen::Vector3d> points; // surface samples, mm
  std::vector<double> heights;         // scallop at each sample, mm
  std::vector<char> gouged;            // 1 where the ball cut below the sample (shown black)
  double max_height = 0.0;             // mm, the red end of the scale
  std::string name;                    // the part, for the title
  std::optional<double> target;        // H, mm, when given
  std::vector<std::vector<Eigen::Vector2d>> passes_xy; // tool tips, mm
};

[[nodiscard]] Expected<void> write_svg(const std::filesystem::path& file,
                                       const VerifyPicture& picture);
[[nodiscard]] Expected<void> write_png(const std::filesystem::path& file,
                                       const VerifyPicture& picture);

} // namespace subfeed::geometry

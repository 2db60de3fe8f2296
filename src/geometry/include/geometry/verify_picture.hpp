#pragma once
// The picture `subfeed verify` draws: a top view (XY, +Y up) of the measured scallop as a
// heat map, blue (none) to red (the worst), black where the ball cut more than 1 um below
// the surface, with the passes over it in white; a title naming the part, H and the worst
// scallop, a colour bar with ticks in mm, and a scale bar in mm. Surface left uncut is marked
// by why: dark grey where no ball came (the planner left it for reach: tilt, collision or the
// floor), light grey where it leans beyond the tilt limit, tan where the ball reaches it only
// below the floor; each has a swatch in the legend. The same picture is written as SVG or PNG.

#include "base/error.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace subfeed::geometry {

// Why a sample of the surface was left out of the scallop map.
enum class LeftUncut : char { no_ball, beyond_tilt, below_floor };

struct LeftSample {
  Eigen::Vector3d point; // on the surface, mm
  LeftUncut why;
};

struct VerifyPicture {
  std::vector<Eigen::Vector3d> points; // surface samples, mm
  std::vector<double> heights;         // scallop at each sample, mm
  std::vector<char> gouged;            // 1 where the ball cut below the sample (shown black)
  double max_height = 0.0;             // mm, the red end of the scale
  std::string name;                    // the part, for the title
  std::optional<double> target;        // H, mm, when given
  std::vector<std::vector<Eigen::Vector2d>> passes_xy; // tool tips, mm
  // Samples left uncut. In a cell a gouge shows first, then surface no ball came to, then
  // the scallop, then the rest: a small region left for reach is not hidden by cut surface
  // over or under it.
  std::vector<LeftSample> left;
};

[[nodiscard]] Expected<void> write_svg(const std::filesystem::path& file,
                                       const VerifyPicture& picture);
[[nodiscard]] Expected<void> write_png(const std::filesystem::path& file,
                                       const VerifyPicture& picture);

} // namespace subfeed::geometry

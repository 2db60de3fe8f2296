#pragma once
// The tool as the spindle holds it: the cutter (a ball end today), its flutes, the shank and
// the holder, each a solid of revolution about the tool axis, stacked from the tip up.
//
// Sign conventions: a body spans heights [from_mm, to_mm] measured along the tool axis
// (unit, tip toward spindle) from the tip; its radius runs linearly from radius_from_mm at
// from_mm to radius_to_mm at to_mm (a cylinder when they agree, a cone otherwise). The ball
// itself is not a body here: its centre is tip + r axis and the motion gate measures it as
// it always has (the cut). Flat and bull-nose cutters would change only the bodies below
// the flutes' top; nothing else here assumes a ball.

#include "base/error.hpp"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace subfeed::geometry {

struct HolderStage {
  double bottom_diameter = 0.0; // mm, at the end nearer the tip
  double top_diameter = 0.0;    // mm; equal to the bottom one for a cylinder
  double length = 0.0;          // mm along the axis

  // "D:L" for a cylinder, "D1:D2:L" for a cone: as --holder takes it.
  [[nodiscard]] std::string text() const;
};

struct ToolBody {
  std::string name; // "flutes", "shank", "holder 1", ...
  double from_mm = 0.0, to_mm = 0.0;
  double radius_from_mm = 0.0, radius_to_mm = 0.0;
  bool cuts = false; // the flutes may go as low as the stock reaches; nothing else may
};

struct ToolAssembly {
  double ball_radius = 3.0;        // mm
  double flute_length = 0.0;       // mm from the tip, the ball included
  double shank_diameter = 0.0;     // mm
  double stickout = 0.0;           // mm from the tip to the holder's face
  std::vector<HolderStage> holder; // bottom first; empty: no holder is known
  bool defaulted = false;          // flute, shank and stick-out were not given: 3D, D, 4D

  // The ball alone, with the defaults the summary names.
  [[nodiscard]] static ToolAssembly ball_only(double ball_radius);
  // Checks the sizes agree (flutes within the stick-out, positive sizes); `what` names
  // where they came from in the error.
  [[nodiscard]] Expected<void> validate(const std::string& what) const;
  // Flutes (above the ball), shank (when the flutes end below the holder), holder stages.
  [[nodiscard]] std::vector<ToolBody> bodies() const;
  // The highest point of the assembly above the tip, mm.
  [[nodiscard]] double length() const;
  // "ball 6, flutes 18, shank 6, stick-out 24, no holder".
  [[nodiscard]] std::string text() const;
};

// The distance from `p` to the body set on a tool at `tip` along `axis` (unit), mm; 0
// inside it.
[[nodiscard]] double body_distance(const ToolBody& body, const Eigen::Vector3d& tip,
                                   const Eigen::Vector3d& axis, const Eigen::Vector3d& p);

// The body's lowest point (one of them where a level edge is lowest), and its z, mm.
[[nodiscard]] Eigen::Vector3d body_lowest_point(const ToolBody& body, const Eigen::Vector3d& tip,
                                                const Eigen::Vector3d& axis);
[[nodiscard]] double body_lowest_z(const ToolBody& body, const Eigen::Vector3d& tip,
                                   const Eigen::Vector3d& axis);

} // namespace subfeed::geometry

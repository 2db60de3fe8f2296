#pragma once
// Whether a rapid between two tool poses keeps the motion gate's rules, measured by the
// planner before it writes the rapid: the ball off the limit surface by a margin, and with
// the whole tool, every body above the ball off the planner's mesh by the fixture's
// clearance and a margin (the gate measures the same tool against its own, coarser mesh:
// the margins cover the two meshes' difference). And the way a link climbs from a pose to
// a height: straight up where that keeps them, else back along the tool axis first.
//
// Why back along the axis: a tool whose bodies never narrow going up (ball, flutes, shank,
// holders) drawn back along its own axis only moves away from every point beside it, so a
// pose the planner cleared stays cleared as far as the assembly reaches. Straight up, a
// tilted tool's shank sweeps sideways past a wall it cleared at the pose.

#include "geometry/assembly_clearance.hpp"
#include "geometry/limit_distance.hpp"

#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

namespace subfeed::geometry {

class LinkClearance {
public:
  // mm kept beyond the gate's rules by every rapid measured here.
  static constexpr double ball_margin_mm = 0.05;
  static constexpr double body_margin_mm = 0.05;

  // `exact`, `part` and what they hold must outlive this; `whole_tool` false: the ball only.
  LinkClearance(const LimitDistance& exact, double ball_radius_mm, bool whole_tool,
                const ToolAssembly& tool, const Fixture& fixture, const TriangleTree& part);

  // The tip straight from t0 to t1, the axis blended from a0 to a1.
  [[nodiscard]] bool clear(const Eigen::Vector3d& t0, const Eigen::Vector3d& a0,
                           const Eigen::Vector3d& t1, const Eigen::Vector3d& a1) const;

  // Feed moves through tips[i] with axes[i]: the bodies above the ball only (the ball cuts),
  // by the same margin. The slack measured at a pose is spent over the moves after it (tip
  // travel plus the axis's turn times the tool's length), and measured again once spent:
  // a link of hundreds of short steps costs as many measures as it has millimetres of
  // closing in, not one a step.
  [[nodiscard]] bool feed_clear(std::span<const Eigen::Vector3d> tips,
                                std::span<const Eigen::Vector3d> axes) const;

  // The way a climb from tip `from` (tool along `axis`) to height `z_mm` goes, its points
  // after `from`, the last at z_mm: straight up where that is clear; else back along the
  // axis a tool's length or two, then straight up; else along the axis all the way; none
  // where nothing tried clears (a tool buried under the part). Not for use by two threads.
  [[nodiscard]] std::optional<std::vector<Eigen::Vector3d>>
  climb(const Eigen::Vector3d& from, const Eigen::Vector3d& axis, double z_mm) const;

private:
  struct Climbed {
    Eigen::Vector3d from, axis;
    double z_mm;
    std::optional<std::vector<Eigen::Vector3d>> way;
  };
  [[nodiscard]] std::optional<std::vector<Eigen::Vector3d>>
  find_climb(const Eigen::Vector3d& from, const Eigen::Vector3d& axis, double z_mm) const;

  const LimitDistance* exact_;
  double ball_radius_;
  double tool_length_; // mm, the assembly's reach from the tip (the ball's diameter alone)
  std::optional<AssemblyClearance> assembly_;
  // The last climbs found: a pass's ends are asked for twice (can it be left, then the link
  // that leaves it), each climb a sweep tens of millimetres long. A memo, not state: an
  // answer is the same asked again.
  mutable std::vector<Climbed> recent_;
};

} // namespace subfeed::geometry

#include "geometry/tool_reach.hpp"

#include "geometry/split_work.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace subfeed::geometry {

namespace {

constexpr double deg = std::numbers::pi / 180.0;
// A wall exactly at the limit is in reach; the normals' rounding must not take it out.
constexpr double angle_slack_deg = 1e-6;

double tilt_deg(const Eigen::Vector3d& n) {
  return std::acos(std::clamp(n.z(), -1.0, 1.0)) / deg;
}

} // namespace

double reach_angle_deg(const ReachOptions& options) {
  return options.fixed_axis ? 90.0 : options.max_tilt_deg;
}

bool withdraws(const TriangleTree& design, const Eigen::Vector3d& centre,
               const Eigen::Vector3d& axis, double top_z, const ReachOptions& options) {
  const double r = options.ball_radius;
  // Starting a little way out: the ball touches its own contact point where it stands. The
  // retract may touch the part as a cut may; the rise is a rapid, which may not.
  const Eigen::Vector3d from = centre + 2.0 * options.margin * axis;
  const Eigen::Vector3d back = from + options.clearance_mm * axis;
  if (design.nearest(from, back, r - options.margin)) {
    return false;
  }
  // The ball's lowest point a radius over the top: nothing of the part is left above it.
  const Eigen::Vector3d above(back.x(), back.y(), top_z + 2.0 * r);
  return above.z() <= back.z() || !design.nearest(back, above, r + options.margin);
}

std::vector<ReachLimit> surface_reach(const SurfaceMesh& mesh,
                                      const std::vector<Eigen::Vector3d>& clear_balls,
                                      const std::vector<Eigen::Vector3d>& axes,
                                      const TriangleTree& design, double top_z,
                                      const ReachOptions& options, StageShare* share) {
  const double limit_deg = reach_angle_deg(options) + angle_slack_deg;
  std::vector<ReachLimit> reach(mesh.points.size(), ReachLimit::reached);
  split_work(reach.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      if (share != nullptr) {
        share->tell(begin, v, end);
      }
      if (tilt_deg(mesh.normals[v]) > limit_deg) {
        reach[v] = ReachLimit::tilt;
      } else if (!withdraws(design, clear_balls[v], axes[v], top_z, options)) {
        reach[v] = ReachLimit::hidden;
      }
    }
  });
  return reach;
}

std::vector<char> reached_mask(const std::vector<ReachLimit>& reach) {
  std::vector<char> mask(reach.size());
  std::ranges::transform(reach, mask.begin(),
                         [](ReachLimit l) { return static_cast<char>(l == ReachLimit::reached); });
  return mask;
}

Eigen::Vector3d within_tilt(const Eigen::Vector3d& axis, double max_tilt_deg) {
  if (tilt_deg(axis) <= max_tilt_deg) {
    return axis;
  }
  const Eigen::Vector2d across(axis.x(), axis.y());
  const Eigen::Vector2d toward =
      across.norm() > 1e-12 ? Eigen::Vector2d(across.normalized()) : Eigen::Vector2d(0.0, -1.0);
  const double a = max_tilt_deg * deg;
  return {std::sin(a) * toward.x(), std::sin(a) * toward.y(), std::cos(a)};
}

} // namespace subfeed::geometry

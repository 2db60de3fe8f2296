#pragma once
// Lead and tilt: the tool axis leaned from the axis the planner would otherwise use (the
// averaged surface normal, turned clear of the part where the whole tool needs it), relative
// to the feed direction, so that a ball-end mill does not cut with its tip, where the
// cutting speed is zero. The ball's centre stays where it is: the scallop does not change,
// only the tool's pose about the ball.
//
// Signs, looking along the feed direction with the tool axis up:
//  - lead > 0 leans the tool's top ahead, toward the feed direction (the tip trails); < 0
//    lags (the top behind);
//  - tilt > 0 leans the top to the left of the feed direction; < 0 to the right.
// Lead turns first, in the plane of the axis and the feed direction; tilt then turns across
// it. Zig-zag passes run both ways, so their leaned axes alternate with them.
//
// Where the full lean would break a rule (the whole tool's clearance, the tilt limit, the
// ball's withdrawal), the point takes the largest of 3/4, 1/2, 1/4 and none of it that
// keeps every rule; the lean then changes along the pass by at most `ramp_deg_per_mm`, so
// the axis turns toward the unleaned one smoothly rather than at once.

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace subfeed::geometry {

struct AxisLean {
  double lead_deg = 0.0;
  double tilt_deg = 0.0;
  double ramp_deg_per_mm = 2.0;

  [[nodiscard]] bool any() const { return lead_deg != 0.0 || tilt_deg != 0.0; }
  // The larger of the two turns, degrees.
  [[nodiscard]] double turn_deg() const;
};

// `axis` (unit) leaned by `fraction` of `lean` for feed along `feed` (need not be unit, nor
// square to the axis; a feed along the axis leaves it unleaned).
[[nodiscard]] Eigen::Vector3d leaned_axis(const Eigen::Vector3d& axis, const Eigen::Vector3d& feed,
                                          const AxisLean& lean, double fraction);

// The feed direction at each point of a pass (centres in order): from the point `span_mm`
// behind to the point `span_mm` ahead along it, so that two crossings a hair apart (near a
// mesh vertex) do not turn it. A pass whose last point is its first is a ring, read round
// past its ends, over at most an eighth of its length.
[[nodiscard]] std::vector<Eigen::Vector3d> feed_directions(const std::vector<Eigen::Vector3d>& at,
                                                           double span_mm);

// The fraction of the lean each point takes: the largest of 1, 3/4, 1/2, 1/4 for which
// `keeps(i, fraction)` holds, then ramped along the pass (ramp_deg_per_mm over the arc
// length of `at`) and checked again, stepping down where the ramped one fails; 0 (the axis
// unleaned) is never asked: the caller's unleaned axis keeps the rules already.
[[nodiscard]] std::vector<double>
lean_fractions(const std::vector<Eigen::Vector3d>& at, const AxisLean& lean,
               const std::function<bool(std::size_t, double)>& keeps);

} // namespace subfeed::geometry

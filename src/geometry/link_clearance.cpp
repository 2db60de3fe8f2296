#include "geometry/link_clearance.hpp"

#include "geometry/assembly_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace subfeed::geometry {

namespace {

// Below this axis z a climb along the axis all the way runs more than twice as far sideways
// as up.
constexpr double least_climb_cos = 0.45;
// mm of slack searched for at each measured pose: rapids are long, and a larger cap takes
// longer steps where the tool is well clear (a climb out of a 20 mm gap between two of
// cubes_semisharp's cubes took 5 times as long at 2 mm). Feed moves stay near the part.
constexpr double rapid_slack_cap_mm = 10.0;
constexpr double feed_slack_cap_mm = 2.0;
constexpr std::size_t climbs_remembered = 4;
constexpr double rapid_least_step_mm = 0.02;
// A blend of two axes this far apart turns at most 1.008 times as fast as evenly (the
// sweep's own bound, assembly_sweep.hpp): beyond it a move is swept, not spent from slack.
constexpr double most_blended_turn_rad = 10.0 * std::numbers::pi / 180.0;
constexpr double blend_speed = 1.008;

Fixture with_margin(Fixture fixture) {
  fixture.clearance_min += LinkClearance::body_margin_mm;
  return fixture;
}

} // namespace

LinkClearance::LinkClearance(const LimitDistance& exact, double ball_radius_mm, bool whole_tool,
                             const ToolAssembly& tool, const Fixture& fixture,
                             const TriangleTree& part)
    : exact_(&exact), ball_radius_(ball_radius_mm), tool_length_(2.0 * ball_radius_mm) {
  if (whole_tool) {
    assembly_.emplace(tool, with_margin(fixture), part);
    tool_length_ = assembly_->reach_mm();
  }
}

bool LinkClearance::clear(const Eigen::Vector3d& t0, const Eigen::Vector3d& a0,
                          const Eigen::Vector3d& t1, const Eigen::Vector3d& a1) const {
  const double r = ball_radius_;
  // The ball's centre runs straight only where the axis does not turn: links turn it at
  // the ends, a rapid here never does.
  if (exact_->nearest(t0 + r * a0, t1 + r * a1, r + ball_margin_mm)) {
    return false;
  }
  return !assembly_ ||
         !sweep_move(*assembly_, t0, a0, t1, a1,
                     {.cap_mm = rapid_slack_cap_mm, .least_step_mm = rapid_least_step_mm},
                     nullptr)
              .first;
}

bool LinkClearance::feed_clear(std::span<const Eigen::Vector3d> tips,
                               std::span<const Eigen::Vector3d> axes) const {
  if (!assembly_) {
    return true;
  }
  double budget = 0.0; // mm of slack left from the last pose measured
  for (std::size_t i = 0; i + 1 < tips.size(); ++i) {
    const double turn = std::acos(std::clamp(axes[i].dot(axes[i + 1]), -1.0, 1.0));
    const double closing =
        (tips[i + 1] - tips[i]).norm() + blend_speed * turn * assembly_->reach_mm();
    if (turn <= most_blended_turn_rad && closing < budget) {
      budget -= closing;
      continue;
    }
    const double slack = assembly_->slack(tips[i], axes[i], feed_slack_cap_mm);
    if (slack < 0.0) {
      return false;
    }
    if (turn <= most_blended_turn_rad && closing < slack) {
      budget = slack - closing;
      continue;
    }
    if (sweep_move(*assembly_, tips[i], axes[i], tips[i + 1], axes[i + 1],
                   {.cap_mm = feed_slack_cap_mm, .least_step_mm = rapid_least_step_mm}, nullptr)
            .first) {
      return false;
    }
    budget = 0.0;
  }
  return true;
}

std::optional<std::vector<Eigen::Vector3d>>
LinkClearance::climb(const Eigen::Vector3d& from, const Eigen::Vector3d& axis,
                     double z_mm) const {
  for (const auto& c : recent_) {
    if (c.from == from && c.axis == axis && c.z_mm == z_mm) {
      return c.way;
    }
  }
  auto way = find_climb(from, axis, z_mm);
  if (recent_.size() == climbs_remembered) {
    recent_.erase(recent_.begin());
  }
  recent_.push_back({from, axis, z_mm, way});
  return way;
}

std::optional<std::vector<Eigen::Vector3d>>
LinkClearance::find_climb(const Eigen::Vector3d& from, const Eigen::Vector3d& axis,
                          double z_mm) const {
  const auto straight_up = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(p.x(), p.y(), std::max(z_mm, p.z()));
  };
  if (clear(from, axis, straight_up(from), axis)) {
    return std::vector{straight_up(from)};
  }
  if (!(axis.z() > 0.0) || z_mm <= from.z()) {
    return std::nullopt;
  }
  // Drawn back a tool's length, nothing the tool cleared at `from` is beside it any more.
  const double all_the_way = (z_mm - from.z()) / axis.z();
  for (const double back : {tool_length_, 2.0 * tool_length_}) {
    if (back >= all_the_way) {
      break;
    }
    const Eigen::Vector3d off = from + back * axis;
    if (clear(from, axis, off, axis) && clear(off, axis, straight_up(off), axis)) {
      return std::vector{off, straight_up(off)};
    }
  }
  if (axis.z() >= least_climb_cos) {
    const Eigen::Vector3d along = from + all_the_way * axis;
    if (clear(from, axis, along, axis)) {
      return std::vector{along};
    }
  }
  return std::nullopt;
}

} // namespace subfeed::geometry

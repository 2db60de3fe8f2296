#include "geometry/assembly_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace subfeed::geometry {

namespace {

constexpr double sweep_piece_turn_rad = 10.0 * std::numbers::pi / 180.0;
constexpr double sweep_blend_speed = 1.008; // 1 / cos^2(5 deg)

} // namespace

SweepFindings sweep_move(const AssemblyClearance& clearance, const Eigen::Vector3d& t0,
                         const Eigen::Vector3d& a0, const Eigen::Vector3d& t1,
                         const Eigen::Vector3d& a1, const SweepOptions& options,
                         std::vector<BodyClearance>* into) {
  const double turn = std::acos(std::clamp(a0.dot(a1), -1.0, 1.0));
  const int pieces = std::max(1, static_cast<int>(std::ceil(turn / sweep_piece_turn_rad)));
  // How far any point of the tool moves per unit of a piece's parameter, at most.
  const double speed =
      (t1 - t0).norm() / pieces + sweep_blend_speed * turn / pieces * clearance.reach_mm();
  SweepFindings found;
  const auto sweep = [&](auto&& slack_at) {
    for (int k = 0; k < pieces; ++k) {
      double s = 0.0;
      while (true) {
        const double u = (k + s) / pieces;
        const Eigen::Vector3d tip = (1.0 - u) * t0 + u * t1;
        const Eigen::Vector3d blend = (1.0 - u) * a0 + u * a1;
        const Eigen::Vector3d axis = blend.norm() > 0.0 ? Eigen::Vector3d(blend.normalized()) : a1;
        const double slack = slack_at(tip, axis);
        if (slack < 0.0) {
          ++found.broken;
          if (!found.first) {
            // The same rules measured again, for where and how far; the slack stands if the
            // second search, bounded differently, lands just the other side of a rule.
            found.first = clearance.violation(tip, axis).value_or(
                ClearanceViolation{"tool", false, clearance.fixture().clearance_min + slack, tip});
          }
          if (options.stop_at_first) {
            return;
          }
        }
        if (s >= 1.0 || speed <= 0.0) {
          break;
        }
        s = std::min(1.0, s + std::max(slack, options.least_step_mm) / speed);
      }
    }
  };
  sweep([&](const Eigen::Vector3d& tip, const Eigen::Vector3d& axis) {
    return std::min(clearance.floor_slack(tip, axis, into), options.cap_mm);
  });
  if (found.first && options.stop_at_first) {
    return found;
  }
  sweep([&](const Eigen::Vector3d& tip, const Eigen::Vector3d& axis) {
    return clearance.part_slack(tip, axis, options.cap_mm, into);
  });
  return found;
}

} // namespace subfeed::geometry

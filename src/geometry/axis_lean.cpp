#include "geometry/axis_lean.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace subfeed::geometry {

namespace {

constexpr double lean_rad_per_deg = std::numbers::pi / 180.0;
constexpr std::array<double, 4> lean_steps{1.0, 0.75, 0.5, 0.25};

// Arc length along the points, from the first.
std::vector<double> arc_lengths(const std::vector<Eigen::Vector3d>& at) {
  std::vector<double> s(at.size(), 0.0);
  for (std::size_t i = 1; i < at.size(); ++i) {
    s[i] = s[i - 1] + (at[i] - at[i - 1]).norm();
  }
  return s;
}

// `cap` itself if keeps(i, cap), else the largest step below it that keeps; 0 when none.
double largest_kept(std::size_t i, double cap,
                    const std::function<bool(std::size_t, double)>& keeps) {
  if (cap <= 0.0) {
    return 0.0;
  }
  if (keeps(i, cap)) {
    return cap;
  }
  for (const double f : lean_steps) {
    if (f < cap && keeps(i, f)) {
      return f;
    }
  }
  return 0.0;
}

// Each fraction lowered so it rises or falls at most `per_mm` a millimetre along the pass:
// the lower envelope of cones, a sweep each way.
void ramp(std::vector<double>& f, const std::vector<double>& s, double per_mm) {
  for (std::size_t i = 1; i < f.size(); ++i) {
    f[i] = std::min(f[i], f[i - 1] + per_mm * (s[i] - s[i - 1]));
  }
  for (std::size_t i = f.size(); i-- > 1;) {
    f[i - 1] = std::min(f[i - 1], f[i] + per_mm * (s[i] - s[i - 1]));
  }
}

} // namespace

double AxisLean::turn_deg() const {
  return std::max(std::abs(lead_deg), std::abs(tilt_deg));
}

Eigen::Vector3d leaned_axis(const Eigen::Vector3d& axis, const Eigen::Vector3d& feed,
                            const AxisLean& lean, double fraction) {
  const Eigen::Vector3d along = feed - feed.dot(axis) * axis;
  if (along.norm() < 1e-9 || fraction == 0.0) {
    return axis;
  }
  const Eigen::Vector3d ahead = along.normalized();
  const Eigen::Vector3d left = axis.cross(ahead);
  const double lead = fraction * lean.lead_deg * lean_rad_per_deg;
  const double tilt = fraction * lean.tilt_deg * lean_rad_per_deg;
  const Eigen::Vector3d led = std::cos(lead) * axis + std::sin(lead) * ahead;
  return (std::cos(tilt) * led + std::sin(tilt) * left).normalized();
}

namespace {

// The direction from `span_mm` behind each point to `span_mm` ahead, along an open polyline.
std::vector<Eigen::Vector3d> chord_directions(const std::vector<Eigen::Vector3d>& at,
                                              double span_mm) {
  const auto s = arc_lengths(at);
  std::vector<Eigen::Vector3d> out(at.size(), Eigen::Vector3d::Zero());
  std::size_t behind = 0, ahead = 0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    while (behind + 1 < i && s[i] - s[behind + 1] >= span_mm) {
      ++behind;
    }
    ahead = std::max(ahead, i);
    while (ahead + 1 < at.size() && s[ahead] - s[i] < span_mm) {
      ++ahead;
    }
    out[i] = at[ahead] - at[behind];
  }
  return out;
}

} // namespace

std::vector<Eigen::Vector3d> feed_directions(const std::vector<Eigen::Vector3d>& at,
                                             double span_mm) {
  const bool closed = at.size() > 3 && (at.front() - at.back()).norm() < 1e-9;
  if (!closed) {
    return chord_directions(at, span_mm);
  }
  // A ring: its ends are neighbours, so the points before its start are those before its
  // end, and it is read round past both ends.
  const double length = arc_lengths(at).back();
  span_mm = std::min(span_mm, length / 8.0);
  const std::size_t n = at.size() - 1; // the last repeats the first
  std::vector<Eigen::Vector3d> round;
  for (std::size_t k = 0; k < 3 * n + 1; ++k) {
    round.push_back(at[k % n]);
  }
  const auto dirs = chord_directions(round, span_mm);
  return {dirs.begin() + static_cast<long>(n), dirs.begin() + static_cast<long>(2 * n + 1)};
}

std::vector<double> lean_fractions(const std::vector<Eigen::Vector3d>& at, const AxisLean& lean,
                                   const std::function<bool(std::size_t, double)>& keeps) {
  std::vector<double> f(at.size(), 0.0);
  for (std::size_t i = 0; i < at.size(); ++i) {
    f[i] = largest_kept(i, 1.0, keeps);
  }
  const auto s = arc_lengths(at);
  const double per_mm = lean.ramp_deg_per_mm / std::max(lean.turn_deg(), 1e-9);
  // Lowering one point's fraction can lower a neighbour's cone: ramp, check, until stable.
  // Fractions only fall, each time to a ramp's value or a step below it, so this ends; the
  // bound is for safety, not reached on the sample parts.
  for (int round = 0; round < 1000; ++round) {
    const auto before = f;
    ramp(f, s, per_mm);
    bool changed = false;
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (f[i] != before[i]) {
        f[i] = largest_kept(i, f[i], keeps);
        changed = true;
      }
    }
    if (!changed) {
      break;
    }
  }
  return f;
}

} // namespace subfeed::geometry

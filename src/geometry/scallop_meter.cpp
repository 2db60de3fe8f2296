#include "geometry/scallop_meter.hpp"

#include "geometry/closest_point.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace subfeed::geometry {

namespace {

// Smallest root >= 0 of a t^2 + b t + c = 0, computed without cancellation.
std::optional<double> first_root(double a, double b, double c) {
  const double disc = b * b - 4.0 * a * c;
  if (a <= 0.0 || disc < 0.0) {
    return std::nullopt;
  }
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  double t0 = q / a, t1 = q != 0.0 ? c / q : t0;
  if (t0 > t1) {
    std::swap(t0, t1);
  }
  if (t0 >= 0.0) {
    return t0;
  }
  return t1 >= 0.0 ? std::optional<double>(t1) : std::nullopt;
}

// Where the ray p + t n (n unit, p outside) first enters the capsule: the cylinder around
// the segment's inner part or either end sphere, whichever comes first.
std::optional<double> entry(const Eigen::Vector3d& p, const Eigen::Vector3d& n, const Capsule& c,
                            double t_max) {
  std::optional<double> best;
  const auto keep = [&](std::optional<double> t) {
    if (t && *t <= t_max && (!best || *t < *best)) {
      best = t;
    }
  };
  for (const Eigen::Vector3d* centre : {&c.a, &c.b}) {
    const Eigen::Vector3d m = p - *centre;
    keep(first_root(1.0, 2.0 * m.dot(n), m.squaredNorm() - c.radius * c.radius));
  }
  const Eigen::Vector3d d = c.b - c.a;
  const double length2 = d.squaredNorm();
  if (length2 > 0.0) {
    const Eigen::Vector3d m = p - c.a;
    const Eigen::Vector3d n_perp = n - (n.dot(d) / length2) * d;
    const Eigen::Vector3d m_perp = m - (m.dot(d) / length2) * d;
    const auto t = first_root(n_perp.squaredNorm(), 2.0 * m_perp.dot(n_perp),
                              m_perp.squaredNorm() - c.radius * c.radius);
    if (t) {
      const double along = (m + *t * n).dot(d) / length2;
      if (along >= 0.0 && along <= 1.0) {
        keep(t);
      }
    }
  }
  return best;
}

} // namespace

ScallopSample measure_scallop(const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                              std::span<const Capsule> capsules, double max_height) {
  // The ray enters a capsule no sooner than p's distance to it, d - radius: a capsule
  // farther than the best entry so far cannot improve on it and is not intersected.
  ScallopSample sample;
  double bound = max_height;
  for (const Capsule& c : capsules) {
    const double gap = (p - closest_on_segment(p, c.a, c.b)).norm() - c.radius;
    if (gap < 0.0) {
      sample.gouge_depth = std::max(sample.gouge_depth, -gap);
      sample.height = 0.0;
      bound = 0.0;
      continue;
    }
    if (gap >= bound) {
      continue;
    }
    if (const auto t = entry(p, n, c, bound); t && *t < sample.height) {
      sample.height = *t;
      bound = *t;
    }
  }
  return sample;
}

} // namespace subfeed::geometry

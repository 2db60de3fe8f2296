#include "geometry/scallop_meter.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace subfeed::geometry {

namespace {

double distance_to_segment(const Eigen::Vector3d& p, const Capsule& c) {
  const Eigen::Vector3d ab = c.b - c.a;
  const double length2 = ab.squaredNorm();
  const double u = length2 > 0.0 ? std::clamp((p - c.a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (c.a + u * ab)).norm();
}

// f(t) = distance(p + t n, segment) - r is convex in t (distance to a convex set along a
// line), so its minimum on [0, t_max] is found by golden section and its first root below
// that minimum by bisection.
std::optional<double> entry(const Eigen::Vector3d& p, const Eigen::Vector3d& n, const Capsule& c,
                            double t_max) {
  const auto f = [&](double t) { return distance_to_segment(p + t * n, c) - c.radius; };
  if (f(0.0) <= 0.0) {
    return 0.0;
  }
  constexpr double phi = 0.6180339887498949;
  double lo = 0.0, hi = t_max;
  double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < 200 && hi - lo > 1e-13 * (1.0 + t_max); ++i) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - phi * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + phi * (hi - lo);
      f2 = f(x2);
    }
  }
  double inside = 0.5 * (lo + hi);
  if (f(inside) > 0.0) {
    return std::nullopt; // the ray passes the capsule by
  }
  double outside = 0.0;
  for (int i = 0; i < 200 && inside - outside > 1e-15 * (1.0 + t_max); ++i) {
    const double mid = 0.5 * (outside + inside);
    (f(mid) > 0.0 ? outside : inside) = mid;
  }
  return inside;
}

} // namespace

ScallopSample measure_scallop(const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                              std::span<const Capsule> capsules, double max_height) {
  ScallopSample sample;
  for (const Capsule& c : capsules) {
    const double d = distance_to_segment(p, c);
    if (d < c.radius) {
      sample.gouge_depth = std::max(sample.gouge_depth, c.radius - d);
      sample.height = 0.0;
      continue;
    }
    if (d - c.radius > max_height + 2.0 * c.radius) {
      continue; // too far to reach within max_height
    }
    if (const auto t = entry(p, n, c, max_height); t && *t < sample.height) {
      sample.height = *t;
    }
  }
  return sample;
}

} // namespace subfeed::geometry

#include "geometry/closest_point.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>

namespace subfeed::geometry {

Eigen::Vector3d closest_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                   const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  return length2 > 0.0 ? a + std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) * ab : a;
}

Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    return a;
  }
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) {
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    return a + (d1 / (d1 - d3)) * ab;
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) {
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    return a + (d2 / (d2 - d6)) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double sum = va + vb + vc;
  if (sum <= 0.0) { // degenerate: the nearest of the three edges' ends was handled above
    return a;
  }
  return a + ab * (vb / sum) + ac * (vc / sum);
}

namespace {

// The nearest points of segments p1q1 and p2q2 (Ericson 5.1.9), degenerate ones included.
std::pair<Eigen::Vector3d, Eigen::Vector3d> closest_segments(const Eigen::Vector3d& p1,
                                                             const Eigen::Vector3d& q1,
                                                             const Eigen::Vector3d& p2,
                                                             const Eigen::Vector3d& q2) {
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double tiny = 1e-300;
  double s = 0.0, t = 0.0;
  if (a <= tiny && e <= tiny) {
    return {p1, p2};
  }
  if (a <= tiny) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= tiny) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return {p1 + s * d1, p2 + t * d2};
}

} // namespace

SegmentTriangleNearest closest_segment_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                                const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                const Eigen::Vector3d& c) {
  // A segment that pierces the triangle meets it; otherwise the nearest pair has an end of
  // the segment or a point of a triangle edge in it.
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double sp = n.dot(p - a), sq = n.dot(q - a);
  if ((sp <= 0.0 && sq >= 0.0) || (sp >= 0.0 && sq <= 0.0)) {
    if (sp != sq) {
      const Eigen::Vector3d x = p + (sp / (sp - sq)) * (q - p);
      if ((closest_on_triangle(x, a, b, c) - x).squaredNorm() <= 1e-24 * n.norm()) {
        return {x, x};
      }
    }
  }
  SegmentTriangleNearest best{p, closest_on_triangle(p, a, b, c)};
  const auto consider = [&](const Eigen::Vector3d& s, const Eigen::Vector3d& t) {
    if ((s - t).squaredNorm() < (best.on_segment - best.on_triangle).squaredNorm()) {
      best = {s, t};
    }
  };
  consider(q, closest_on_triangle(q, a, b, c));
  const std::array<std::pair<const Eigen::Vector3d*, const Eigen::Vector3d*>, 3> edges{
      {{&a, &b}, {&b, &c}, {&c, &a}}};
  for (const auto& [u, v] : edges) {
    const auto [s, t] = closest_segments(p, q, *u, *v);
    consider(s, t);
  }
  return best;
}

} // namespace subfeed::geometry

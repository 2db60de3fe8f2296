#pragma once
// A ball lifted along a direction until nothing lies inside it, by whatever answers "the
// nearest point nearer than this": the limit surface (limit_distance.hpp) for poses that go
// to a machine, a mesh of it for what is only decided per vertex. Each round lifts the ball
// clear of the nearest point inside it; lifted, it may meet another (the far wall of a
// groove), so rounds go on until none is inside, at most `most_rounds`.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>

namespace subfeed::geometry {

// `nearest(at, limit)`: the point nearest `at` if nearer than `limit`, else none. Returns
// how far `centre` moves along unit `dir`, mm (0 where nothing is inside the ball); each
// round overshoots by `slack_mm`, so the ball ends at least that clear of the point it met.
template <class Nearest>
double lift_ball(Nearest&& nearest, const Eigen::Vector3d& centre, const Eigen::Vector3d& dir,
                 double radius, double slack_mm, int most_rounds = 16) {
  double total = 0.0;
  for (int round = 0; round < most_rounds; ++round) {
    const Eigen::Vector3d at = centre + total * dir;
    const std::optional<Eigen::Vector3d> inside = nearest(at, radius - slack_mm);
    if (!inside) {
      break;
    }
    // The least s >= 0 with |at + s dir - inside| = radius.
    const Eigen::Vector3d v = at - *inside;
    const double b = v.dot(dir);
    const double c = v.squaredNorm() - radius * radius;
    total += -b + std::sqrt(std::max(0.0, b * b - c)) + slack_mm;
  }
  return total;
}

} // namespace subfeed::geometry

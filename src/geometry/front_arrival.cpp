#include "geometry/front_arrival.hpp"

#include "geometry/vertex_triangles.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace subfeed::geometry {

namespace {

constexpr double never = std::numeric_limits<double>::infinity();

// The least time to reach c through the edge from a (reached at ta) to b (at tb), the
// time along the edge linear between them, crossing the triangle straight with slowness f:
// min over x on [a, b] of t(x) + f |c - x|. Where the minimum lies inside the edge this is
// the time of the planar front through a and b; at an end, the time along that edge.
double across_edge(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   double ta, double tb, double f) {
  const Eigen::Vector3d u = a - b, w = c - b;
  const double length = u.norm();
  const auto at = [&](double lambda) {
    return tb + lambda * (ta - tb) + f * (w - lambda * u).norm();
  };
  double best = std::min(at(0.0), at(1.0));
  if (length <= 0.0 || f <= 0.0) {
    return best;
  }
  const double p = w.dot(u) / length;
  const double q = std::sqrt(std::max(0.0, w.squaredNorm() - p * p));
  const double k = (ta - tb) / (f * length); // the cosine the path makes with the edge
  if (std::abs(k) < 1.0) {
    const double lambda = std::clamp((p - k * q / std::sqrt(1.0 - k * k)) / length, 0.0, 1.0);
    best = std::min(best, at(lambda));
  }
  return best;
}

} // namespace

std::vector<double> front_arrival(const std::vector<Eigen::Vector3d>& p,
                                  const std::vector<std::array<int, 3>>& triangles,
                                  const std::vector<double>& slowness,
                                  const std::vector<int>& sources) {
  const std::size_t n = p.size();
  const auto [start, around] = vertex_triangles(triangles, n);
  std::vector<double> time(n, never);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap;
  for (const int s : sources) {
    time[static_cast<std::size_t>(s)] = 0.0;
    heap.emplace(0.0, s);
  }
  std::vector<char> settled(n, 0);
  const auto offer = [&](std::size_t v, double t) {
    if (settled[v] == 0 && t < time[v]) {
      time[v] = t;
      heap.emplace(t, static_cast<int>(v));
    }
  };
  while (!heap.empty()) {
    const auto [t, vi] = heap.top();
    heap.pop();
    const auto v = static_cast<std::size_t>(vi);
    if (settled[v] != 0 || t > time[v]) {
      continue; // a later, lower time of v has been handled
    }
    settled[v] = 1;
    for (int k = start[v]; k < start[v + 1]; ++k) {
      const auto& tri = triangles[static_cast<std::size_t>(around[static_cast<std::size_t>(k)])];
      for (int corner = 0; corner < 3; ++corner) {
        const auto c = static_cast<std::size_t>(tri[static_cast<std::size_t>(corner)]);
        if (c == v) {
          continue;
        }
        const auto o =
            static_cast<std::size_t>(tri[static_cast<std::size_t>((corner + 1) % 3)] == vi
                                         ? tri[static_cast<std::size_t>((corner + 2) % 3)]
                                         : tri[static_cast<std::size_t>((corner + 1) % 3)]);
        const double f = (slowness[v] + slowness[c] + slowness[o]) / 3.0;
        offer(c, time[v] + 0.5 * (slowness[v] + slowness[c]) * (p[c] - p[v]).norm());
        if (std::isfinite(time[o])) {
          offer(c, across_edge(p[v], p[o], p[c], time[v], time[o], f));
        }
      }
    }
  }
  return time;
}

} // namespace subfeed::geometry

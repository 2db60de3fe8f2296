#include "geometry/pass_insertion.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace subfeed::geometry {

namespace {

// One ring of growth: every triangle takes the largest depth among the triangles that share
// a vertex with it.
void grow_once(const std::vector<std::array<int, 3>>& triangles, std::size_t vertices,
               std::vector<unsigned char>& depth) {
  std::vector<unsigned char> at_vertex(vertices, 0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (const int v : triangles[t]) {
      auto& d = at_vertex[static_cast<std::size_t>(v)];
      d = std::max(d, depth[t]);
    }
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (const int v : triangles[t]) {
      depth[t] = std::max(depth[t], at_vertex[static_cast<std::size_t>(v)]);
    }
  }
}

std::array<std::size_t, 3> corners(const std::array<int, 3>& t) {
  return {static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
          static_cast<std::size_t>(t[2])};
}

} // namespace

Eigen::Vector3d level_gradient(const Eigen::Vector3d& ci, const Eigen::Vector3d& cj,
                               const Eigen::Vector3d& ck, double vi, double vj, double vk) {
  const Eigen::Vector3d e1 = cj - ci, e2 = ck - ci;
  const Eigen::Vector3d normal = e1.cross(e2);
  const double area2 = normal.squaredNorm();
  if (area2 <= 0.0) {
    return Eigen::Vector3d::Zero();
  }
  // The linear function with differences d1, d2 along e1, e2.
  const double d1 = vj - vi, d2 = vk - vi;
  return (d1 * e2.cross(normal) + d2 * normal.cross(e1)) / area2;
}

std::vector<Eigen::Vector3d> vertex_gradients(const std::vector<Eigen::Vector3d>& p,
                                              const std::vector<std::array<int, 3>>& triangles,
                                              const std::vector<double>& deformed) {
  std::vector<Eigen::Vector3d> sum(p.size(), Eigen::Vector3d::Zero());
  std::vector<double> area(p.size(), 0.0);
  for (const auto& t : triangles) {
    const auto [i, j, k] = corners(t);
    const double a = 0.5 * (p[j] - p[i]).cross(p[k] - p[i]).norm();
    const Eigen::Vector3d g =
        a * level_gradient(p[i], p[j], p[k], deformed[i], deformed[j], deformed[k]);
    for (const auto v : {i, j, k}) {
      sum[v] += g;
      area[v] += a;
    }
  }
  for (std::size_t v = 0; v < p.size(); ++v) {
    if (area[v] > 0.0) {
      sum[v] /= area[v];
    }
  }
  return sum;
}

std::vector<double> level_lengths(const std::vector<Eigen::Vector3d>& p,
                                  const std::vector<std::array<int, 3>>& triangles,
                                  const std::vector<double>& deformed, double step) {
  std::vector<double> out(triangles.size(), 0.0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto [i, j, k] = corners(triangles[t]);
    const auto g = level_gradient(p[i], p[j], p[k], deformed[i], deformed[j], deformed[k]);
    out[t] = 0.5 * (p[j] - p[i]).cross(p[k] - p[i]).norm() * g.norm() / step;
  }
  return out;
}

SpacingRatios spacing_ratios(const std::vector<Eigen::Vector3d>& c,
                             const std::vector<std::array<int, 3>>& triangles,
                             const std::vector<double>& deformed, double step,
                             const PassIntervals& intervals) {
  SpacingRatios out;
  out.ratio.assign(triangles.size(), 0.0);
  std::vector<Eigen::Vector3d> gradient(triangles.size());
  std::vector<Eigen::Vector3d> vertex_sum(c.size(), Eigen::Vector3d::Zero());
  std::vector<double> vertex_area(c.size(), 0.0);
  std::vector<double> vertex_length(c.size(), 0.0); // area-weighted |gradient|
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto [i, j, k] = corners(triangles[t]);
    gradient[t] = level_gradient(c[i], c[j], c[k], deformed[i], deformed[j], deformed[k]);
    const double area = 0.5 * (c[j] - c[i]).cross(c[k] - c[i]).norm();
    for (const auto v : {i, j, k}) {
      vertex_sum[v] += area * gradient[t];
      vertex_length[v] += area * gradient[t].norm();
      vertex_area[v] += area;
    }
  }
  const auto ratio_of = [&](const Eigen::Vector3d& g, double need) {
    const double n = g.norm();
    return n > 0.0 ? step / n / need : std::numeric_limits<double>::infinity();
  };
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto [i, j, k] = corners(triangles[t]);
    if (!intervals.cuts(i) || !intervals.cuts(j) || !intervals.cuts(k) ||
        gradient[t].squaredNorm() == 0.0) {
      continue; // unreachable, or a triangle no level crosses: its neighbours decide
    }
    const double need =
        std::min({intervals.cl_spacing[i], intervals.cl_spacing[j], intervals.cl_spacing[k]});
    double r = ratio_of(gradient[t], need);
    // Level lines that kink at a vertex (a chevron) leave a wider gap at the kink than
    // either arm's spacing d: with the arms' normals 2 phi apart, the point of the gap
    // farthest from both lines is d / (1 + cos phi) from them, against d / 2 between
    // straight lines. The area-weighted mean gradient there is shorter than each arm's by
    // cos phi, so the spacing at the kink is 2 step / (|own| + |mean|).
    for (const auto v : {i, j, k}) {
      if (vertex_area[v] > 0.0) {
        const double mean = (vertex_sum[v] / vertex_area[v]).norm();
        const double own = vertex_length[v] / vertex_area[v];
        if (own + mean > 0.0) {
          r = std::max(r, 2.0 * step / (own + mean) / intervals.cl_spacing[v]);
        }
      }
    }
    out.ratio[t] = std::isfinite(r) ? r : 0.0;
    out.worst = std::max(out.worst, out.ratio[t]);
  }
  return out;
}

int level_depth(long index) {
  int depth = max_insertion_depth;
  while (depth > 0 && index % 2 == 0) {
    index /= 2;
    --depth;
  }
  return depth;
}

PassInsertion pass_insertion(const std::vector<Eigen::Vector3d>& c,
                             const std::vector<std::array<int, 3>>& triangles,
                             const std::vector<double>& deformed, double step,
                             const PassIntervals& intervals, double margin, double allowance) {
  return pass_insertion(c, triangles, spacing_ratios(c, triangles, deformed, step, intervals),
                        level_lengths(c, triangles, deformed, step), margin, allowance);
}

PassInsertion pass_insertion(const std::vector<Eigen::Vector3d>& c,
                             const std::vector<std::array<int, 3>>& triangles,
                             const SpacingRatios& measured, const std::vector<double>& level_length,
                             double margin, double allowance) {
  PassInsertion out;
  out.worst_ratio = measured.worst;
  out.depth.assign(triangles.size(), 0);
  double edge_sum = 0.0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto [i, j, k] = corners(triangles[t]);
    edge_sum += (c[j] - c[i]).norm();
    int d = 0;
    while (d < max_insertion_depth && measured.ratio[t] > std::ldexp(1.0, d) * (1.0 + allowance)) {
      ++d;
    }
    out.depth[t] = static_cast<unsigned char>(d);
    out.max_depth = std::max(out.max_depth, d);
  }
  if (out.max_depth > 0) {
    const double edge = edge_sum / static_cast<double>(triangles.size());
    const int rings = std::clamp(static_cast<int>(std::ceil(margin / edge)), 1, 64);
    for (int i = 0; i < rings; ++i) {
      grow_once(triangles, c.size(), out.depth);
    }
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    out.predicted_length += std::ldexp(level_length[t], out.depth[t]);
  }
  return out;
}

} // namespace subfeed::geometry

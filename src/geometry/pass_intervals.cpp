#include "geometry/pass_intervals.hpp"

#include "geometry/step_over.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace subfeed::geometry {

namespace {

// Beyond this radius the curved formulas' x underflows: the surface is flat to rounding.
constexpr double flat_radius = 1e9;

} // namespace

PassIntervals pass_intervals(const SurfaceMesh& mesh, double r, double h, const Eigen::Vector3d& s,
                             const std::vector<char>& in_reach, double min_fraction) {
  PassIntervals out;
  out.in_reach = in_reach;
  const auto n_vertices = static_cast<std::size_t>(mesh.vertex_count());
  out.cl_spacing.resize(n_vertices);
  out.plane_interval.resize(n_vertices);
  out.reachable.assign(n_vertices, 1);
  out.min_interval = std::numeric_limits<double>::infinity();
  const double flat = flat_step(r, h);
  for (std::size_t i = 0; i < n_vertices; ++i) {
    const Eigen::Vector3d& n = mesh.normals[i];
    const double sn = std::clamp(s.dot(n), -1.0, 1.0);
    const Eigen::Vector3d across = s - sn * n;
    double spacing = flat;
    // The ball fits only where the surface bends toward it by less than 1/r in every
    // direction, not only across the passes: a hollow that is narrow along the passes folds
    // the CL surface there as well.
    if (mesh.concave_curvature(static_cast<int>(i)) * r * (1.0 + 1e-9) >= 1.0) {
      out.reachable[i] = 0; // the ball is wider than the hollow
    } else if (across.norm() > 1e-9) {
      const double rho = mesh.radius_along(static_cast<int>(i), across.normalized());
      if (std::abs(rho) < flat_radius) {
        spacing = cl_step(r, h, rho);
      }
    }
    out.cl_spacing[i] = spacing;
    const double interval = std::max(plane_interval(spacing, sn), min_fraction * spacing);
    out.plane_interval[i] = interval;
    if (out.cuts(i)) {
      out.min_interval = std::min(out.min_interval, interval);
      out.max_interval = std::max(out.max_interval, interval);
    }
  }
  if (!std::isfinite(out.min_interval)) {
    out.min_interval = out.max_interval = flat;
  }
  return out;
}

std::vector<double> cl_spacing_across(const SurfaceMesh& mesh, double r, double h,
                                      const std::vector<Eigen::Vector3d>& across,
                                      const std::vector<double>& fallback) {
  std::vector<double> out = fallback;
  const double flat = flat_step(r, h);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Eigen::Vector3d& n = mesh.normals[i];
    const Eigen::Vector3d t = across[i] - across[i].dot(n) * n;
    if (t.norm() <= 1e-9 * std::max(across[i].norm(), 1e-300)) {
      continue;
    }
    const double rho = mesh.radius_along(static_cast<int>(i), t.normalized());
    out[i] = std::abs(rho) < flat_radius ? cl_step(r, h, rho) : flat;
  }
  return out;
}

double ideal_cutting_length(const std::vector<Eigen::Vector3d>& cl_points,
                            const std::vector<std::array<int, 3>>& triangles,
                            const PassIntervals& intervals) {
  double length = 0.0;
  for (const auto& t : triangles) {
    const auto a = static_cast<std::size_t>(t[0]), b = static_cast<std::size_t>(t[1]),
               c = static_cast<std::size_t>(t[2]);
    if (!intervals.cuts(a) || !intervals.cuts(b) || !intervals.cuts(c)) {
      continue;
    }
    const double area =
        0.5 * (cl_points[b] - cl_points[a]).cross(cl_points[c] - cl_points[a]).norm();
    const double spacing =
        (intervals.cl_spacing[a] + intervals.cl_spacing[b] + intervals.cl_spacing[c]) / 3.0;
    length += spacing > 0.0 ? area / spacing : 0.0;
  }
  return length;
}

} // namespace subfeed::geometry

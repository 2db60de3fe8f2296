#include "geometry/deformation.hpp"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <numeric>

namespace subfeed::geometry {

namespace {

using Edge = std::pair<int, int>;

std::vector<Edge> unique_edges(const std::vector<std::array<int, 3>>& triangles) {
  std::vector<Edge> edges;
  edges.reserve(triangles.size() * 3);
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::ranges::sort(edges);
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

// One vertex per connected piece: the one with the least xi.
std::vector<int> anchors(int n, const std::vector<Edge>& edges, const std::vector<double>& xi) {
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      auto& p = parent[static_cast<std::size_t>(v)];
      p = parent[static_cast<std::size_t>(p)];
      v = p;
    }
    return v;
  };
  for (const auto& [a, b] : edges) {
    parent[static_cast<std::size_t>(find(a))] = find(b);
  }
  std::vector<int> best(static_cast<std::size_t>(n), -1);
  for (int v = 0; v < n; ++v) {
    auto& b = best[static_cast<std::size_t>(find(v))];
    if (b < 0 || xi[static_cast<std::size_t>(v)] < xi[static_cast<std::size_t>(b)]) {
      b = v;
    }
  }
  std::vector<int> out;
  for (const int b : best) {
    if (b >= 0) {
      out.push_back(b);
    }
  }
  return out;
}

// Spacing between xi' level lines on each triangle over the spacing its vertices need;
// raises eta on the vertices of triangles where it is too wide. Returns the worst ratio.
double measure_and_raise(const std::vector<Eigen::Vector3d>& c,
                         const std::vector<std::array<int, 3>>& triangles,
                         const std::vector<double>& deformed, double reference,
                         const PassIntervals& intervals, std::vector<double>& eta) {
  std::vector<double> raise(eta.size(), 1.0);
  double worst = 0.0;
  for (const auto& t : triangles) {
    const auto i = static_cast<std::size_t>(t[0]), j = static_cast<std::size_t>(t[1]),
               k = static_cast<std::size_t>(t[2]);
    if (!intervals.reachable[i] || !intervals.reachable[j] || !intervals.reachable[k]) {
      continue;
    }
    const Eigen::Vector3d e1 = c[j] - c[i], e2 = c[k] - c[i];
    const Eigen::Vector3d normal = e1.cross(e2);
    const double area2 = normal.squaredNorm();
    if (area2 <= 0.0) {
      continue;
    }
    // Gradient of the linear function with values d1, d2 along e1, e2 in the triangle.
    const double d1 = deformed[j] - deformed[i], d2 = deformed[k] - deformed[i];
    const Eigen::Vector3d gradient = (d1 * e2.cross(normal) + d2 * normal.cross(e1)) / area2;
    const double g = gradient.norm();
    if (g <= 0.0) {
      continue;
    }
    const double need =
        std::min({intervals.cl_spacing[i], intervals.cl_spacing[j], intervals.cl_spacing[k]});
    const double ratio = reference / g / need;
    worst = std::max(worst, ratio);
    for (const auto v : {i, j, k}) {
      raise[v] = std::max(raise[v], ratio);
    }
  }
  for (std::size_t v = 0; v < eta.size(); ++v) {
    eta[v] *= raise[v] > 1.0 ? raise[v] * 1.02 : 1.0; // a little past, to converge from above
  }
  return worst;
}

} // namespace

Deformation iso_planar(const std::vector<Eigen::Vector3d>& cl_points, const Eigen::Vector3d& s,
                       const PassIntervals& intervals) {
  Deformation d;
  for (const auto& c : cl_points) {
    d.xi.push_back(s.dot(c));
  }
  d.deformed = d.xi;
  d.reference = intervals.min_interval;
  return d;
}

Expected<Deformation> deform_cl_mesh(const std::vector<Eigen::Vector3d>& c,
                                     const std::vector<std::array<int, 3>>& triangles,
                                     const Eigen::Vector3d& s, const PassIntervals& intervals,
                                     int max_iterations) {
  Deformation d = iso_planar(c, s, intervals);
  const int n = static_cast<int>(c.size());
  const auto edges = unique_edges(triangles);
  std::vector<double> eta(c.size());
  for (std::size_t v = 0; v < c.size(); ++v) {
    eta[v] = intervals.reachable[v] ? d.reference / intervals.plane_interval[v] : 1.0;
  }
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(edges.size() * 4 + c.size());
  for (const auto& [a, b] : edges) {
    entries.emplace_back(a, a, 1.0);
    entries.emplace_back(b, b, 1.0);
    entries.emplace_back(a, b, -1.0);
    entries.emplace_back(b, a, -1.0);
  }
  const auto fixed = anchors(n, edges, d.xi);
  const double penalty = 1e6;
  for (const int v : fixed) {
    entries.emplace_back(v, v, penalty);
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
  if (solver.info() != Eigen::Success) {
    return fail(ErrorCode::bad_input, "the CL surface deformation could not be solved");
  }
  Eigen::VectorXd rhs(n);
  for (d.iterations = 1; d.iterations <= max_iterations; ++d.iterations) {
    rhs.setZero();
    for (const auto& [i, j] : edges) {
      const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
      const double target = 0.5 * (eta[ui] + eta[uj]) * (d.xi[uj] - d.xi[ui]);
      rhs[j] += target;
      rhs[i] -= target;
    }
    for (const int v : fixed) {
      rhs[v] += penalty * d.xi[static_cast<std::size_t>(v)];
    }
    const Eigen::VectorXd x = solver.solve(rhs);
    d.deformed.assign(x.data(), x.data() + n);
    d.worst_ratio = measure_and_raise(c, triangles, d.deformed, d.reference, intervals, eta);
    if (d.worst_ratio <= 1.005) {
      break;
    }
  }
  d.iterations = std::min(d.iterations, max_iterations);
  return d;
}

} // namespace subfeed::geometry

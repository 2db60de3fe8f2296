#include "geometry/deformation.hpp"

#include "geometry/mesh_edges.hpp"
#include "geometry/pass_insertion.hpp"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace subfeed::geometry {

namespace {

// One vertex per connected piece: the one with the least xi.
std::vector<int> anchors(int n, const std::vector<MeshEdge>& edges, const std::vector<double>& xi) {
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
  for (const auto& e : edges) {
    parent[static_cast<std::size_t>(find(e.a))] = find(e.b);
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

// The normal equations of the edge differences, each anchor held by a penalty.
Eigen::SparseMatrix<double> normal_matrix(int n, const std::vector<MeshEdge>& edges,
                                          const std::vector<int>& fixed, double penalty) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(edges.size() * 4 + fixed.size());
  for (const auto& e : edges) {
    entries.emplace_back(e.a, e.a, 1.0);
    entries.emplace_back(e.b, e.b, 1.0);
    entries.emplace_back(e.a, e.b, -1.0);
    entries.emplace_back(e.b, e.a, -1.0);
  }
  for (const int v : fixed) {
    entries.emplace_back(v, v, penalty);
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

// Raises eta on the vertices of triangles whose passes lie too far apart, a little past the
// measured ratio so the solves converge from above.
void raise_eta(const std::vector<std::array<int, 3>>& triangles, const SpacingRatios& measured,
               std::vector<double>& eta) {
  std::vector<double> raise(eta.size(), 1.0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (const int v : triangles[t]) {
      auto& r = raise[static_cast<std::size_t>(v)];
      r = std::max(r, measured.ratio[t]);
    }
  }
  for (std::size_t v = 0; v < eta.size(); ++v) {
    eta[v] *= raise[v] > 1.0 ? raise[v] * 1.02 : 1.0;
  }
}

} // namespace

PlaneSpacing space_planes(const std::vector<double>& deformed, double reference) {
  if (deformed.empty()) {
    return {0.0, reference, 0};
  }
  const auto [lo, hi] = std::ranges::minmax_element(deformed);
  const double range = *hi - *lo;
  const double inset = 1e-6 * std::max(range, 1.0);
  const long planes =
      std::max(2L, static_cast<long>(std::ceil((range - 2 * inset) / reference)) + 1);
  return {*lo + inset, (range - 2 * inset) / static_cast<double>(planes - 1), planes};
}

Deformation iso_planar(const std::vector<Eigen::Vector3d>& cl_points, const Eigen::Vector3d& s,
                       const PassIntervals& intervals) {
  Deformation d;
  for (const auto& c : cl_points) {
    d.xi.push_back(s.dot(c));
  }
  d.deformed = d.xi;
  d.reference = intervals.min_interval;
  d.planes = space_planes(d.deformed, d.reference);
  return d;
}

Expected<Deformation> deform_cl_mesh(const std::vector<Eigen::Vector3d>& c,
                                     const std::vector<Eigen::Vector3d>& path_points,
                                     const std::vector<std::array<int, 3>>& triangles,
                                     const Eigen::Vector3d& s, const PassIntervals& intervals,
                                     int max_iterations, double insertion_margin, double allowance,
                                     const SolveProgress& on_solve) {
  Deformation d = iso_planar(c, s, intervals);
  const int n = static_cast<int>(c.size());
  const auto edges = mesh_edges(triangles);
  std::vector<double> eta(c.size());
  for (std::size_t v = 0; v < c.size(); ++v) {
    eta[v] = intervals.reachable[v] ? d.reference / intervals.plane_interval[v] : 1.0;
  }
  const auto fixed = anchors(n, edges, d.xi);
  const double penalty = 1e6;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(
      normal_matrix(n, edges, fixed, penalty));
  if (solver.info() != Eigen::Success) {
    return fail(ErrorCode::bad_input, "the CL surface deformation could not be solved");
  }
  Eigen::VectorXd rhs(n);
  std::vector<double> deformed;
  double cheapest = std::numeric_limits<double>::infinity();
  for (d.iterations = 1; d.iterations <= max_iterations; ++d.iterations) {
    if (on_solve) {
      on_solve(d.iterations, max_iterations);
    }
    rhs.setZero();
    for (const auto& e : edges) {
      const auto ui = static_cast<std::size_t>(e.a), uj = static_cast<std::size_t>(e.b);
      const double target = 0.5 * (eta[ui] + eta[uj]) * (d.xi[uj] - d.xi[ui]);
      rhs[e.b] += target;
      rhs[e.a] -= target;
    }
    for (const int v : fixed) {
      rhs[v] += penalty * d.xi[static_cast<std::size_t>(v)];
    }
    const Eigen::VectorXd x = solver.solve(rhs);
    deformed.assign(x.data(), x.data() + n);
    const auto planes = space_planes(deformed, d.reference);
    const auto measured = spacing_ratios(c, triangles, deformed, planes.step, intervals);
    auto insertion = pass_insertion(c, triangles, measured,
                                    level_lengths(path_points, triangles, deformed, planes.step),
                                    insertion_margin, allowance);
    if (insertion.predicted_length < cheapest) {
      cheapest = insertion.predicted_length;
      d.deformed = deformed;
      d.planes = planes;
      d.worst_ratio = insertion.worst_ratio;
      d.insertion = std::move(insertion);
      d.chosen = d.iterations;
    }
    if (measured.worst <= 1.005) {
      break;
    }
    raise_eta(triangles, measured, eta);
  }
  d.iterations = std::min(d.iterations, max_iterations);
  return d;
}

} // namespace subfeed::geometry

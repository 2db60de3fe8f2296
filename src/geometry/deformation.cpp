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

// The weight of an edge that runs along the passes, against 1 for one across them.
constexpr double along_pass_weight = 0.01;

// Each edge weighs by how far it runs across the passes (along s). An edge along a pass
// asks that xi' not change along it, which holds the passes straight: where the need
// changes along a pass (a dome's top against its walls), straight passes are too far apart
// in one place and too close in another, and the gap takes inserted passes. Weighed
// lightly, those edges let the passes bend toward each other where the need is greater,
// as the paper's row-by-row integration on a grid does; they keep neighbouring rows
// together so the system stays well posed and the passes smooth. Measured on the sample
// parts along X: cutting 1 to 9 % shorter (the saddle 0.8 % longer); links on the dome
// 6.6 m -> 0.1 m, on the seat 1.7 m -> 0.3 m. Weights from 0.01 down to 1e-5 cut within 1 %
// of each other; 0.1 and above lose most of the gain.
std::vector<double> edge_weights(const std::vector<Eigen::Vector3d>& c,
                                 const std::vector<MeshEdge>& edges,
                                 const std::vector<double>& xi) {
  std::vector<double> w(edges.size(), 1.0);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto a = static_cast<std::size_t>(edges[i].a), b = static_cast<std::size_t>(edges[i].b);
    const double length = (c[b] - c[a]).norm();
    const double across = length > 0.0 ? (xi[b] - xi[a]) / length : 0.0;
    w[i] = along_pass_weight + (1.0 - along_pass_weight) * across * across;
  }
  return w;
}

// The normal equations of the weighted edge differences, each anchor held by a penalty.
Eigen::SparseMatrix<double> normal_matrix(int n, const std::vector<MeshEdge>& edges,
                                          const std::vector<double>& w,
                                          const std::vector<int>& fixed, double penalty) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(edges.size() * 4 + fixed.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto& e = edges[i];
    entries.emplace_back(e.a, e.a, w[i]);
    entries.emplace_back(e.b, e.b, w[i]);
    entries.emplace_back(e.a, e.b, -w[i]);
    entries.emplace_back(e.b, e.a, -w[i]);
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
                                     const SolveProgress& on_solve, const NeedAcross& need_across) {
  Deformation d = iso_planar(c, s, intervals);
  const int n = static_cast<int>(c.size());
  const auto edges = mesh_edges(triangles);
  std::vector<double> eta(c.size());
  for (std::size_t v = 0; v < c.size(); ++v) {
    eta[v] = intervals.cuts(v) ? d.reference / intervals.plane_interval[v] : 1.0;
  }
  const auto fixed = anchors(n, edges, d.xi);
  const double penalty = 1e6;
  const auto w = edge_weights(c, edges, d.xi);
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(
      normal_matrix(n, edges, w, fixed, penalty));
  if (solver.info() != Eigen::Success) {
    return fail(ErrorCode::bad_input, "the CL surface deformation could not be solved");
  }
  Eigen::VectorXd rhs(n);
  std::vector<double> deformed;
  double cheapest = std::numeric_limits<double>::infinity();
  PassIntervals measured_against = intervals;
  for (d.iterations = 1; d.iterations <= max_iterations; ++d.iterations) {
    if (on_solve) {
      on_solve(d.iterations, max_iterations);
    }
    rhs.setZero();
    for (std::size_t ei = 0; ei < edges.size(); ++ei) {
      const auto& e = edges[ei];
      const auto ui = static_cast<std::size_t>(e.a), uj = static_cast<std::size_t>(e.b);
      const double target = w[ei] * 0.5 * (eta[ui] + eta[uj]) * (d.xi[uj] - d.xi[ui]);
      rhs[e.b] += target;
      rhs[e.a] -= target;
    }
    for (const int v : fixed) {
      rhs[v] += penalty * d.xi[static_cast<std::size_t>(v)];
    }
    const Eigen::VectorXd x = solver.solve(rhs);
    deformed.assign(x.data(), x.data() + n);
    const auto planes = space_planes(deformed, d.reference);
    if (need_across) {
      measured_against.cl_spacing = need_across(vertex_gradients(c, triangles, deformed));
    }
    const auto measured = spacing_ratios(c, triangles, deformed, planes.step, measured_against);
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

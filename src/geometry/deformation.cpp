#include "geometry/deformation.hpp"

#include "geometry/mesh_edges.hpp"
#include "geometry/pass_insertion.hpp"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
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

// Per vertex, the largest measured/needed spacing of the triangles around it.
std::vector<double> vertex_raise(std::size_t vertices,
                                 const std::vector<std::array<int, 3>>& triangles,
                                 const SpacingRatios& measured) {
  std::vector<double> raise(vertices, 1.0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (const int v : triangles[t]) {
      auto& r = raise[static_cast<std::size_t>(v)];
      r = std::max(r, measured.ratio[t]);
    }
  }
  return raise;
}

// Raises eta where the passes lie too far apart, a little past the measured ratio so the
// solves converge from above.
void raise_eta(const std::vector<double>& raise, std::vector<double>& eta) {
  for (std::size_t v = 0; v < eta.size(); ++v) {
    eta[v] *= raise[v] > 1.0 ? raise[v] * 1.02 : 1.0;
  }
}

// One solve's planes, what the passes between them still need, and how far apart they lie
// against the need per triangle.
struct Priced {
  PlaneSpacing planes;
  SpacingRatios measured;
  PassInsertion insertion;
};

Priced price(const DeformedMesh& m, const std::vector<double>& deformed, double reference,
             PassIntervals& measured_against, double insertion_margin, double allowance) {
  Priced p;
  p.planes = space_planes(deformed, reference);
  if (m.need_across) {
    measured_against.cl_spacing =
        m.need_across(vertex_gradients(m.cl_points, m.triangles, deformed));
  }
  p.measured = spacing_ratios(m.cl_points, m.triangles, deformed, p.planes.step, measured_against);
  p.insertion = pass_insertion(m.cl_points, m.triangles, p.measured,
                               level_lengths(m.path_points, m.triangles, deformed, p.planes.step),
                               insertion_margin, allowance);
  return p;
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

namespace {

// The normal equations of one mesh and slicing normal, factorised once: xi' for any eta.
class DeformationSystem {
public:
  [[nodiscard]] static Expected<DeformationSystem>
  build(const std::vector<Eigen::Vector3d>& c, const std::vector<std::array<int, 3>>& triangles,
        const std::vector<double>& xi) {
    DeformationSystem system;
    system.n_ = static_cast<int>(c.size());
    system.edges_ = mesh_edges(triangles);
    system.fixed_ = anchors(system.n_, system.edges_, xi);
    system.w_ = edge_weights(c, system.edges_, xi);
    system.solver_ = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(
        normal_matrix(system.n_, system.edges_, system.w_, system.fixed_, penalty));
    if (system.solver_->info() != Eigen::Success) {
      return fail(ErrorCode::bad_input, "the CL surface deformation could not be solved");
    }
    return system;
  }

  [[nodiscard]] std::vector<double> solve(const std::vector<double>& xi,
                                          const std::vector<double>& eta) const {
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n_);
    for (std::size_t ei = 0; ei < edges_.size(); ++ei) {
      const auto& e = edges_[ei];
      const auto ui = static_cast<std::size_t>(e.a), uj = static_cast<std::size_t>(e.b);
      const double target = w_[ei] * 0.5 * (eta[ui] + eta[uj]) * (xi[uj] - xi[ui]);
      rhs[e.b] += target;
      rhs[e.a] -= target;
    }
    for (const int v : fixed_) {
      rhs[v] += penalty * xi[static_cast<std::size_t>(v)];
    }
    const Eigen::VectorXd x = solver_->solve(rhs);
    return {x.data(), x.data() + n_};
  }

private:
  static constexpr double penalty = 1e6;
  int n_ = 0;
  std::vector<MeshEdge> edges_;
  std::vector<int> fixed_;
  std::vector<double> w_;
  std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> solver_;
};

// One solve measured: xi' on the mesh it is priced on, its price, and per vertex of the
// solved mesh how far eta must rise.
struct Round {
  std::vector<double> deformed;
  Priced priced;
  std::vector<double> raise;
};
using Measure = std::function<Round(std::vector<double> solved, const std::vector<double>& eta)>;

// A solve on `m` measured and priced on `m` itself, eta to rise at its own vertices.
Round measured_on(const DeformedMesh& m, std::vector<double> deformed, double reference,
                  PassIntervals& against, double insertion_margin, double allowance) {
  Round round;
  round.priced = price(m, deformed, reference, against, insertion_margin, allowance);
  round.raise = vertex_raise(m.cl_points.size(), m.triangles, round.priced.measured);
  round.deformed = std::move(deformed);
  return round;
}

// Solves `rounds` times at most from `eta`, keeping in `d` the cheapest solve and in
// `kept_eta` its eta, and stops once the passes are nowhere wider than the need.
void solve_rounds(const DeformationSystem& system, const std::vector<double>& xi,
                  std::vector<double> eta, int rounds, const Measure& measure,
                  const std::function<void()>& on_solve, Deformation& d,
                  std::vector<double>& kept_eta) {
  double cheapest = std::numeric_limits<double>::infinity();
  for (int i = 1; i <= rounds; ++i) {
    on_solve();
    ++d.iterations;
    auto round = measure(system.solve(xi, eta), eta);
    if (round.priced.insertion.predicted_length < cheapest) {
      cheapest = round.priced.insertion.predicted_length;
      d.deformed = std::move(round.deformed);
      d.planes = round.priced.planes;
      d.worst_ratio = round.priced.insertion.worst_ratio;
      d.insertion = std::move(round.priced.insertion);
      d.chosen = d.iterations;
      kept_eta = eta;
    }
    if (round.priced.measured.worst <= 1.005) {
      break;
    }
    raise_eta(round.raise, eta);
  }
}

// xi' on the fine mesh. A fine vertex lies off its coarse triangle's chord by
// delta = xi - (xi carried), and xi' rises eta times as fast as xi there: so xi' carried
// plus eta * delta. (Carried alone, xi' is off by the chord's sag: on a 190 mm shell with
// 1 mm coarse cells up to 0.12 mm, five plane steps, and the fine passes cut 4 times longer.)
std::vector<double> carry(const CoarseMesh& map, const std::vector<double>& solved,
                          const std::vector<double>& eta, const std::vector<double>& fine_xi,
                          const std::vector<double>& carried_xi) {
  auto out = map.to_fine(solved);
  const auto fine_eta = map.to_fine(eta);
  for (std::size_t v = 0; v < out.size(); ++v) {
    out[v] += fine_eta[v] * (fine_xi[v] - carried_xi[v]);
  }
  return out;
}

// A fine vertex's raise, at each coarse vertex it is carried from.
std::vector<double> raise_at_corners(const CoarseMesh& map, const std::vector<double>& fine_raise,
                                     std::size_t coarse_vertices) {
  std::vector<double> raise(coarse_vertices, 1.0);
  for (std::size_t v = 0; v < fine_raise.size(); ++v) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (map.fine_weights[v][static_cast<Eigen::Index>(k)] > 0.0) {
        auto& r = raise[static_cast<std::size_t>(map.fine_corners[v][k])];
        r = std::max(r, fine_raise[v]);
      }
    }
  }
  return raise;
}

std::vector<double> initial_eta(const PassIntervals& intervals, double reference) {
  std::vector<double> eta(intervals.plane_interval.size());
  for (std::size_t v = 0; v < eta.size(); ++v) {
    eta[v] = intervals.cuts(v) ? reference / intervals.plane_interval[v] : 1.0;
  }
  return eta;
}

} // namespace

Expected<Deformation> deform_cl_mesh(const std::vector<Eigen::Vector3d>& c,
                                     const std::vector<Eigen::Vector3d>& path_points,
                                     const std::vector<std::array<int, 3>>& triangles,
                                     const Eigen::Vector3d& s, const PassIntervals& intervals,
                                     int max_iterations, double insertion_margin, double allowance,
                                     const SolveProgress& on_solve, const NeedAcross& need_across) {
  Deformation d = iso_planar(c, s, intervals);
  SUBFEED_TRY_ASSIGN(const auto system, DeformationSystem::build(c, triangles, d.xi));
  PassIntervals measured_against = intervals;
  const DeformedMesh mesh{c, path_points, triangles, intervals, need_across};
  const auto measure = [&](std::vector<double> deformed, const std::vector<double>&) {
    return measured_on(mesh, std::move(deformed), d.reference, measured_against, insertion_margin,
                       allowance);
  };
  std::vector<double> kept_eta;
  solve_rounds(
      system, d.xi, initial_eta(intervals, d.reference), max_iterations, measure,
      [&] {
        if (on_solve) {
          on_solve(d.iterations + 1, max_iterations);
        }
      },
      d, kept_eta);
  return d;
}

Expected<Deformation> deform_on_coarse(const DeformedMesh& coarse, const CoarseMesh& map,
                                       const DeformedMesh& fine, const Eigen::Vector3d& s,
                                       const DeformSettings& settings) {
  const int most = settings.coarse_rounds + settings.fine_rounds;
  const auto told = [&settings, most](const Deformation& counted) {
    return [&settings, most, solves = &counted] {
      if (settings.on_solve) {
        settings.on_solve(solves->iterations + 1, most);
      }
    };
  };
  // First on the coarse mesh alone, as deform_cl_mesh does.
  Deformation on_coarse = iso_planar(coarse.cl_points, s, coarse.intervals);
  SUBFEED_TRY_ASSIGN(const auto system,
                     DeformationSystem::build(coarse.cl_points, coarse.triangles, on_coarse.xi));
  PassIntervals coarse_against = coarse.intervals;
  const auto measure_coarse = [&](std::vector<double> deformed, const std::vector<double>&) {
    return measured_on(coarse, std::move(deformed), on_coarse.reference, coarse_against,
                       settings.insertion_margin, settings.allowance);
  };
  std::vector<double> kept_eta = initial_eta(coarse.intervals, on_coarse.reference);
  solve_rounds(system, on_coarse.xi, kept_eta, settings.coarse_rounds, measure_coarse,
               told(on_coarse), on_coarse, kept_eta);
  // Then measured on the fine mesh, whose need varies within a coarse cell (a fillet's
  // curvature): eta rises at the coarse corners of every fine triangle still too wide.
  Deformation d = iso_planar(fine.cl_points, s, fine.intervals);
  d.iterations = on_coarse.iterations;
  PassIntervals fine_against = fine.intervals;
  const auto carried_xi = map.to_fine(on_coarse.xi);
  const auto measure_fine = [&](const std::vector<double>& solved, const std::vector<double>& eta) {
    Round round;
    round.deformed = carry(map, solved, eta, d.xi, carried_xi);
    round.priced = price(fine, round.deformed, d.reference, fine_against, settings.insertion_margin,
                         settings.allowance);
    round.raise = raise_at_corners(
        map, vertex_raise(fine.cl_points.size(), fine.triangles, round.priced.measured),
        solved.size());
    return round;
  };
  std::vector<double> kept;
  solve_rounds(system, on_coarse.xi, std::move(kept_eta), settings.fine_rounds, measure_fine,
               told(d), d, kept);
  return d;
}

} // namespace subfeed::geometry

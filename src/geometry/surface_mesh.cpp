#include "geometry/surface_mesh.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace subfeed::geometry {

namespace {

// Normals of the same point from two faces that differ by more than 2 degrees are the two
// sides of a sharp crease: those vertices stay apart.
const double same_normal_dot = std::cos(2.0 * 3.14159265358979323846 / 180.0);

} // namespace

double lowest_z(const SurfaceMesh& mesh) {
  return lowest_point(mesh).z();
}

Eigen::Vector3d lowest_point(const SurfaceMesh& mesh) {
  return std::ranges::min(mesh.points, {}, [](const Eigen::Vector3d& p) { return p.z(); });
}

Eigen::Matrix3d curvature_matrix(const LimitSample& s) {
  Eigen::Matrix<double, 3, 2> j;
  j << s.du, s.dv;
  Eigen::Matrix2d first;
  first << s.du.dot(s.du), s.du.dot(s.dv), s.du.dot(s.dv), s.dv.dot(s.dv);
  Eigen::Matrix2d second;
  second << s.duu.dot(s.normal), s.duv.dot(s.normal), s.duv.dot(s.normal), s.dvv.dot(s.normal);
  const Eigen::Matrix2d inv = first.inverse();
  const Eigen::Matrix<double, 3, 2> pinv_t = j * inv; // (J^+)^T
  return pinv_t * second * pinv_t.transpose();
}

double SurfaceMesh::radius_along(int i, const Eigen::Vector3d& t) const {
  const double kappa = t.dot(curvature[static_cast<std::size_t>(i)] * t);
  if (kappa == 0.0) {
    return std::numeric_limits<double>::infinity();
  }
  return -1.0 / kappa;
}

double SurfaceMesh::concave_curvature(int i) const {
  // W maps the tangent plane into itself and the normal to zero, so its largest eigenvalue
  // is the largest normal curvature over tangent directions (or 0 where all are convex).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(curvature[static_cast<std::size_t>(i)],
                                                             Eigen::EigenvaluesOnly);
  return eigen.eigenvalues().maxCoeff();
}

std::vector<int> rates_for_tolerance(const LimitSurface& surface, double chord_tolerance,
                                     int max_rate, double max_edge_mm, double min_edge_mm) {
  std::vector<int> rates(static_cast<std::size_t>(surface.face_count()), 0);
  constexpr int grid = 5;
  for (int f = 0; f < surface.face_count(); ++f) {
    if (!surface.has_patch(f)) {
      continue;
    }
    double worst = 0.0, stretch = 0.0; // |S''.n| and the longest parameter derivative
    for (const auto& uv : surface.tessellate(f, grid).uv) {
      const auto s = surface.evaluate_regular(f, uv.x(), uv.y());
      if (!s) {
        continue;
      }
      // Along u, v and both diagonals of a parameter cell (triangles take one of them).
      const double uu = s->duu.dot(s->normal), mixed = s->duv.dot(s->normal),
                   vv = s->dvv.dot(s->normal);
      worst = std::max({worst, std::abs(uu), std::abs(vv), std::abs(uu + 2 * mixed + vv),
                        std::abs(uu - 2 * mixed + vv)});
      stretch = std::max({stretch, s->du.norm(), s->dv.norm()});
    }
    // A chord over parameter step d/rate sags by |S''(d, d).n| / (8 rate^2).
    double rate = std::ceil(std::sqrt(worst / (8.0 * chord_tolerance)));
    if (min_edge_mm > 0.0) {
      rate = std::min(rate, std::ceil(stretch / min_edge_mm));
    }
    if (max_edge_mm > 0.0) {
      rate = std::max(rate, std::ceil(stretch / max_edge_mm));
    }
    rates[static_cast<std::size_t>(f)] =
        static_cast<int>(std::clamp(rate, 2.0, static_cast<double>(max_rate)));
  }
  return rates;
}

Expected<SurfaceMesh> mesh_surface(const Cage& cage, const LimitSurface& surface, int rate) {
  return mesh_surface(cage, surface,
                      std::vector<int>(static_cast<std::size_t>(surface.face_count()), rate));
}

std::vector<std::vector<int>> edge_rates_per_face(const Cage& cage, const LimitSurface& surface,
                                                  const std::vector<int>& face_rates) {
  std::map<std::pair<long, long>, int> edge_rate;
  const auto edge_key = [](long a, long b) { return std::pair{std::min(a, b), std::max(a, b)}; };
  for (int f = 0; f < surface.face_count(); ++f) {
    const auto loop = cage.face(f);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      auto& r = edge_rate[edge_key(loop[i], loop[(i + 1) % loop.size()])];
      r = std::max(r, face_rates[static_cast<std::size_t>(f)]);
    }
  }
  std::vector<std::vector<int>> out(static_cast<std::size_t>(surface.face_count()));
  for (int f = 0; f < surface.face_count(); ++f) {
    const auto loop = cage.face(f);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      out[static_cast<std::size_t>(f)].push_back(
          edge_rate[edge_key(loop[i], loop[(i + 1) % loop.size()])]);
    }
  }
  return out;
}

Expected<SurfaceMesh> mesh_surface(const Cage& cage, const LimitSurface& surface,
                                   const std::vector<int>& face_rates, StageShare* share) {
  SurfaceMesh mesh;
  mesh.face_rates = face_rates;
  const auto edge_rates = edge_rates_per_face(cage, surface, face_rates);
  // Points on a cage edge or corner are shared with the neighbouring faces: keyed by the
  // cage topology (Bfr lists a face's boundary points first, corner by corner, then the
  // edge's inner points), not by position, since two faces' approximations of the same
  // edge may differ in the last digits near irregular features.
  std::map<std::array<long, 3>, std::vector<int>> shared;
  const auto faces = static_cast<std::size_t>(surface.face_count());
  for (int f = 0; f < surface.face_count(); ++f) {
    mesh.face_points_begin.push_back(static_cast<int>(mesh.face_points.size()));
    if (share != nullptr) {
      share->tell(0, static_cast<std::size_t>(f), faces);
    }
    if (!surface.has_patch(f)) {
      continue;
    }
    const auto loop = cage.face(f);
    const auto n = loop.size();
    const auto& rates = edge_rates[static_cast<std::size_t>(f)];
    std::vector<long> edge_of, step_of; // per boundary point: its edge and index along it
    for (std::size_t e = 0; e < n; ++e) {
      mesh.rate = std::max(mesh.rate, rates[e]);
      for (int j = 0; j < rates[e]; ++j) {
        edge_of.push_back(static_cast<long>(e));
        step_of.push_back(j);
      }
    }
    const auto tess = surface.tessellate(f, rates, face_rates[static_cast<std::size_t>(f)]);
    std::vector<int> index(tess.uv.size());
    for (std::size_t k = 0; k < tess.uv.size(); ++k) {
      SUBFEED_TRY_ASSIGN(const auto s, surface.evaluate_regular(f, tess.uv[k].x(), tess.uv[k].y()));
      std::vector<int>* same_place = nullptr;
      if (k < edge_of.size()) {
        const auto e = static_cast<std::size_t>(edge_of[k]);
        const long j = step_of[k], rate = rates[e];
        const long v0 = loop[e], v1 = loop[(e + 1) % n];
        const std::array<long, 3> key = j == 0    ? std::array<long, 3>{v0, -1, 0}
                                        : v0 < v1 ? std::array<long, 3>{v0, v1, j}
                                                  : std::array<long, 3>{v1, v0, rate - j};
        same_place = &shared[key];
        const auto found = std::ranges::find_if(*same_place, [&](int v) {
          return mesh.normals[static_cast<std::size_t>(v)].dot(s.normal) > same_normal_dot;
        });
        if (found != same_place->end()) {
          index[k] = *found;
          continue;
        }
      }
      index[k] = mesh.vertex_count();
      if (same_place != nullptr) {
        same_place->push_back(index[k]);
      }
      mesh.points.push_back(s.point);
      mesh.normals.push_back(s.normal);
      mesh.curvature.push_back(curvature_matrix(s));
    }
    mesh.face_points.insert(mesh.face_points.end(), index.begin(), index.end());
    for (const auto& t : tess.triangles) {
      mesh.triangles.push_back({index[static_cast<std::size_t>(t[0])],
                                index[static_cast<std::size_t>(t[1])],
                                index[static_cast<std::size_t>(t[2])]});
    }
  }
  mesh.face_points_begin.push_back(static_cast<int>(mesh.face_points.size()));
  if (mesh.triangles.empty()) {
    return fail(ErrorCode::bad_input, "the cage has no limit surface to machine");
  }
  return mesh;
}

} // namespace subfeed::geometry

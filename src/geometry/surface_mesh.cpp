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

int rate_for_tolerance(const LimitSurface& surface, double chord_tolerance, int max_rate) {
  double worst = 0.0;
  constexpr int grid = 5;
  for (int f = 0; f < surface.face_count(); ++f) {
    if (!surface.has_patch(f)) {
      continue;
    }
    for (const auto& uv : surface.tessellate(f, grid).uv) {
      const auto s = surface.evaluate_regular(f, uv.x(), uv.y());
      if (!s) {
        continue;
      }
      worst = std::max({worst, std::abs(s->duu.dot(s->normal)), std::abs(s->dvv.dot(s->normal)),
                        std::abs(s->duv.dot(s->normal))});
    }
  }
  // A chord over parameter length 1/rate sags by |S''.n| / (8 rate^2).
  const double rate = std::ceil(std::sqrt(worst / (8.0 * chord_tolerance)));
  return static_cast<int>(std::clamp(rate, 2.0, static_cast<double>(max_rate)));
}

Expected<SurfaceMesh> mesh_surface(const Cage& cage, const LimitSurface& surface, int rate) {
  SurfaceMesh mesh;
  mesh.rate = rate;
  // Points on a cage edge or corner are shared with the neighbouring faces: keyed by the
  // cage topology (Bfr lists a face's boundary points first, corner by corner, rate per
  // edge), not by position, since two faces' approximations of the same edge may differ
  // in the last digits near irregular features.
  std::map<std::array<long, 3>, std::vector<int>> shared;
  for (int f = 0; f < surface.face_count(); ++f) {
    const auto tess = surface.tessellate(f, rate);
    const auto loop = cage.face(f);
    const auto n = static_cast<long>(loop.size());
    std::vector<int> index(tess.uv.size());
    for (std::size_t k = 0; k < tess.uv.size(); ++k) {
      SUBFEED_TRY_ASSIGN(const auto s, surface.evaluate_regular(f, tess.uv[k].x(), tess.uv[k].y()));
      std::vector<int>* same_place = nullptr;
      if (static_cast<long>(k) < n * rate) {
        const long e = static_cast<long>(k) / rate, j = static_cast<long>(k) % rate;
        const long v0 = loop[static_cast<std::size_t>(e)],
                   v1 = loop[static_cast<std::size_t>((e + 1) % n)];
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
    for (const auto& t : tess.triangles) {
      mesh.triangles.push_back({index[static_cast<std::size_t>(t[0])],
                                index[static_cast<std::size_t>(t[1])],
                                index[static_cast<std::size_t>(t[2])]});
    }
  }
  if (mesh.triangles.empty()) {
    return fail(ErrorCode::bad_input, "the cage has no limit surface to machine");
  }
  return mesh;
}

} // namespace subfeed::geometry

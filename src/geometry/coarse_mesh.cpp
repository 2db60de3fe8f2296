#include "geometry/coarse_mesh.hpp"

#include "geometry/closest_point.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace subfeed::geometry {

namespace {

// Barycentric weights of p in the triangle (a, b, c) of the parameter plane.
Eigen::Vector3d barycentric(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  Eigen::Matrix2d m;
  m << b - a, c - a;
  const double det = m.determinant();
  if (std::abs(det) < 1e-300) {
    return {1.0, 0.0, 0.0};
  }
  const Eigen::Vector2d st = m.inverse() * (p - a);
  return {1.0 - st.x() - st.y(), st.x(), st.y()};
}

// Barycentric weights of the point of triangle (a, b, c) nearest p.
Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d q = closest_on_triangle(p, a, b, c);
  const Eigen::Vector3d e0 = b - a, e1 = c - a, d = q - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double det = d00 * d11 - d01 * d01;
  if (det <= 1e-300) {
    return {1.0, 0.0, 0.0};
  }
  const double s = (d11 * e0.dot(d) - d01 * e1.dot(d)) / det;
  const double t = (d00 * e1.dot(d) - d01 * e0.dot(d)) / det;
  return {1.0 - s - t, s, t};
}

// One face's tessellation, where its points landed in a mesh, and its triangles bucketed
// over the face's parameter domain so a point finds its triangle in a few tests. Bfr lays
// a face of other than four sides out as one tile per corner (a Catmull-Clark triangle
// too), and a triangle along the border of two tiles spans the domain between them: there
// the triangle is found by the point's position instead (such faces are few: one
// subdivision step leaves none).
class FaceCells {
public:
  FaceCells(FaceTessellation tess, std::span<const int> vertex, int cells_across,
            const std::vector<Eigen::Vector3d>* by_position)
      : tess_(std::move(tess)), vertex_(vertex), n_(std::max(1, cells_across)),
        points_(by_position) {
    lo_ = hi_ = tess_.uv.front();
    for (const auto& uv : tess_.uv) {
      lo_ = lo_.cwiseMin(uv);
      hi_ = hi_.cwiseMax(uv);
    }
    size_ = (hi_ - lo_).cwiseMax(Eigen::Vector2d::Constant(1e-12));
    cells_.resize(static_cast<std::size_t>(n_ * n_));
    for (std::size_t t = 0; t < tess_.triangles.size(); ++t) {
      Eigen::Vector2d a = corner(t, 0), b = a;
      for (int k = 1; k < 3; ++k) {
        a = a.cwiseMin(corner(t, k));
        b = b.cwiseMax(corner(t, k));
      }
      const auto [x0, y0] = cell(a);
      const auto [x1, y1] = cell(b);
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          cells_[static_cast<std::size_t>(y * n_ + x)].push_back(static_cast<int>(t));
        }
      }
    }
  }

  [[nodiscard]] const FaceTessellation& tessellation() const { return tess_; }
  [[nodiscard]] int vertex(std::size_t point) const { return vertex_[point]; }

  // The mesh vertices of the triangle holding uv and their weights there. Rounding may put
  // a point on the domain's edge a hair outside every triangle: the least outside is taken.
  [[nodiscard]] std::pair<std::array<int, 3>, Eigen::Vector3d>
  locate(const Eigen::Vector2d& uv, const Eigen::Vector3d& p) const {
    std::size_t best = 0;
    Eigen::Vector3d best_w(1.0, 0.0, 0.0);
    if (points_ != nullptr) {
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t t = 0; t < tess_.triangles.size(); ++t) {
        const auto& a = at(t, 0);
        const auto w = barycentric(p, a, at(t, 1), at(t, 2));
        const double d = (w.x() * a + w.y() * at(t, 1) + w.z() * at(t, 2) - p).squaredNorm();
        if (d < nearest) {
          nearest = d;
          best = t;
          best_w = w;
        }
      }
    } else {
      const auto [x, y] = cell(uv);
      double best_inside = -std::numeric_limits<double>::infinity();
      for (const int t : cells_[static_cast<std::size_t>(y * n_ + x)]) {
        const auto w = barycentric(uv, corner(t, 0), corner(t, 1), corner(t, 2));
        if (w.minCoeff() > best_inside) {
          best_inside = w.minCoeff();
          best = static_cast<std::size_t>(t);
          best_w = w;
        }
      }
    }
    const auto& tri = tess_.triangles[best];
    const Eigen::Vector3d clamped = best_w.cwiseMax(0.0);
    return {{vertex_[static_cast<std::size_t>(tri[0])], vertex_[static_cast<std::size_t>(tri[1])],
             vertex_[static_cast<std::size_t>(tri[2])]},
            clamped / clamped.sum()};
  }

private:
  [[nodiscard]] const Eigen::Vector2d& corner(std::size_t t, int k) const {
    return tess_.uv[static_cast<std::size_t>(tess_.triangles[t][static_cast<std::size_t>(k)])];
  }
  [[nodiscard]] const Eigen::Vector3d& at(std::size_t t, int k) const {
    return (*points_)[static_cast<std::size_t>(
        vertex_[static_cast<std::size_t>(tess_.triangles[t][static_cast<std::size_t>(k)])])];
  }
  [[nodiscard]] std::pair<int, int> cell(const Eigen::Vector2d& uv) const {
    const Eigen::Vector2d at = (uv - lo_).cwiseQuotient(size_) * n_;
    return {std::clamp(static_cast<int>(std::floor(at.x())), 0, n_ - 1),
            std::clamp(static_cast<int>(std::floor(at.y())), 0, n_ - 1)};
  }

  FaceTessellation tess_;
  std::span<const int> vertex_;
  int n_;
  const std::vector<Eigen::Vector3d>* points_; // the mesh's, where found by position
  Eigen::Vector2d lo_, hi_, size_;
  std::vector<std::vector<int>> cells_;
};

std::span<const int> face_points(const SurfaceMesh& mesh, int f) {
  const auto begin = static_cast<std::size_t>(mesh.face_points_begin[static_cast<std::size_t>(f)]);
  const auto end =
      static_cast<std::size_t>(mesh.face_points_begin[static_cast<std::size_t>(f) + 1]);
  return std::span<const int>(mesh.face_points).subspan(begin, end - begin);
}

} // namespace

std::vector<double> CoarseMesh::to_fine(const std::vector<double>& coarse) const {
  std::vector<double> out(fine_corners.size());
  for (std::size_t v = 0; v < out.size(); ++v) {
    const auto& c = fine_corners[v];
    const auto& w = fine_weights[v];
    out[v] = w.x() * coarse[static_cast<std::size_t>(c[0])] +
             w.y() * coarse[static_cast<std::size_t>(c[1])] +
             w.z() * coarse[static_cast<std::size_t>(c[2])];
  }
  return out;
}

Expected<CoarseMesh> coarse_mesh(const Cage& cage, const LimitSurface& surface,
                                 const SurfaceMesh& fine, int factor) {
  std::vector<int> rates;
  for (const int r : fine.face_rates) {
    rates.push_back(r == 0 ? 0 : std::max(1, (r + factor / 2) / factor));
  }
  CoarseMesh out;
  SUBFEED_TRY_ASSIGN(out.mesh, mesh_surface(cage, surface, rates));
  const auto fine_edges = edge_rates_per_face(cage, surface, fine.face_rates);
  const auto coarse_edges = edge_rates_per_face(cage, surface, rates);
  out.fine_corners.assign(fine.points.size(), {-1, -1, -1});
  out.fine_weights.assign(fine.points.size(), Eigen::Vector3d::Zero());
  out.nearest_fine.assign(out.mesh.points.size(), -1);
  for (int f = 0; f < surface.face_count(); ++f) {
    const auto i = static_cast<std::size_t>(f);
    if (!surface.has_patch(f)) {
      continue;
    }
    const bool tiled = surface.face_size(f) != 4;
    const FaceCells fine_face(surface.tessellate(f, fine_edges[i], fine.face_rates[i]),
                              face_points(fine, f), fine.face_rates[i],
                              tiled ? &fine.points : nullptr);
    const FaceCells coarse_face(surface.tessellate(f, coarse_edges[i], rates[i]),
                                face_points(out.mesh, f), rates[i],
                                tiled ? &out.mesh.points : nullptr);
    if (fine_face.tessellation().uv.size() != face_points(fine, f).size() ||
        coarse_face.tessellation().uv.size() != face_points(out.mesh, f).size()) {
      return fail(ErrorCode::bad_input,
                  "face " + std::to_string(f) + " tessellates differently from its mesh");
    }
    const auto& fine_uv = fine_face.tessellation().uv;
    for (std::size_t k = 0; k < fine_uv.size(); ++k) {
      const auto v = static_cast<std::size_t>(fine_face.vertex(k));
      if (out.fine_corners[v][0] < 0) {
        std::tie(out.fine_corners[v], out.fine_weights[v]) =
            coarse_face.locate(fine_uv[k], fine.points[v]);
      }
    }
    const auto& coarse_uv = coarse_face.tessellation().uv;
    for (std::size_t k = 0; k < coarse_uv.size(); ++k) {
      const auto c = static_cast<std::size_t>(coarse_face.vertex(k));
      auto& nearest = out.nearest_fine[c];
      if (nearest < 0) {
        const auto [corners, w] = fine_face.locate(coarse_uv[k], out.mesh.points[c]);
        Eigen::Index most = 0;
        w.maxCoeff(&most);
        nearest = corners[static_cast<std::size_t>(most)];
      }
    }
  }
  if (std::ranges::any_of(out.fine_corners, [](const auto& c) { return c[0] < 0; }) ||
      std::ranges::any_of(out.nearest_fine, [](int v) { return v < 0; })) {
    return fail(ErrorCode::bad_input, "a mesh vertex lies on no cage face");
  }
  return out;
}

} // namespace subfeed::geometry

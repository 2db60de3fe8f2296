#pragma once
// A coarser mesh of the same limit surface, for fields that vary over the scale of the
// surface's shape rather than of the chordal tolerance (the deformation's xi'), and where the
// two meshes lie in each other. Both are Bfr tessellations of the same cage faces, so a fine
// vertex is found in the coarse triangle that holds its (u, v) in its own face's domain (on
// a face of other than four sides, the triangle nearest it of that face's), and
// a field on the coarse vertices is carried to it by barycentric weights there: exact at
// shared points, continuous across cage edges (neighbours share every point along them).
// Each coarse vertex also knows the fine vertex nearest it in that domain, for per-vertex
// facts only the fine mesh has (whether the tool reaches it).

#include "base/error.hpp"
#include "geometry/surface_mesh.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace subfeed::geometry {

struct CoarseMesh {
  SurfaceMesh mesh;
  std::vector<std::array<int, 3>> fine_corners; // per fine vertex: 3 coarse vertices
  std::vector<Eigen::Vector3d> fine_weights;    // per fine vertex: their weights, sum 1
  std::vector<int> nearest_fine;                // per coarse vertex

  // A field on the coarse vertices at every fine vertex.
  [[nodiscard]] std::vector<double> to_fine(const std::vector<double>& coarse) const;
  // A per-vertex fact of the fine mesh at every coarse vertex (its nearest fine vertex's).
  template <class T> [[nodiscard]] std::vector<T> from_fine(const std::vector<T>& fine) const {
    if (fine.empty()) {
      return {};
    }
    std::vector<T> out;
    out.reserve(nearest_fine.size());
    for (const int v : nearest_fine) {
      out.push_back(fine[static_cast<std::size_t>(v)]);
    }
    return out;
  }
};

// `fine` must be mesh_surface's mesh of `cage` and `surface`. Each face is cut `factor`
// times more coarsely than in `fine` (at least once).
[[nodiscard]] Expected<CoarseMesh> coarse_mesh(const Cage& cage, const LimitSurface& surface,
                                               const SurfaceMesh& fine, int factor);

} // namespace subfeed::geometry

#pragma once
// A fine mesh's deformation solved on its coarse mesh (coarse_mesh.hpp): the coarse mesh's
// ball centres and tool path made once, then per slicing normal its intervals and the need
// across bending passes, and deform_on_coarse. The planner's deformation and the feed
// direction's pricing both solve this way on large meshes.

#include "base/error.hpp"
#include "geometry/coarse_mesh.hpp"
#include "geometry/deformation.hpp"
#include "geometry/pass_intervals.hpp"

#include <Eigen/Core>
#include <vector>

namespace subfeed::geometry {

class CoarseSolver {
public:
  // `fixed_axis`: the tool's path runs over the ball centres, not the surface (deformation.hpp).
  CoarseSolver(CoarseMesh map, double ball_radius, double scallop, bool fixed_axis);

  // `fine_*` describe the fine mesh as deform_cl_mesh takes it; `intervals` are its own
  // along `s`. Solves at most `coarse_rounds` on the coarse mesh, then `fine_rounds`
  // measured on the fine one.
  [[nodiscard]] Expected<Deformation>
  solve(const SurfaceMesh& fine, const std::vector<Eigen::Vector3d>& fine_cl,
        const std::vector<Eigen::Vector3d>& fine_path, const Eigen::Vector3d& s,
        const PassIntervals& intervals, DeformSettings settings) const;

  [[nodiscard]] int vertex_count() const { return map_.mesh.vertex_count(); }

private:
  CoarseMesh map_;
  double r_, scallop_;
  std::vector<Eigen::Vector3d> cl_;
  bool fixed_axis_;
};

} // namespace subfeed::geometry

#include "geometry/coarse_deformation.hpp"

namespace subfeed::geometry {

CoarseSolver::CoarseSolver(CoarseMesh map, double ball_radius, double scallop, bool fixed_axis)
    : map_(std::move(map)), r_(ball_radius), scallop_(scallop), fixed_axis_(fixed_axis) {
  const auto& m = map_.mesh;
  cl_.reserve(m.points.size());
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    cl_.push_back(m.points[v] + r_ * m.normals[v]);
  }
}

Expected<Deformation> CoarseSolver::solve(const SurfaceMesh& fine,
                                          const std::vector<Eigen::Vector3d>& fine_cl,
                                          const std::vector<Eigen::Vector3d>& fine_path,
                                          const Eigen::Vector3d& s, const PassIntervals& intervals,
                                          DeformSettings settings) const {
  const auto& cm = map_.mesh;
  auto coarse_intervals = pass_intervals(cm, r_, scallop_, s, map_.from_fine(intervals.in_reach));
  // The same reference: planes as close as the finest need anywhere on the fine mesh.
  coarse_intervals.min_interval = intervals.min_interval;
  coarse_intervals.max_interval = intervals.max_interval;
  const auto coarse_need = [&](const std::vector<Eigen::Vector3d>& across) {
    return cl_spacing_across(cm, r_, scallop_, across, coarse_intervals.cl_spacing);
  };
  const auto need = [&](const std::vector<Eigen::Vector3d>& across) {
    return cl_spacing_across(fine, r_, scallop_, across, intervals.cl_spacing);
  };
  return deform_on_coarse(
      {cl_, fixed_axis_ ? cl_ : cm.points, cm.triangles, coarse_intervals, coarse_need}, map_,
      {fine_cl, fine_path, fine.triangles, intervals, need}, s, settings);
}

} // namespace subfeed::geometry

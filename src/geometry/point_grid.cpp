#include "geometry/point_grid.hpp"

namespace subfeed::geometry {

std::array<long long, 3> grid_cell(const Eigen::Vector3d& p, double cell) {
  return {static_cast<long long>(std::floor(p.x() / cell)),
          static_cast<long long>(std::floor(p.y() / cell)),
          static_cast<long long>(std::floor(p.z() / cell))};
}

std::uint64_t grid_cell_key(long long x, long long y, long long z) {
  const auto part = [](long long v) { return static_cast<std::uint64_t>(v) & 0x1FFFFF; };
  return part(x) << 42 | part(y) << 21 | part(z);
}

PointGrid::PointGrid(const std::vector<Eigen::Vector3d>& points, double cell)
    : points_(&points), cell_(cell) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto c = grid_cell(points[i], cell);
    cells_[grid_cell_key(c[0], c[1], c[2])].push_back(static_cast<int>(i));
  }
}

} // namespace subfeed::geometry

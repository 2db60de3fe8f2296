#include "geometry/point_grid.hpp"

namespace subfeed::geometry {

PointGrid::PointGrid(const std::vector<Eigen::Vector3d>& points, double cell)
    : points_(&points), cell_(cell) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto c = cell_of(points[i]);
    cells_[key(c[0], c[1], c[2])].push_back(static_cast<int>(i));
  }
}

std::array<long long, 3> PointGrid::cell_of(const Eigen::Vector3d& p) const {
  return {static_cast<long long>(std::floor(p.x() / cell_)),
          static_cast<long long>(std::floor(p.y() / cell_)),
          static_cast<long long>(std::floor(p.z() / cell_))};
}

std::uint64_t PointGrid::key(long long x, long long y, long long z) {
  // 21 bits per axis: cells of 0.01 mm reach +-10 m before keys wrap (wrapping only costs
  // extra candidates, never misses one).
  const auto part = [](long long v) { return static_cast<std::uint64_t>(v) & 0x1FFFFF; };
  return part(x) << 42 | part(y) << 21 | part(z);
}

} // namespace subfeed::geometry

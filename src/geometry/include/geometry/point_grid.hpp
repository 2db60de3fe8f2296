#pragma once
// A uniform hash grid over points for "which of them lie within this radius" queries. The
// caller keeps the points; the grid keeps indices.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace subfeed::geometry {

// The integer cell of a uniform grid with cells of size `cell` that holds p.
[[nodiscard]] std::array<long long, 3> grid_cell(const Eigen::Vector3d& p, double cell);
// A hash key for a cell: 21 bits per axis, so cells of 0.01 mm reach +-10 m before keys
// wrap (wrapping only costs extra candidates, never misses one).
[[nodiscard]] std::uint64_t grid_cell_key(long long x, long long y, long long z);

class PointGrid {
public:
  PointGrid(const std::vector<Eigen::Vector3d>& points, double cell);

  // Calls visit(index) for every point within `radius` of `p` (radius <= cell is cheapest).
  template <class Visit> void within(const Eigen::Vector3d& p, double radius, Visit&& visit) const {
    const int reach = static_cast<int>(std::ceil(radius / cell_));
    const auto c = grid_cell(p, cell_);
    const double r2 = radius * radius;
    for (int dx = -reach; dx <= reach; ++dx) {
      for (int dy = -reach; dy <= reach; ++dy) {
        for (int dz = -reach; dz <= reach; ++dz) {
          const auto found = cells_.find(grid_cell_key(c[0] + dx, c[1] + dy, c[2] + dz));
          if (found == cells_.end()) {
            continue;
          }
          for (const int i : found->second) {
            if (((*points_)[static_cast<std::size_t>(i)] - p).squaredNorm() <= r2) {
              visit(i);
            }
          }
        }
      }
    }
  }

private:
  const std::vector<Eigen::Vector3d>* points_;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

} // namespace subfeed::geometry

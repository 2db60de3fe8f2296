#include "geometry/lifted_regions.hpp"

#include "geometry/point_grid.hpp"
#include "geometry/vertex_groups.hpp"

#include <algorithm>
#include <map>
#include <unordered_map>

namespace subfeed::geometry {

std::vector<LiftedRegion> lifted_regions(const std::vector<LiftedPoint>& points, double link) {
  std::unordered_map<std::uint64_t, std::size_t> first_in_cell;
  std::vector<std::array<long long, 3>> cells;
  cells.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    cells.push_back(grid_cell(points[i].contact, link));
    const auto& c = cells.back();
    first_in_cell.try_emplace(grid_cell_key(c[0], c[1], c[2]), i);
  }
  VertexGroups groups(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& c = cells[i];
    for (long long dx = -1; dx <= 1; ++dx) {
      for (long long dy = -1; dy <= 1; ++dy) {
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = first_in_cell.find(grid_cell_key(c[0] + dx, c[1] + dy, c[2] + dz));
          if (it != first_in_cell.end()) {
            groups.join(i, it->second);
          }
        }
      }
    }
  }
  std::map<std::size_t, LiftedRegion> by_root;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    auto [it, fresh] = by_root.try_emplace(groups.root(i));
    auto& r = it->second;
    r.low = fresh ? p.contact : r.low.cwiseMin(p.contact);
    r.high = fresh ? p.contact : r.high.cwiseMax(p.contact);
    r.centroid += p.contact;
    r.max_lift_mm = std::max(r.max_lift_mm, p.lift_mm);
    ++r.points;
  }
  std::vector<LiftedRegion> out;
  for (auto& [root, r] : by_root) {
    r.centroid /= static_cast<double>(r.points);
    out.push_back(r);
  }
  std::ranges::stable_sort(out, std::greater{}, &LiftedRegion::max_lift_mm);
  return out;
}

} // namespace subfeed::geometry

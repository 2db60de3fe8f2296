#include "geometry/uncut_regions.hpp"

#include "geometry/point_grid.hpp"
#include "geometry/vertex_groups.hpp"

#include <algorithm>
#include <map>

namespace subfeed::geometry {

std::vector<UncutRegion> uncut_regions(const std::vector<Eigen::Vector3d>& points,
                                       const std::vector<double>& areas, double link_mm) {
  VertexGroups groups(points.size());
  const PointGrid grid(points, link_mm);
  for (std::size_t i = 0; i < points.size(); ++i) {
    grid.within(points[i], link_mm, [&](int j) { groups.join(i, static_cast<std::size_t>(j)); });
  }
  std::map<std::size_t, UncutRegion> by_root;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& p = points[i];
    auto [it, fresh] = by_root.try_emplace(groups.root(i));
    auto& r = it->second;
    r.low = fresh ? p : r.low.cwiseMin(p);
    r.high = fresh ? p : r.high.cwiseMax(p);
    r.centroid += areas[i] * p;
    r.area_mm2 += areas[i];
    ++r.samples;
  }
  std::vector<UncutRegion> out;
  for (auto& [root, r] : by_root) {
    r.centroid = r.area_mm2 > 0.0 ? Eigen::Vector3d(r.centroid / r.area_mm2) : r.low;
    out.push_back(r);
  }
  std::ranges::stable_sort(out, std::greater{}, &UncutRegion::area_mm2);
  return out;
}

} // namespace subfeed::geometry

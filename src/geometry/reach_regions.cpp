#include "geometry/reach_regions.hpp"

#include "geometry/vertex_groups.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

namespace subfeed::geometry {

namespace {

bool left(const std::vector<ReachLimit>& reach, const std::array<int, 3>& t) {
  return std::ranges::any_of(
      t, [&](int v) { return reach[static_cast<std::size_t>(v)] != ReachLimit::reached; });
}

} // namespace

std::vector<ReachRegion> reach_regions(const SurfaceMesh& mesh,
                                       const std::vector<ReachLimit>& reach) {
  VertexGroups groups(reach.size());
  for (const auto& t : mesh.triangles) {
    if (left(reach, t)) {
      groups.join(static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]));
      groups.join(static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2]));
    }
  }
  std::map<std::size_t, ReachRegion> by_root;
  std::vector<char> counted(reach.size(), 0);
  for (const auto& t : mesh.triangles) {
    if (!left(reach, t)) {
      continue;
    }
    const auto p = [&](int k) -> const Eigen::Vector3d& {
      return mesh.points[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
    };
    auto [it, fresh] = by_root.try_emplace(groups.root(static_cast<std::size_t>(t[0])));
    auto& r = it->second;
    const double area = 0.5 * (p(1) - p(0)).cross(p(2) - p(0)).norm();
    r.area_mm2 += area;
    r.centroid += area * (p(0) + p(1) + p(2)) / 3.0;
    r.low = fresh ? p(0) : r.low;
    r.high = fresh ? p(0) : r.high;
    for (const int v : t) {
      const auto u = static_cast<std::size_t>(v);
      r.low = r.low.cwiseMin(mesh.points[u]);
      r.high = r.high.cwiseMax(mesh.points[u]);
      const double tilt =
          std::acos(std::clamp(mesh.normals[u].z(), -1.0, 1.0)) * 180.0 / std::numbers::pi;
      r.steepest_deg = std::max(r.steepest_deg, tilt);
      if (counted[u] == 0) {
        counted[u] = 1;
        r.tilted += reach[u] == ReachLimit::tilt ? 1 : 0;
        r.hidden += reach[u] == ReachLimit::hidden ? 1 : 0;
        r.collides += reach[u] == ReachLimit::collision ? 1 : 0;
        r.below_floor += reach[u] == ReachLimit::floor ? 1 : 0;
      }
    }
  }
  std::vector<ReachRegion> out;
  for (auto& [root, r] : by_root) {
    if (r.area_mm2 > 0.0) {
      r.centroid /= r.area_mm2;
    }
    out.push_back(r);
  }
  std::ranges::stable_sort(out, std::greater{}, &ReachRegion::area_mm2);
  return out;
}

} // namespace subfeed::geometry

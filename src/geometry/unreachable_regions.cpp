#include "geometry/unreachable_regions.hpp"

#include "geometry/vertex_groups.hpp"

#include <algorithm>
#include <map>

namespace subfeed::geometry {

std::vector<UnreachableRegion> unreachable_regions(const SurfaceMesh& mesh,
                                                   const std::vector<char>& reachable,
                                                   const std::vector<double>& material) {
  const auto blocked = [&](int v) { return reachable[static_cast<std::size_t>(v)] == 0; };
  VertexGroups groups(reachable.size());
  for (const auto& t : mesh.triangles) {
    for (int e = 0; e < 3; ++e) {
      const int a = t[static_cast<std::size_t>(e)], b = t[static_cast<std::size_t>((e + 1) % 3)];
      if (blocked(a) && blocked(b)) {
        groups.join(static_cast<std::size_t>(a), static_cast<std::size_t>(b));
      }
    }
  }
  std::map<std::size_t, UnreachableRegion> by_root;
  for (std::size_t i = 0; i < reachable.size(); ++i) {
    if (reachable[i] != 0) {
      continue;
    }
    const Eigen::Vector3d& p = mesh.points[i];
    auto [it, fresh] = by_root.try_emplace(groups.root(i));
    auto& r = it->second;
    r.low = fresh ? p : r.low.cwiseMin(p);
    r.high = fresh ? p : r.high.cwiseMax(p);
    r.centroid += p;
    ++r.vertices;
    r.material_mm = i < material.size() ? std::max(r.material_mm, material[i]) : r.material_mm;
  }
  std::vector<UnreachableRegion> out;
  for (auto& [root, r] : by_root) {
    r.centroid /= static_cast<double>(r.vertices);
    out.push_back(r);
  }
  std::ranges::stable_sort(out, std::greater{}, &UnreachableRegion::vertices);
  return out;
}

} // namespace subfeed::geometry

#include "geometry/mesh_edges.hpp"

#include <algorithm>

namespace subfeed::geometry {

std::vector<MeshEdge> mesh_edges(const std::vector<std::array<int, 3>>& triangles) {
  std::vector<std::pair<int, int>> all;
  all.reserve(triangles.size() * 3);
  for (const auto& t : triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      all.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::ranges::sort(all);
  std::vector<MeshEdge> edges;
  for (const auto& [a, b] : all) {
    if (!edges.empty() && edges.back().a == a && edges.back().b == b) {
      ++edges.back().triangles;
    } else {
      edges.push_back({a, b, 1});
    }
  }
  return edges;
}

int triangles_on_edge(const std::vector<MeshEdge>& edges, int a, int b) {
  const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
  const auto it = std::ranges::lower_bound(edges, key, {}, &MeshEdge::key);
  return it != edges.end() && it->key() == key ? it->triangles : 0;
}

} // namespace subfeed::geometry

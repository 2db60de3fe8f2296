#pragma once
// The edges of a triangle mesh, each once as (a, b) with a < b, sorted by (a, b), with the
// number of triangles that use it: 1 on the mesh's boundary and along the tears kept at
// sharp creases, 2 inside.

#include <array>
#include <utility>
#include <vector>

namespace subfeed::geometry {

struct MeshEdge {
  int a = 0;
  int b = 0;
  int triangles = 0;

  [[nodiscard]] std::pair<int, int> key() const { return {a, b}; }
};

[[nodiscard]] std::vector<MeshEdge> mesh_edges(const std::vector<std::array<int, 3>>& triangles);

// The number of triangles on the edge between a and b (either order) of sorted `edges`; 0
// when there is no such edge.
[[nodiscard]] int triangles_on_edge(const std::vector<MeshEdge>& edges, int a, int b);

} // namespace subfeed::geometry

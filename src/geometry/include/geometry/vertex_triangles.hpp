#pragma once
// The triangles around each vertex of a triangle mesh, packed: those of vertex v are
// triangles[start[v]] .. triangles[start[v + 1] - 1], in increasing index.

#include <array>
#include <vector>

namespace subfeed::geometry {

struct VertexTriangles {
  std::vector<int> start; // vertex count + 1 offsets
  std::vector<int> triangles;
};

[[nodiscard]] VertexTriangles vertex_triangles(const std::vector<std::array<int, 3>>& triangles,
                                               std::size_t vertex_count);

} // namespace subfeed::geometry

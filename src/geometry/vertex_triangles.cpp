#include "geometry/vertex_triangles.hpp"

#include <numeric>

namespace subfeed::geometry {

VertexTriangles vertex_triangles(const std::vector<std::array<int, 3>>& triangles,
                                 std::size_t vertex_count) {
  VertexTriangles out;
  out.start.assign(vertex_count + 1, 0);
  for (const auto& t : triangles) {
    for (const int v : t) {
      ++out.start[static_cast<std::size_t>(v) + 1];
    }
  }
  std::partial_sum(out.start.begin(), out.start.end(), out.start.begin());
  out.triangles.resize(static_cast<std::size_t>(out.start.back()));
  auto fill = out.start;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (const int v : triangles[i]) {
      out.triangles[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] =
          static_cast<int>(i);
    }
  }
  return out;
}

} // namespace subfeed::geometry

#pragma once
// Cuts a triangle mesh with the level sets of a per-vertex scalar (the deformed coordinate
// xi'), one level at a time, and chains the pieces into polylines. A point of a polyline
// is an edge (a, b) and the parameter t where the level crosses it, so the caller maps it
// back onto any per-vertex data exactly (the inverse deformation of docs/METHOD.md §3). Memory:
// the mesh, an order of its triangles, and one level's pieces.

#include <array>
#include <functional>
#include <vector>

namespace subfeed::geometry {

struct EdgePoint {
  int a = 0;
  int b = 0;
  double t = 0.0; // the point is (1 - t) at a + t at b
};

using SlicePolyline = std::vector<EdgePoint>;

class MeshSlicer {
public:
  MeshSlicer(const std::vector<std::array<int, 3>>& triangles, const std::vector<double>& values);

  [[nodiscard]] double min_value() const { return min_; }
  [[nodiscard]] double max_value() const { return max_; }

  // Polylines where the values equal `level`; levels must come in increasing order. A
  // polyline is open where the mesh ends and closed (first point repeated) around holes.
  // With `depth`, only triangles t with depth[t] >= min_depth are cut, and polylines also
  // end where that region ends.
  [[nodiscard]] std::vector<SlicePolyline>
  slice(double level, const std::vector<unsigned char>* depth = nullptr, int min_depth = 0);

private:
  const std::vector<std::array<int, 3>>* triangles_;
  const std::vector<double>* values_;
  std::vector<int> by_min_; // triangle indices by their least value
  std::vector<double> tri_min_, tri_max_;
  std::size_t next_ = 0;    // first triangle of by_min_ not yet active
  std::vector<int> active_; // triangles whose range may contain the level
  double min_ = 0.0, max_ = 0.0;
};

} // namespace subfeed::geometry

#include "support/grid_cage.hpp"

namespace subfeed::testing {

geometry::Cage grid_cage(int n, double g, double a, double b) {
  geometry::Cage cage;
  cage.source = "grid";
  const double half = 0.5 * (n - 1) * g;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = i * g - half;
      const double y = j * g - half;
      cage.positions.emplace_back(x, y, a * x * x + b * y * y - (a + b) * g * g / 3.0);
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int v = j * n + i;
      cage.face_offsets.push_back(static_cast<int>(cage.face_indices.size()));
      cage.face_indices.insert(cage.face_indices.end(), {v, v + 1, v + 1 + n, v + n});
      cage.face_sizes.push_back(4);
      cage.face_lines.push_back(0);
    }
  }
  return cage;
}

geometry::Cage lifted(geometry::Cage cage, double z0) {
  for (auto& p : cage.positions) {
    p.z() += z0;
  }
  return cage;
}

int grid_face(int n, int i, int j) {
  return j * (n - 1) + i;
}

geometry::Cage cube_cage() {
  geometry::Cage cage;
  cage.source = "cube";
  for (int k = 0; k < 8; ++k) {
    cage.positions.emplace_back((k & 1) ? 0.5 : -0.5, (k & 2) ? 0.5 : -0.5, (k & 4) ? 0.5 : -0.5);
  }
  // Outward-facing loops.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    cage.face_offsets.push_back(static_cast<int>(cage.face_indices.size()));
    cage.face_indices.insert(cage.face_indices.end(), f, f + 4);
    cage.face_sizes.push_back(4);
    cage.face_lines.push_back(0);
  }
  return cage;
}

} // namespace subfeed::testing

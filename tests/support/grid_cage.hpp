#pragma once
// Cages with known limit surfaces (docs/METHOD.md §5): on an n x n grid with spacing g, control
// points z = a x^2 + b y^2 - (a + b) g^2 / 3 give the limit surface z = a x^2 + b y^2 exactly
// on the interior faces. Faces wind counter-clockwise seen from +Z.

#include "geometry/cage.hpp"

namespace subfeed::testing {

[[nodiscard]] geometry::Cage grid_cage(int n, double g, double a, double b);

// The same cage lifted by z0 (mm): the same part elsewhere on the machine's Z.
[[nodiscard]] geometry::Cage lifted(geometry::Cage cage, double z0);

// The grid's x and y of a parameter point (u, v) on face (i, j): interior faces of a uniform
// bicubic B-spline map parameters linearly onto the grid.
[[nodiscard]] int grid_face(int n, int i, int j);

// A unit cube centred at the origin: eight extraordinary (valence 3) vertices.
[[nodiscard]] geometry::Cage cube_cage();

} // namespace subfeed::testing

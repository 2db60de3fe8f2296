#pragma once
// The CL-surface deformation of Kim & Yang as docs/METHOD.md §3 corrects it: every CL vertex
// gets a deformed coordinate xi' along the slicing normal s with d(xi')/d(xi) = eta =
// reference / interval, solved over the whole mesh as sparse least squares over its edges
// (one vertex anchored per connected piece; Eigen's sparse LDLT). Edges weigh by how far
// they run across the passes, so that the passes bend where the need changes along them. Planes
// equally spaced by `reference` in xi' then cut the original surface at the varying intervals each
// vertex needs.
//
// Being first order, the result is measured: on every triangle the spacing between the
// level lines of xi' (the passes) is compared with the spacing its vertices need, eta is
// raised where it is too wide and the system solved again (the factorisation is reused).
// Raising eta near one spot crowds passes over a wide area around it, so each solve is
// also priced: the cutting length its planes plus the passes inserted where they are still
// too far apart (pass_insertion.hpp) would take along the tool's path, by the co-area
// formula. The cheapest solve is kept.

#include "base/error.hpp"
#include "geometry/coarse_mesh.hpp"
#include "geometry/pass_insertion.hpp"
#include "geometry/pass_intervals.hpp"

#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

namespace subfeed::geometry {

// Equally spaced levels of xi' from the least value to the greatest (each a hair inside,
// so it cuts the surface), no farther apart than the reference.
struct PlaneSpacing {
  double first = 0.0; // xi' of the first plane, mm
  double step = 0.0;  // mm
  long planes = 0;
};
[[nodiscard]] PlaneSpacing space_planes(const std::vector<double>& deformed, double reference);

// Told of each solve as it is made (1-based) and the most there may be.
using SolveProgress = std::function<void(int solve, int most)>;

// The CL spacing each vertex needs across passes whose spacing runs along the given
// direction per vertex (pass_intervals.hpp's cl_spacing_across for one mesh and tool).
using NeedAcross = std::function<std::vector<double>(const std::vector<Eigen::Vector3d>&)>;

struct Deformation {
  std::vector<double> xi;       // s . c per CL vertex, mm
  std::vector<double> deformed; // xi' per CL vertex, mm
  double reference = 0.0;       // plane spacing in xi', mm
  PlaneSpacing planes;
  PassInsertion insertion;  // where passes between the planes are still needed
  int iterations = 0;       // solves made
  int chosen = 0;           // the solve kept (1-based)
  double worst_ratio = 0.0; // largest measured/needed spacing of the kept solve
  // Rings about these vertices (concentric_field.hpp) instead of planes along s; xi is
  // then empty and iterations count the front's marches.
  std::vector<int> ring_centres;
};

// `path_points` are where the tool's path runs, vertex for vertex (the tool tips: the design
// mesh for a tool along the normal, the ball centres for a fixed axis): a solve is priced
// by the length of its passes there, the length the machine cuts. With `need_across`, each
// solve's passes are measured against the spacing needed across them as they run (they
// bend away from the planes' direction), else against `intervals`.
[[nodiscard]] Expected<Deformation> deform_cl_mesh(
    const std::vector<Eigen::Vector3d>& cl_points, const std::vector<Eigen::Vector3d>& path_points,
    const std::vector<std::array<int, 3>>& triangles, const Eigen::Vector3d& s,
    const PassIntervals& intervals, int max_iterations, double insertion_margin, double allowance,
    const SolveProgress& on_solve = {}, const NeedAcross& need_across = {});

// One mesh's part in a deformation: its CL points, where the tool's path runs over them,
// its triangles, the spacing each vertex needs, and the need across bending passes.
struct DeformedMesh {
  const std::vector<Eigen::Vector3d>& cl_points;
  const std::vector<Eigen::Vector3d>& path_points;
  const std::vector<std::array<int, 3>>& triangles;
  const PassIntervals& intervals;
  NeedAcross need_across;
};

struct DeformSettings {
  int coarse_rounds = 60; // solves measured on the coarse mesh
  int fine_rounds = 8;    // then solves measured on the fine one
  double insertion_margin = 0.0;
  double allowance = 0.01;
  SolveProgress on_solve;
};

// The deformation solved on `map`'s coarse mesh and carried to the fine one: first solves
// measured and priced on the coarse mesh, as deform_cl_mesh does; then, from the cheapest,
// solves measured and priced on the fine mesh, eta raised at the coarse corners of its
// triangles still too wide. The solve kept is the cheapest of those, on the fine mesh; its
// passes inserted are those the fine mesh needs. Both meshes must share the reference
// (intervals.min_interval).
[[nodiscard]] Expected<Deformation>
deform_on_coarse(const DeformedMesh& coarse, const CoarseMesh& map, const DeformedMesh& fine,
                 const Eigen::Vector3d& s, const DeformSettings& settings);

// The constant-interval iso-planar baseline: xi' = xi, spaced by the smallest interval, with
// nothing inserted.
[[nodiscard]] Deformation iso_planar(const std::vector<Eigen::Vector3d>& cl_points,
                                     const Eigen::Vector3d& s, const PassIntervals& intervals);

} // namespace subfeed::geometry

#pragma once
// Where the deformed CL surface still spaces its passes wider than the scallop allows, extra
// passes are cut at intermediate levels of xi' (half, then quarter, ... of the plane step),
// on those triangles only. A level of xi' can only add passes that run from boundary to
// boundary, so a region that needs more passes than its neighbours (the rounded nose of a
// seat) otherwise forces the deformation to crowd passes over a wide area around it;
// inserted passes start and end where they are needed.
//
// depth[t] = number of halvings triangle t needs: the smallest d with
// spacing ratio (below) / 2^d <= 1 + allowance. The
// allowance keeps a spot where the passes lie a hair too far apart (the scallop there
// grows by about twice the allowance) from costing a patch of doubled passes. The field is then
// grown by `margin` (mm, across the surface) so inserted passes do not stop and start on
// every small change of the measured spacing.

#include "geometry/pass_intervals.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace subfeed::geometry {

struct PassInsertion {
  std::vector<unsigned char> depth; // per triangle
  int max_depth = 0;
  double worst_ratio = 0.0; // measured/needed spacing before insertion
  // Cutting length the planes and inserted passes would take, mm: the triangles' level
  // line lengths, each times 2^depth.
  double predicted_length = 0.0;
};

// Deepest insertion: passes at 1/16 of the plane step.
inline constexpr int max_insertion_depth = 4;

// How far apart the level lines of `deformed` (spaced `step`) lie on each triangle of the CL
// mesh c against the least spacing its vertices need (> 1: too far apart); 0 where
// unreachable or no level crosses. Per triangle the larger of its own gradient's spacing and
// the spacing at a kink at each of its vertices: lines that kink leave a gap there as wide
// as straight lines 2 step / (|gradient| + |mean gradient|) apart (area-weighted means over
// the vertex's triangles): for arms d apart whose normals differ by 2 phi, 2 d / (1 + cos
// phi), less than the d / cos phi the mean gradient alone says.
struct SpacingRatios {
  std::vector<double> ratio;
  double worst = 0.0;
};
[[nodiscard]] SpacingRatios spacing_ratios(const std::vector<Eigen::Vector3d>& cl_points,
                                           const std::vector<std::array<int, 3>>& triangles,
                                           const std::vector<double>& deformed, double step,
                                           const PassIntervals& intervals);

// The area-weighted mean gradient of `deformed` at each vertex of the mesh (1/mm times
// the field's unit): the direction across its level lines there.
[[nodiscard]] std::vector<Eigen::Vector3d>
vertex_gradients(const std::vector<Eigen::Vector3d>& points,
                 const std::vector<std::array<int, 3>>& triangles,
                 const std::vector<double>& deformed);

// mm of level lines of `deformed` (spaced `step`) on each triangle of the mesh with these
// points, by the co-area formula: area * |gradient| / step.
[[nodiscard]] std::vector<double> level_lengths(const std::vector<Eigen::Vector3d>& points,
                                                const std::vector<std::array<int, 3>>& triangles,
                                                const std::vector<double>& deformed, double step);

// The gradient of the linear function with values vi, vj, vk at the corners, 1/mm.
[[nodiscard]] Eigen::Vector3d level_gradient(const Eigen::Vector3d& ci, const Eigen::Vector3d& cj,
                                             const Eigen::Vector3d& ck, double vi, double vj,
                                             double vk);

[[nodiscard]] PassInsertion pass_insertion(const std::vector<Eigen::Vector3d>& cl_points,
                                           const std::vector<std::array<int, 3>>& triangles,
                                           const std::vector<double>& deformed, double step,
                                           const PassIntervals& intervals, double margin,
                                           double allowance);
// The same from spacing ratios already measured, priced by `level_length` (level_lengths
// on the points the tool's path runs through).
[[nodiscard]] PassInsertion pass_insertion(const std::vector<Eigen::Vector3d>& cl_points,
                                           const std::vector<std::array<int, 3>>& triangles,
                                           const SpacingRatios& measured,
                                           const std::vector<double>& level_length, double margin,
                                           double allowance);

// The depth a level at `index` (in units of step / 2^max_insertion_depth) belongs to: 0 for
// whole planes, 1 for halves, ...
[[nodiscard]] int level_depth(long index);

} // namespace subfeed::geometry

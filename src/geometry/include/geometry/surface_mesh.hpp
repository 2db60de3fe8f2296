#pragma once
// The limit surface as one welded triangle mesh, fine enough that its chords stay within a
// tolerance of the true surface. Every vertex carries the exact limit point, unit normal
// (toward the tool) and curvature from Bfr, not values estimated from the triangles. Where
// normals disagree at the same point (a sharp crease) the vertices stay separate, one per
// side, so the offset surface can see the tear.

#include "base/error.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/stage_share.hpp"

#include <Eigen/Core>
#include <array>
#include <vector>

namespace subfeed::geometry {

struct SurfaceMesh {
  std::vector<Eigen::Vector3d> points;  // mm
  std::vector<Eigen::Vector3d> normals; // unit, toward the tool
  // Second fundamental form as a symmetric 3x3 matrix W in the work frame: the normal
  // curvature along a unit tangent t is t' W t (1/mm; negative where the surface bends away
  // from the tool, i.e. convex).
  std::vector<Eigen::Matrix3d> curvature;
  std::vector<std::array<int, 3>> triangles; // counter-clockwise seen from the tool
  int rate = 0;                              // most segments along any cage face edge
  // Where each cage face's tessellation points landed, in the order LimitSurface::tessellate
  // lists them at `face_rates` and edge_rates_per_face: face f's are
  // face_points[face_points_begin[f]] up to face_points[face_points_begin[f + 1]].
  std::vector<int> face_rates;
  std::vector<int> face_points_begin;
  std::vector<int> face_points;

  [[nodiscard]] int vertex_count() const { return static_cast<int>(points.size()); }
  [[nodiscard]] int triangle_count() const { return static_cast<int>(triangles.size()); }
  // Signed radius of normal curvature along unit tangent t at vertex i: > 0 convex, < 0
  // concave, +-infinity flat.
  [[nodiscard]] double radius_along(int i, const Eigen::Vector3d& t) const;
  // The largest normal curvature toward the tool at vertex i over all tangent directions
  // (1/mm, > 0 where some direction is concave, else <= 0).
  [[nodiscard]] double concave_curvature(int i) const;
};

// W for one limit sample (see SurfaceMesh::curvature).
[[nodiscard]] Eigen::Matrix3d curvature_matrix(const LimitSample& sample);

// The lowest vertex's z, mm: the vertices lie on the limit surface, so this is the part's
// lowest point within the mesh's chord (the default floor).
[[nodiscard]] double lowest_z(const SurfaceMesh& mesh);
[[nodiscard]] Eigen::Vector3d lowest_point(const SurfaceMesh& mesh); // its lowest vertex

// Per cage face, the tessellation rate that keeps every chord within `chord_tolerance` (mm)
// of the surface, estimated from second derivatives sampled over the face, and, with
// `max_edge_mm`, every cell edge about that short or shorter (flat faces too, so that
// whatever is decided per vertex, such as the tool's reach, is decided that finely); with
// `min_edge_mm`, no face cut so finely for its chord that its longest cell edge falls under
// that (beside a crease the limit surface turns within a hair's breadth, and following it
// there costs faces x max_rate^2); clamped to 2..max_rate (0 for a face without a patch).
[[nodiscard]] std::vector<int> rates_for_tolerance(const LimitSurface& surface,
                                                   double chord_tolerance, int max_rate = 128,
                                                   double max_edge_mm = 0.0,
                                                   double min_edge_mm = 0.0);

// Per cage face, the segments along each of its edges (from its vertex i to i + 1): the
// larger rate of the two faces that share the edge.
[[nodiscard]] std::vector<std::vector<int>> edge_rates_per_face(const Cage& cage,
                                                                const LimitSurface& surface,
                                                                const std::vector<int>& face_rates);

// A face is cut at its own rate inside; a cage edge at the larger rate of its two faces, so
// neighbours share every point along it. `share`, when given, hears of the faces done.
[[nodiscard]] Expected<SurfaceMesh> mesh_surface(const Cage& cage, const LimitSurface& surface,
                                                 const std::vector<int>& face_rates,
                                                 StageShare* share = nullptr);
// Every face at the same rate.
[[nodiscard]] Expected<SurfaceMesh> mesh_surface(const Cage& cage, const LimitSurface& surface,
                                                 int rate);

} // namespace subfeed::geometry

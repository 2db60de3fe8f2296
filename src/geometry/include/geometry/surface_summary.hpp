#pragma once
// What a machinist wants to know about a part before planning: cage statistics and the
// extent and area of the limit surface (the stock it needs and the area to finish).
// Extent and area come from sampling each face on a uniform grid, so the box may be
// smaller than the true one by at most the sampling sagitta.

#include "base/error.hpp"
#include "geometry/cage.hpp"
#include "geometry/limit_surface.hpp"

namespace subfeed::geometry {

struct CageStats {
  int vertices = 0;
  int faces = 0;
  int quads = 0;
  int boundary_edges = 0;
  int extraordinary_vertices = 0; // interior vertices whose valence is not 4
  int creases = 0;
  int corners = 0;
};

struct SurfaceSummary {
  CageStats cage;
  int patches = 0;
  Eigen::Vector3d min = Eigen::Vector3d::Zero(); // mm
  Eigen::Vector3d max = Eigen::Vector3d::Zero(); // mm
  double area = 0.0;                             // mm^2
  // Steepest slope of the surface against the XY plane, degrees (90: a vertical wall), and
  // where it is: how far a three-axis ball end must reach down a wall, and how far a five-axis
  // head must tilt.
  double steepest_deg = 0.0;
  Eigen::Vector3d steepest_at = Eigen::Vector3d::Zero();
};

[[nodiscard]] CageStats cage_stats(const Cage& cage);

// `rate`: samples per face edge.
[[nodiscard]] Expected<SurfaceSummary> summarize(const Cage& cage, const LimitSurface& surface,
                                                 int rate = 16);

} // namespace subfeed::geometry

#include "geometry/surface_summary.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>

namespace subfeed::geometry {

CageStats cage_stats(const Cage& cage) {
  CageStats stats;
  stats.vertices = cage.vertex_count();
  stats.faces = cage.face_count();
  stats.quads = static_cast<int>(std::ranges::count(cage.face_sizes, 4));
  stats.creases = static_cast<int>(cage.creases.size());
  stats.corners = static_cast<int>(cage.corners.size());

  std::map<std::pair<int, int>, int> edge_faces;
  for (int f = 0; f < cage.face_count(); ++f) {
    const auto loop = cage.face(f);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i];
      const int b = loop[(i + 1) % loop.size()];
      ++edge_faces[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<int> valence(cage.positions.size(), 0);
  std::vector<bool> on_boundary(cage.positions.size(), false);
  for (const auto& [edge, faces] : edge_faces) {
    ++valence[edge.first];
    ++valence[edge.second];
    if (faces == 1) {
      ++stats.boundary_edges;
      on_boundary[edge.first] = on_boundary[edge.second] = true;
    }
  }
  for (std::size_t v = 0; v < valence.size(); ++v) {
    if (valence[v] > 0 && !on_boundary[v] && valence[v] != 4) {
      ++stats.extraordinary_vertices;
    }
  }
  return stats;
}

Expected<SurfaceSummary> summarize(const Cage& cage, const LimitSurface& surface, int rate) {
  SurfaceSummary summary;
  summary.cage = cage_stats(cage);
  summary.min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  summary.max = -summary.min;
  for (int f = 0; f < surface.face_count(); ++f) {
    if (!surface.has_patch(f)) {
      continue;
    }
    ++summary.patches;
    const FaceTessellation tess = surface.tessellate(f, rate);
    std::vector<Eigen::Vector3d> points;
    points.reserve(tess.uv.size());
    for (const auto& uv : tess.uv) {
      auto sample = surface.evaluate_regular(f, uv.x(), uv.y());
      if (!sample) {
        return std::unexpected(sample.error());
      }
      points.push_back(sample->point);
      const double slope =
          std::acos(std::clamp(std::abs(sample->normal.z()), 0.0, 1.0)) * 180.0 / std::numbers::pi;
      if (slope > summary.steepest_deg) {
        summary.steepest_deg = slope;
        summary.steepest_at = sample->point;
      }
      summary.min = summary.min.cwiseMin(sample->point);
      summary.max = summary.max.cwiseMax(sample->point);
    }
    for (const auto& t : tess.triangles) {
      summary.area += 0.5 * (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).norm();
    }
  }
  if (summary.patches == 0) {
    return fail(ErrorCode::bad_input, "the cage has no face with a limit surface",
                {cage.source, 0, {}});
  }
  return summary;
}

} // namespace subfeed::geometry

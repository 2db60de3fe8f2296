#include "geometry/cage_refinement.hpp"

#include "cage_topology.hpp"

#include <opensubdiv/far/primvarRefiner.h>

#include <string>
#include <vector>

namespace subfeed::geometry {

namespace osd = OpenSubdiv;

namespace {

// A control point as OpenSubdiv's primvar refiner interpolates it.
struct RefinedPoint {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  void Clear() { p.setZero(); }
  void AddWithWeight(const RefinedPoint& other, float weight) { p += weight * other.p; }
};

// The last level's points, interpolated level by level from the cage's.
std::vector<Eigen::Vector3d> refined_points(const osd::Far::TopologyRefiner& refiner,
                                            const Cage& cage, int levels) {
  std::vector<RefinedPoint> points(static_cast<std::size_t>(refiner.GetNumVerticesTotal()));
  for (int v = 0; v < cage.vertex_count(); ++v) {
    points[static_cast<std::size_t>(v)].p = cage.positions[static_cast<std::size_t>(v)];
  }
  const osd::Far::PrimvarRefiner primvar(refiner);
  RefinedPoint* source = points.data();
  for (int level = 1; level <= levels; ++level) {
    RefinedPoint* destination = source + refiner.GetLevel(level - 1).GetNumVertices();
    primvar.Interpolate(level, source, destination);
    source = destination;
  }
  std::vector<Eigen::Vector3d> out;
  const int count = refiner.GetLevel(levels).GetNumVertices();
  out.reserve(static_cast<std::size_t>(count));
  for (int v = 0; v < count; ++v) {
    out.push_back(source[v].p);
  }
  return out;
}

} // namespace

Expected<Cage> refine_cage(const Cage& cage, int levels) {
  if (levels <= 0) {
    return cage;
  }
  const auto refiner = make_refiner(cage);
  if (!refiner) {
    return fail(ErrorCode::bad_input, "OpenSubdiv rejected the cage topology",
                {cage.source, 0, {}});
  }
  osd::Far::TopologyRefiner::UniformOptions uniform(levels);
  uniform.fullTopologyInLastLevel = true; // its edges, for the creases
  refiner->RefineUniform(uniform);
  const auto& last = refiner->GetLevel(levels);
  Cage out;
  out.source = cage.source;
  out.boundary = cage.boundary;
  out.creasing = cage.creasing;
  out.triangles = cage.triangles;
  out.positions = refined_points(*refiner, cage, levels);
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const auto loop = last.GetFaceVertices(f);
    out.face_offsets.push_back(static_cast<int>(out.face_indices.size()));
    out.face_sizes.push_back(loop.size());
    out.face_lines.push_back(0);
    out.face_indices.insert(out.face_indices.end(), loop.begin(), loop.end());
    if (last.IsFaceHole(f)) {
      out.holes.push_back({f, 0});
    }
  }
  for (int e = 0; e < last.GetNumEdges(); ++e) {
    if (const float s = last.GetEdgeSharpness(e); s > 0.0f) {
      const auto ends = last.GetEdgeVertices(e);
      out.creases.push_back({ends[0], ends[1], s, 0});
    }
  }
  for (int v = 0; v < last.GetNumVertices(); ++v) {
    if (const float s = last.GetVertexSharpness(v); s > 0.0f) {
      out.corners.push_back({v, s, 0});
    }
  }
  return out;
}

} // namespace subfeed::geometry

#include "cage_topology.hpp"

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <vector>

namespace subfeed::geometry {

namespace osd = OpenSubdiv;

namespace {

osd::Sdc::Options::VtxBoundaryInterpolation to_sdc(BoundaryInterpolation b) {
  switch (b) {
  case BoundaryInterpolation::none:
    return osd::Sdc::Options::VTX_BOUNDARY_NONE;
  case BoundaryInterpolation::edge_only:
    return osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY;
  case BoundaryInterpolation::edge_and_corner:
    return osd::Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER;
  }
  return osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY;
}

} // namespace

std::unique_ptr<osd::Far::TopologyRefiner> make_refiner(const Cage& cage) {
  std::vector<int> crease_pairs;
  std::vector<float> crease_weights;
  for (const Crease& c : cage.creases) {
    crease_pairs.insert(crease_pairs.end(), {c.v0, c.v1});
    crease_weights.push_back(static_cast<float>(c.sharpness));
  }
  std::vector<int> corner_vertices;
  std::vector<float> corner_weights;
  for (const Corner& c : cage.corners) {
    corner_vertices.push_back(c.vertex);
    corner_weights.push_back(static_cast<float>(c.sharpness));
  }
  std::vector<int> hole_faces;
  for (const Hole& h : cage.holes) {
    hole_faces.push_back(h.face);
  }
  osd::Far::TopologyDescriptor desc;
  desc.numVertices = cage.vertex_count();
  desc.numFaces = cage.face_count();
  desc.numVertsPerFace = cage.face_sizes.data();
  desc.vertIndicesPerFace = cage.face_indices.data();
  desc.numCreases = static_cast<int>(crease_weights.size());
  desc.creaseVertexIndexPairs = crease_pairs.data();
  desc.creaseWeights = crease_weights.data();
  desc.numCorners = static_cast<int>(corner_weights.size());
  desc.cornerVertexIndices = corner_vertices.data();
  desc.cornerWeights = corner_weights.data();
  desc.numHoles = static_cast<int>(hole_faces.size());
  desc.holeIndices = hole_faces.data();

  osd::Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(to_sdc(cage.boundary));
  sdc.SetCreasingMethod(cage.creasing == CreasingMethod::chaikin
                            ? osd::Sdc::Options::CREASE_CHAIKIN
                            : osd::Sdc::Options::CREASE_UNIFORM);
  sdc.SetTriangleSubdivision(cage.triangles == TriangleRule::smooth
                                 ? osd::Sdc::Options::TRI_SUB_SMOOTH
                                 : osd::Sdc::Options::TRI_SUB_CATMARK);
  using Factory = osd::Far::TopologyRefinerFactory<osd::Far::TopologyDescriptor>;
  return std::unique_ptr<osd::Far::TopologyRefiner>(
      Factory::Create(desc, Factory::Options(osd::Sdc::SCHEME_CATMARK, sdc)));
}

} // namespace subfeed::geometry

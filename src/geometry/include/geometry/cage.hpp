#pragma once
// A Catmull-Clark control cage as read from a file: positions (mm once set up on the machine,
// geometry/part_setup.hpp), faces as vertex index
// loops (counter-clockwise seen from the side the tool comes from), semi-sharp creases and
// corners, holes, and the OpenSubdiv rules that shape it (boundary, creasing, triangles). A Cage
// that came out of read_obj() is manifold, consistently oriented, without degenerate or repeated
// faces and with finite coordinates; `face_lines` keeps each face's source line for later error
// messages.

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

namespace subfeed::geometry {

enum class BoundaryInterpolation {
  none,            // boundary faces are holes; only interior faces have a limit surface
  edge_only,       // boundary edges are sharp creases (OpenSubdiv's VTX_BOUNDARY_EDGE_ONLY)
  edge_and_corner, // as edge_only, and valence-2 boundary vertices are sharp corners
};

struct Crease {
  int v0 = 0;
  int v1 = 0;
  double sharpness = 0.0; // OpenSubdiv sharpness: 0 smooth, >= 10 infinitely sharp
  int line = 0;           // source line of the tag, for messages
};

struct Corner {
  int vertex = 0;
  double sharpness = 0.0;
  int line = 0;
};

struct Hole {
  int face = 0; // 0-based cage face with no limit surface of its own
  int line = 0;
};

// OpenSubdiv's `creasemethod`: how semi-sharp crease sharpness decays with each level.
enum class CreasingMethod {
  uniform, // "normal": every edge's sharpness drops by one per level
  chaikin, // sharpness averaged along the crease, so it blends smoothly along its length
};

// OpenSubdiv's `smoothtriangles`: the rule for triangles in a Catmull-Clark cage.
enum class TriangleRule {
  catmark, // plain Catmull-Clark
  smooth,  // a modified first level that makes triangles' limit surfaces smoother
};

struct Cage {
  std::string source; // file name for messages
  std::vector<Eigen::Vector3d> positions;
  std::vector<int> face_sizes;
  std::vector<int> face_indices; // concatenated loops, 0-based
  std::vector<int> face_offsets; // start of each face in face_indices
  std::vector<int> face_lines;   // 1-based source line of each face
  std::vector<Crease> creases;
  std::vector<Corner> corners;
  std::vector<Hole> holes;
  BoundaryInterpolation boundary = BoundaryInterpolation::edge_only;
  CreasingMethod creasing = CreasingMethod::uniform;
  TriangleRule triangles = TriangleRule::catmark;

  [[nodiscard]] int face_count() const { return static_cast<int>(face_sizes.size()); }
  [[nodiscard]] int vertex_count() const { return static_cast<int>(positions.size()); }
  [[nodiscard]] std::span<const int> face(int f) const {
    return {face_indices.data() + face_offsets[f], static_cast<std::size_t>(face_sizes[f])};
  }
};

} // namespace subfeed::geometry

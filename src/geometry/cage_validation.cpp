#include "geometry/cage_validation.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace subfeed::geometry {

namespace {

std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32U) | hi;
}

std::unexpected<Error> at_line(const Cage& cage, int line, std::string message) {
  return fail(ErrorCode::bad_input, std::move(message), {cage.source, line, {}});
}

// A face whose vertices are (nearly) collinear has no normal; the Newell normal's length is
// twice the area of the (possibly non-planar) loop.
double newell_area(const Cage& cage, std::span<const int> loop) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Eigen::Vector3d& a = cage.positions[loop[i]];
    const Eigen::Vector3d& b = cage.positions[loop[(i + 1) % loop.size()]];
    normal += a.cross(b);
  }
  return 0.5 * normal.norm();
}

double bounding_diagonal(const Cage& cage) {
  Eigen::Vector3d lo = cage.positions.front();
  Eigen::Vector3d hi = lo;
  for (const auto& p : cage.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

Expected<void> check_faces(const Cage& cage) {
  const double min_area = 1e-12 * std::max(1.0, std::pow(bounding_diagonal(cage), 2));
  std::unordered_map<std::string, int> seen; // sorted vertex list -> line
  for (int f = 0; f < cage.face_count(); ++f) {
    const auto loop = cage.face(f);
    std::vector<int> sorted(loop.begin(), loop.end());
    std::ranges::sort(sorted);
    if (std::ranges::adjacent_find(sorted) != sorted.end()) {
      return at_line(cage, cage.face_lines[f], "degenerate face: a vertex appears twice");
    }
    if (newell_area(cage, loop) <= min_area) {
      return at_line(cage, cage.face_lines[f], "degenerate face: zero area");
    }
    std::string key(reinterpret_cast<const char*>(sorted.data()), sorted.size() * sizeof(int));
    const auto [it, inserted] = seen.emplace(std::move(key), cage.face_lines[f]);
    if (!inserted) {
      return at_line(cage, cage.face_lines[f],
                     "repeated face: same vertices as the face on line " +
                         std::to_string(it->second));
    }
  }
  return {};
}

struct EdgeUse {
  int faces = 0;
  int first_face = -1;
  bool first_forward = false; // first face runs lo -> hi
};

Expected<void> check_edges(const Cage& cage, std::unordered_map<std::uint64_t, EdgeUse>& edges) {
  for (int f = 0; f < cage.face_count(); ++f) {
    const auto loop = cage.face(f);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i];
      const int b = loop[(i + 1) % loop.size()];
      EdgeUse& use = edges[edge_key(a, b)];
      const bool forward = a < b;
      const std::string name = "edge " + std::to_string(a + 1) + "-" + std::to_string(b + 1);
      if (use.faces == 2) {
        return at_line(cage, cage.face_lines[f], "non-manifold " + name + ": a third face uses it");
      }
      if (use.faces == 1 && use.first_forward == forward) {
        return at_line(cage, cage.face_lines[f],
                       "inconsistent orientation across " + name + " with the face on line " +
                           std::to_string(cage.face_lines[use.first_face]));
      }
      if (use.faces == 0) {
        use.first_face = f;
        use.first_forward = forward;
      }
      ++use.faces;
    }
  }
  return {};
}

// A manifold vertex has a single fan: no boundary edges (closed fan) or exactly two (open
// fan), and one face more than interior edges on an open fan. Two fans meeting at one
// vertex (a bow tie) have four or more boundary edges.
Expected<void> check_vertex_fans(const Cage& cage,
                                 const std::unordered_map<std::uint64_t, EdgeUse>& edges) {
  std::vector<int> boundary_edges(cage.positions.size(), 0);
  for (const auto& [key, use] : edges) {
    if (use.faces == 1) {
      ++boundary_edges[key >> 32U];
      ++boundary_edges[key & 0xffffffffU];
    }
  }
  for (int f = 0; f < cage.face_count(); ++f) {
    for (const int v : cage.face(f)) {
      if (boundary_edges[v] > 2) {
        return at_line(cage, cage.face_lines[f],
                       "non-manifold vertex " + std::to_string(v + 1) +
                           ": faces meet there in more than one fan");
      }
    }
  }
  return {};
}

Expected<void> check_tags(const Cage& cage,
                          const std::unordered_map<std::uint64_t, EdgeUse>& edges) {
  const int n = cage.vertex_count();
  for (const Crease& c : cage.creases) {
    if (c.v0 < 0 || c.v0 >= n || c.v1 < 0 || c.v1 >= n) {
      return at_line(cage, c.line,
                     "crease vertex out of range (0-based, " + std::to_string(n) + " vertices)");
    }
    if (!edges.contains(edge_key(c.v0, c.v1))) {
      return at_line(cage, c.line,
                     "crease " + std::to_string(c.v0) + "-" + std::to_string(c.v1) +
                         " is not an edge of the cage");
    }
  }
  for (const Corner& c : cage.corners) {
    if (c.vertex < 0 || c.vertex >= n) {
      return at_line(cage, c.line,
                     "corner vertex out of range (0-based, " + std::to_string(n) + " vertices)");
    }
  }
  for (const Hole& h : cage.holes) {
    if (h.face < 0 || h.face >= cage.face_count()) {
      return at_line(cage, h.line,
                     "hole face " + std::to_string(h.face) + " out of range (0-based, " +
                         std::to_string(cage.face_count()) + " faces)");
    }
  }
  return {};
}

} // namespace

Expected<void> validate_cage(const Cage& cage) {
  if (cage.face_count() == 0 || cage.positions.empty()) {
    return fail(ErrorCode::bad_input, "no faces: not a control cage", {cage.source, 0, {}});
  }
  for (int v = 0; v < cage.vertex_count(); ++v) {
    if (!cage.positions[v].allFinite()) {
      return fail(ErrorCode::bad_input,
                  "vertex " + std::to_string(v + 1) + " has a coordinate that is not finite",
                  {cage.source, 0, {}});
    }
  }
  if (auto ok = check_faces(cage); !ok) {
    return ok;
  }
  std::unordered_map<std::uint64_t, EdgeUse> edges;
  if (auto ok = check_edges(cage, edges); !ok) {
    return ok;
  }
  if (auto ok = check_vertex_fans(cage, edges); !ok) {
    return ok;
  }
  return check_tags(cage, edges);
}

} // namespace subfeed::geometry

#pragma once
// The Catmull-Clark limit surface of a validated cage, evaluated exactly (up to the chosen
// approximation level near irregular features) through OpenSubdiv's Bfr. Every face of the
// cage with a limit surface gets one patch, parameterised by (u, v) over Bfr's domain for
// that face (the unit square for quads). Evaluation is const and allocation-free, so one
// LimitSurface may be shared by threads.

#include "base/error.hpp"
#include "geometry/cage.hpp"

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

namespace subfeed::geometry {

struct LimitSample {
  Eigen::Vector3d point;  // mm
  Eigen::Vector3d du, dv; // first derivatives
  Eigen::Vector3d duu, duv, dvv;
  Eigen::Vector3d normal; // unit, (du x dv) direction: the side the face loops wind toward
};

// Parameter points and triangles covering one face's domain, from Bfr's tessellation.
struct FaceTessellation {
  std::vector<Eigen::Vector2d> uv;
  std::vector<std::array<int, 3>> triangles; // indices into uv, same winding as the face
};

// 4 is the least level that matches exact evaluation near extraordinary vertices to
// rounding (docs/METHOD.md §1); OpenSubdiv's default of 2 is off by up to 4e-3 mm on a unit cube.
inline constexpr int min_approx_level = 4;
inline constexpr int max_approx_level = 10;

class LimitSurface {
public:
  [[nodiscard]] static Expected<LimitSurface> build(const Cage& cage,
                                                    int approx_level = min_approx_level);

  LimitSurface(LimitSurface&&) noexcept;
  LimitSurface& operator=(LimitSurface&&) noexcept;
  ~LimitSurface();

  [[nodiscard]] int face_count() const;
  // False for faces without a limit surface (boundary faces when boundary = none).
  [[nodiscard]] bool has_patch(int face) const;
  // Vertex count of the cage face, which decides Bfr's parameter domain for it.
  [[nodiscard]] int face_size(int face) const;
  [[nodiscard]] int approx_level() const; // as built

  // (u, v) must lie in the face's domain; a degenerate tangent plane (du and dv within
  // 1e-6 rad of parallel, where their cross product is rounding) is an error.
  [[nodiscard]] Expected<LimitSample> evaluate(int face, double u, double v) const;

  // As evaluate(), but where the tangent plane degenerates or is too ill-conditioned for
  // curvature (du and dv within 1e-3 rad of parallel: a valence-2 corner of an interpolated
  // boundary): the point stays exact, the normal is the limit of its neighbourhood's (a
  // hair toward the face's centre), and the derivatives and curvature are the neighbourhood's
  // at the scale of a mesh cell (where du and dv are 3 degrees apart, a few hundredths of the
  // way to the centre), since the corner's own curvature grows without bound.
  [[nodiscard]] Expected<LimitSample> evaluate_regular(int face, double u, double v) const;

  // `rate` segments along each edge of the face (1..256); empty for a face without patch.
  [[nodiscard]] FaceTessellation tessellate(int face, int rate) const;
  // edge_rates[i] segments along the edge from the face's vertex i to vertex i+1 and
  // `inner` across the face, so neighbours that agree on their shared edge's rate meet
  // point for point. The boundary points come first, corner i then its edge's inner points.
  [[nodiscard]] FaceTessellation tessellate(int face, const std::vector<int>& edge_rates,
                                            int inner) const;

  // Parameter triangles about `rate` to an edge, each inside one parameter tile of the face,
  // so that (u, v) interpolated linearly across a triangle stays on the surface: a quad's
  // domain is one tile (as tessellate()); a face of another size (a triangle, a pentagon),
  // which Bfr lays out as one quad tile per corner round the centre, is cut tile by tile
  // (tessellate() joins points of neighbouring tiles into triangles across the gaps).
  // Points are not shared between tiles.
  [[nodiscard]] FaceTessellation tessellate_tiles(int face, int rate) const;

private:
  struct Patches;
  // Bfr's evaluation as it is, the normal zero where du x dv is.
  [[nodiscard]] Expected<LimitSample> sample(int face, double u, double v) const;
  explicit LimitSurface(std::unique_ptr<Patches> patches);
  std::unique_ptr<Patches> patches_;
};

} // namespace subfeed::geometry

#pragma once
// Distances to the limit surface itself, not to a mesh of it: what the motion gate and the
// planner's own poses are held to, so that neither rests on how finely the surface was cut.
//
// How: a guide mesh of the limit patches (each cage face tessellated at a modest rate, its
// triangles not welded across faces) in a box tree finds the patches a query comes near;
// each guide triangle carries a bound on how far the surface over its own (u, v) triangle
// strays from it, measured at build by evaluating the surface inside it. A triangle whose
// distance less its bound cannot beat the nearest found is skipped; every other is refined
// on the surface: Newton on (u, v) (and the segment's parameter) by Bfr's exact first and
// second derivatives, held to that (u, v) triangle, so the pieces searched cover every
// face's domain and each piece's least distance is found where it lies.
//
// Promise: a distance returned is the distance to a point of the limit surface (exact to
// Newton's convergence, 1e-9 mm); the nearest point is missed only if the surface over a
// guide triangle strays from it by more than twice the most its samples showed (the bound
// keeps that factor), which the tests hold on curved faces, creases and extraordinary
// vertices. Memory and time grow with the cage's faces and the guide rate, not with a
// tolerance: a cage face beside a crease costs what any face costs.

#include "base/error.hpp"
#include "geometry/cage.hpp"
#include "geometry/limit_surface.hpp"

#include <Eigen/Core>
#include <memory>
#include <optional>

namespace subfeed::geometry {

struct LimitNearest {
  double distance = 0.0;      // mm
  Eigen::Vector3d on_segment; // the query's point nearest the surface
  Eigen::Vector3d on_surface; // the surface's point nearest the query
  int face = -1;              // cage face of `on_surface`
  Eigen::Vector2d uv;         // its parameters in that face's domain
};

struct LimitDistanceOptions {
  // mm the guide triangles aim to keep from the surface, and the most segments a cage face
  // edge takes for it: a face that would need more keeps a wider bound, and costs only more
  // refinement near it.
  double guide_chord_mm = 0.005;
  int max_rate = 32;
  int approx_level = min_approx_level;
};

class LimitDistance {
public:
  // Its own limit surface of `cage`: nothing it answers rests on another stage's surface.
  [[nodiscard]] static Expected<LimitDistance> build(const Cage& cage,
                                                     const LimitDistanceOptions& options = {});

  LimitDistance(LimitDistance&&) noexcept;
  LimitDistance& operator=(LimitDistance&&) noexcept;
  ~LimitDistance();

  // The nearest point of the surface to segment pq if nearer than `limit` (mm), else none.
  [[nodiscard]] std::optional<LimitNearest> nearest(const Eigen::Vector3d& p,
                                                    const Eigen::Vector3d& q, double limit) const;
  [[nodiscard]] std::optional<LimitNearest> nearest(const Eigen::Vector3d& p, double limit) const {
    return nearest(p, p, limit);
  }

  // How far `centre` must move along unit `dir` until no point of the surface lies nearer
  // than `radius` (0 where none does): a ball lifted clear of the surface, touching it.
  [[nodiscard]] double lift(const Eigen::Vector3d& centre, const Eigen::Vector3d& dir,
                            double radius) const;

  // `centre` moved out from the surface's nearest point until no point of the surface lies
  // nearer than `radius`: the shortest way clear where the surface is smooth (along its
  // normal) and round a crease (out from the edge). None where that does not settle, as in
  // a gap narrower than the ball.
  [[nodiscard]] std::optional<Eigen::Vector3d> pushed_clear(const Eigen::Vector3d& centre,
                                                            double radius) const;

  // The z of the surface's lowest point in the hollow under `start` (mm), found as the foot
  // of points far below: a mesh's lowest vertex, made exact.
  [[nodiscard]] double lowest_z_under(const Eigen::Vector3d& start) const;

  // The guide mesh's size and its largest bound, mm (for reports and benchmarks).
  [[nodiscard]] long guide_triangles() const;
  [[nodiscard]] double largest_bound() const;
  [[nodiscard]] const LimitSurface& surface() const;

  // mm to which a distance is exact: Newton stops within this.
  static constexpr double precision_mm = 1e-9;

private:
  struct Guide;
  explicit LimitDistance(std::unique_ptr<Guide> guide);
  std::unique_ptr<Guide> guide_;
};

} // namespace subfeed::geometry

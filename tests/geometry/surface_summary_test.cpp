#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/surface_summary.hpp"
#include "support/grid_cage.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using subfeed::geometry::BoundaryInterpolation;
using subfeed::geometry::LimitSurface;

TEST_CASE("a plane cage with sharp corners covers exactly its cage square") {
  auto cage = subfeed::testing::grid_cage(9, 5.0, 0, 0);
  cage.boundary = BoundaryInterpolation::edge_and_corner;
  const auto surface = LimitSurface::build(cage).value();
  const auto s = subfeed::geometry::summarize(cage, surface, 8).value();
  CHECK(s.patches == 64);
  CHECK(s.area == Approx(1600.0).margin(1e-9));
  CHECK(s.min.x() == Approx(-20.0).margin(1e-12));
  CHECK(s.max.y() == Approx(20.0).margin(1e-12));
  CHECK(s.max.z() == Approx(0.0).margin(1e-12));
  CHECK(s.cage.vertices == 81);
  CHECK(s.cage.quads == 64);
  CHECK(s.cage.boundary_edges == 32);
  CHECK(s.cage.extraordinary_vertices == 0);
}

TEST_CASE("the cube has eight extraordinary vertices and no boundary") {
  const auto stats = subfeed::geometry::cage_stats(subfeed::testing::cube_cage());
  CHECK(stats.extraordinary_vertices == 8);
  CHECK(stats.boundary_edges == 0);
}

TEST_CASE("the sample seat has the paper's dimensions") {
  const auto cage =
      subfeed::geometry::read_obj(std::string(SUBFEED_SOURCE_DIR) + "/examples/seat.obj");
  REQUIRE(cage);
  const auto surface = LimitSurface::build(*cage).value();
  const auto s = subfeed::geometry::summarize(*cage, surface, 64).value();
  const Eigen::Vector3d size = s.max - s.min;
  CHECK(size.x() == Approx(17.67).margin(1e-3));
  CHECK(size.y() == Approx(11.02).margin(1e-3));
  CHECK(size.z() == Approx(4.23).margin(1e-3));
}

TEST_CASE("the steepest slope of a tilted plane is its tilt, and of the dome 70 degrees") {
  auto cage = subfeed::testing::grid_cage(5, 5.0, 0, 0);
  for (auto& p : cage.positions) {
    p.z() = 0.5 * p.x(); // an affine cage has an affine limit surface, boundary included
  }
  const auto surface = LimitSurface::build(cage).value();
  const auto s = subfeed::geometry::summarize(cage, surface, 8).value();
  CHECK(s.steepest_deg == Approx(std::atan(0.5) * 180.0 / 3.14159265358979323846).epsilon(1e-9));
  const auto dome =
      subfeed::geometry::read_obj(std::string(SUBFEED_SOURCE_DIR) + "/examples/dome.obj");
  REQUIRE(dome);
  const auto d =
      subfeed::geometry::summarize(*dome, LimitSurface::build(*dome).value(), 16).value();
  CHECK(d.steepest_deg == Approx(70.0).margin(0.5));
}

#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/surface_summary.hpp"
#include "support/grid_cage.hpp"

#include <catch2/catch.hpp>

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

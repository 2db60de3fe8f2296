// The tear at a sharp convex crease, bridged by a stay-down link: the ball rolls over the
// edge, touching it all the way and cutting nothing below the surface. On the sample ridge
// (crease along y = 0) cut across the crease.

#include "geometry/limit_distance.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/toolpath_planner.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

using namespace subfeed;

TEST_CASE("a sharp crease is bridged by the ball rolling over its edge", "[slow]") {
  const auto cage = geometry::read_obj(std::string(SUBFEED_SOURCE_DIR) + "/examples/ridge.obj");
  REQUIRE(cage);
  const auto surface = geometry::LimitSurface::build(*cage);
  REQUIRE(surface);
  geometry::PlanOptions o;
  o.ball_radius = 3.0;
  o.scallop = 0.03;
  o.direction_deg = 90.0; // across the crease
  o.stay_down = 4.0;
  auto planner = geometry::ToolpathPlanner::prepare(*cage, *surface, o);
  REQUIRE(planner);
  std::vector<cl::ClPose> over_edge; // feed poses whose ball centre is over the crease
  REQUIRE(planner->run([&](const cl::ClPose& p) -> Expected<void> {
    const double centre_y = p.tip[1] + o.ball_radius * p.axis[1];
    if (p.kind == cl::MoveKind::feed && std::abs(centre_y) < 0.5) {
      over_edge.push_back(p);
    }
    return {};
  }));
  const auto& s = planner->summary();
  INFO(s.stay_down_links << " stay-down links, " << over_edge.size() << " poses over the edge");
  CHECK(s.stay_down_links * 10 >= s.passes * 9); // the crease no longer retracts
  REQUIRE(over_edge.size() > 100);
  // Measured on the limit surface itself, where the poses are placed.
  const auto exact = geometry::LimitDistance::build(*cage);
  REQUIRE(exact);
  double worst_gap = 0.0, worst_cut = 0.0, farthest_contact = 0.0;
  for (const auto& p : over_edge) {
    const Eigen::Vector3d centre = Eigen::Vector3d(p.tip[0], p.tip[1], p.tip[2]) +
                                   o.ball_radius * Eigen::Vector3d(p.axis[0], p.axis[1], p.axis[2]);
    const auto near = exact->nearest(centre, 2.0 * o.ball_radius);
    REQUIRE(near);
    worst_gap = std::max(worst_gap, near->distance - o.ball_radius);
    worst_cut = std::max(worst_cut, o.ball_radius - near->distance);
    farthest_contact = std::max(farthest_contact, std::abs(near->on_surface.y()));
  }
  INFO("ball off the surface by up to " << worst_gap << " mm, into it by up to " << worst_cut
                                        << " mm, touching it up to " << farthest_contact
                                        << " mm from the edge");
  CHECK(worst_cut <= 1e-6);        // never below the surface
  CHECK(worst_gap <= 2e-3);        // touching: no air gap over the edge
  CHECK(farthest_contact <= 0.05); // and the contact is the edge itself
}

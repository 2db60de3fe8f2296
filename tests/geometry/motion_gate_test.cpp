// The motion gate against paths that are wrong on purpose, on surfaces with exact answers:
// the plane z = 0 and the grid dome z = a (x^2 + y^2) (exact on interior faces).

#include "geometry/closest_point.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/motion_gate.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/triangle_tree.hpp"
#include "support/grid_cage.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <random>

using namespace subfeed;

namespace {

constexpr double r = 3.0;

struct Part {
  geometry::Cage cage;
  geometry::LimitSurface surface;
};

Part part(double a, double z0 = 0.0, int n = 9) {
  auto cage = subfeed::testing::lifted(subfeed::testing::grid_cage(n, 5.0, a, a), z0);
  auto surface = geometry::LimitSurface::build(cage);
  REQUIRE(surface);
  return {std::move(cage), std::move(*surface)};
}

geometry::MotionGate gate_for(const Part& p, double tolerance = 1e-3) {
  auto gate = geometry::MotionGate::build(p.cage, p.surface, {r, tolerance, false, {}, {}});
  REQUIRE(gate);
  return std::move(*gate);
}

cl::ClPose pose(double x, double y, double z, cl::MoveKind kind = cl::MoveKind::feed,
                Eigen::Vector3d axis = Eigen::Vector3d::UnitZ(), long line = 0) {
  return {{x, y, z},
          {axis.x(), axis.y(), axis.z()},
          kind,
          kind == cl::MoveKind::rapid ? 0 : 500.0,
          line};
}

// The ball touching the dome z = a (x^2 + y^2) + z0 at (x, y), tool along the normal.
cl::ClPose on_dome(double a, double x, double y, double z0 = 0.0) {
  const Eigen::Vector3d n = Eigen::Vector3d(-2 * a * x, -2 * a * y, 1.0).normalized();
  return pose(x, y, a * (x * x + y * y) + z0, cl::MoveKind::feed, n);
}

} // namespace

TEST_CASE("the gate passes a pass on the plane and refuses it pushed in past 1 um", "[unit]") {
  const auto plane = part(0.0);
  for (const double z : {0.0, -0.0005, -0.0015, -0.01, -0.5}) {
    INFO("pass ending at z = " << z);
    auto gate = gate_for(plane);
    REQUIRE(gate.check(pose(-10, 0, 5, cl::MoveKind::rapid)));
    REQUIRE(gate.check(pose(-10, 0, 0.5, cl::MoveKind::rapid)));
    REQUIRE(gate.check(pose(-10, 0, 0, cl::MoveKind::plunge)));
    const auto across =
        gate.check(pose(10, 3, z, cl::MoveKind::feed, Eigen::Vector3d::UnitZ(), 17));
    if (z >= -0.001) {
      CHECK(across);
      CHECK(gate.report().moves == 4);
      continue;
    }
    REQUIRE_FALSE(across);
    CHECK(across.error().code == ErrorCode::bad_input);
    CHECK(across.error().where.line == 17);
    char depth[32];
    std::snprintf(depth, sizeof depth, "%.4f", -z);
    char end[32];
    std::snprintf(end, sizeof end, "%.4f", z);
    CHECK(across.error().message ==
          std::string("tool path refused: the cutting move from (-10.0000, 0.0000, 0.0000) to "
                      "(10.0000, 3.0000, ") +
              end + ") cuts " + depth +
              " mm into the part (tolerance 0.001 mm) at (10.0000, 3.0000, 0.0000)");
    // The refused pose is not taken: the gate stays where it was.
    CHECK(gate.report().moves == 3);
    CHECK(gate.check(pose(10, 3, 0)));
  }
}

TEST_CASE("the gate refuses a rapid through the part and one that only grazes it", "[unit]") {
  const auto plane = part(0.0);
  auto gate = gate_for(plane);
  REQUIRE(gate.check(pose(-10, 0, 10, cl::MoveKind::rapid)));
  REQUIRE(gate.check(pose(-10, 0, 0.01, cl::MoveKind::rapid))); // ball 0.01 mm above
  const auto through = gate.check(pose(10, 0, -2, cl::MoveKind::rapid));
  REQUIRE_FALSE(through);
  CHECK(through.error().message.find("the rapid from (-10.0000, 0.0000, 0.0100) to (10.0000, "
                                     "0.0000, -2.0000) touches the part (the ball 2.0000 mm "
                                     "deep)") != std::string::npos);
  // A rapid may not even touch: the ball resting on the part is refused, a feed is not.
  const auto resting = gate.check(pose(-10, 0, 0, cl::MoveKind::rapid));
  REQUIRE_FALSE(resting);
  CHECK(resting.error().message.find("touches the part") != std::string::npos);
  CHECK(gate.check(pose(-10, 0, 0, cl::MoveKind::plunge)));
  // The first pose alone, already inside.
  auto fresh = gate_for(plane);
  const auto inside = fresh.check(pose(0, 0, -1, cl::MoveKind::rapid));
  REQUIRE_FALSE(inside);
  CHECK(inside.error().message.find("the first pose, a rapid at (0.0000, 0.0000, -1.0000),") !=
        std::string::npos);
}

TEST_CASE("the gate measures the sweep between poses, not only the poses", "[unit]") {
  // Two poses that each touch a dome exactly: the straight move between them cuts through
  // the top by the CL curve's sagitta, which no check of the poses alone could see.
  for (const double a : {-0.01, -0.04}) {
    for (const double z0 : {0.0, 20.0}) {
      INFO("dome a = " << a << ", lifted " << z0 << " mm");
      const auto dome = part(a, z0, 5); // interior faces, where it is exact: |x|, |y| < 5
      auto gate = gate_for(dome);
      REQUIRE(gate.check(on_dome(a, -4.5, 1, z0)));
      auto alone = gate_for(dome);
      REQUIRE(alone.check(on_dome(a, 4.5, 1, z0)));
      const auto over = gate.check(on_dome(a, 4.5, 1, z0));
      REQUIRE_FALSE(over);
      CHECK(over.error().message.find("cuts") != std::string::npos);
      // Small steps along the same line, from where the refused move left the gate (at its
      // last accepted pose), touch all the way.
      for (double x = -4.4; x <= 4.5 + 1e-9; x += 0.1) {
        const auto step = gate.check(on_dome(a, x, 1, z0));
        INFO("x = " << x);
        REQUIRE(step);
      }
    }
  }
}

TEST_CASE("the gate measures the depth on the limit surface itself", "[unit]") {
  // A ball pushed along the normal into domes and bowls of several curvatures is reported
  // as deep as it was pushed, to the message's 0.1 um: no mesh chord stands in between.
  for (const double a : {-0.05, -0.02, 0.0, 0.02, 0.05}) {
    const auto dome = part(a);
    for (const double depth : {0.0123, 0.0457}) {
      auto gate = gate_for(dome); // the first pose is measured where it stands
      auto in = on_dome(a, 2.0, 1.0);
      const Eigen::Vector3d n(in.axis[0], in.axis[1], in.axis[2]);
      for (int i = 0; i < 3; ++i) {
        in.tip[static_cast<std::size_t>(i)] -= depth * n[i];
      }
      const auto refused = gate.check(in);
      REQUIRE_FALSE(refused);
      INFO(refused.error().message);
      CHECK(refused.error().message.find(fmt::format("cuts {:.4f} mm", depth)) !=
            std::string::npos);
    }
    CHECK(gate_for(dome).report().chord <= 1e-9);
  }
}

TEST_CASE("segment to triangle: the nearest pair against dense sampling", "[unit]") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  const auto point = [&] {
    return Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
  };
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d a = point(), b = point(), c = point(), p = point();
    const Eigen::Vector3d q = trial % 5 == 0 ? p : point(); // some segments are points
    const auto nearest = geometry::closest_segment_triangle(p, q, a, b, c);
    // The pair lies on the segment and the triangle, so it is never nearer than the truth.
    CHECK((geometry::closest_on_segment(nearest.on_segment, p, q) - nearest.on_segment).norm() <
          1e-9);
    CHECK(
        (geometry::closest_on_triangle(nearest.on_triangle, a, b, c) - nearest.on_triangle).norm() <
        1e-9);
    double sampled = 1e300;
    for (int i = 0; i <= 400; ++i) {
      const Eigen::Vector3d s = p + (i / 400.0) * (q - p);
      sampled = std::min(sampled, (geometry::closest_on_triangle(s, a, b, c) - s).norm());
    }
    INFO("trial " << trial);
    CHECK(nearest.distance() <= sampled + 1e-12);
    CHECK(nearest.distance() >= sampled - 0.5 * (q - p).norm() / 400.0 - 1e-12);
  }
}

TEST_CASE("triangle tree: the nearest point under a limit as every triangle gives it", "[unit]") {
  const auto dome = part(-0.02);
  const auto mesh = geometry::mesh_surface(dome.cage, dome.surface, 6);
  REQUIRE(mesh);
  const geometry::TriangleTree tree(mesh->points, mesh->triangles);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> xy(-22.0, 22.0), z(-4.0, 6.0), step(-3.0, 3.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d p(xy(random), xy(random), z(random));
    const Eigen::Vector3d q = p + Eigen::Vector3d(step(random), step(random), step(random));
    double truth = 1e300;
    for (const auto& t : mesh->triangles) {
      truth = std::min(truth, geometry::closest_segment_triangle(
                                  p, q, mesh->points[static_cast<std::size_t>(t[0])],
                                  mesh->points[static_cast<std::size_t>(t[1])],
                                  mesh->points[static_cast<std::size_t>(t[2])])
                                  .distance());
    }
    INFO("trial " << trial);
    for (const double limit : {1.0, 3.0, 100.0}) {
      const auto found = tree.nearest(p, q, limit);
      if (truth < limit) {
        REQUIRE(found);
        CHECK(found->distance == Approx(truth).margin(1e-12));
      } else {
        CHECK_FALSE(found);
      }
    }
  }
}

TEST_CASE("a boundary corner's normal is its neighbourhood's wherever the part stands", "[unit]") {
  // At an interpolated boundary's valence-2 corner du and dv are parallel: their cross
  // product is rounding, which once turned the corner normal 90 degrees, inward or outward
  // by the coordinates' magnitude (a dome lifted 20 mm was cut 3 mm deep).
  const auto reference = part(-0.02);
  const auto expected = reference.surface.evaluate_regular(0, 0.01, 0.01);
  REQUIRE(expected);
  for (const double z0 : {0.0, 5.0, 12.0, 20.0, 1000.0}) {
    INFO("lifted " << z0 << " mm");
    const auto dome = part(-0.02, z0);
    CHECK_FALSE(dome.surface.evaluate(0, 0.0, 0.0)); // degenerate, and said so
    const auto corner = dome.surface.evaluate_regular(0, 0.0, 0.0);
    REQUIRE(corner);
    CHECK(corner->normal.dot(expected->normal) > std::cos(0.5 * 3.14159265358979 / 180));
    CHECK(corner->point.z() == Approx(z0 + reference.surface.evaluate_regular(0, 0, 0)->point.z()));
    // And the rates the planner meshes with do not depend on where the part stands (at a
    // tolerance that puts no face's rate on a whole number, where rounding could tip it).
    CHECK(geometry::rates_for_tolerance(dome.surface, 3e-4) ==
          geometry::rates_for_tolerance(reference.surface, 3e-4));
  }
}

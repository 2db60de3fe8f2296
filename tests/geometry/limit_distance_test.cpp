// Distances to the limit surface by refinement on its patches, held to surfaces whose
// distances are known: the grid paraboloids z = a x^2 + b y^2 (exact on interior faces),
// over curvatures, signs and aspect ratios; and, where no closed form exists (a cube's
// extraordinary corners, creased edges), to a mesh 64 times finer than the guide.

#include "geometry/limit_distance.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/triangle_tree.hpp"
#include "support/grid_cage.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>

using namespace subfeed;

namespace {

// Every edge of `cage` creased at `sharpness` (10: infinitely sharp).
void crease_every_edge(geometry::Cage& cage, double sharpness) {
  for (int f = 0; f < cage.face_count(); ++f) {
    const auto loop = cage.face(f);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int u = loop[i], v = loop[(i + 1) % loop.size()];
      if (u < v) {
        cage.creases.push_back({u, v, sharpness, 0});
      }
    }
  }
}

// The distance from p to z = a x^2 + b y^2 over |x|, |y| <= half, by a dense search refined
// by Newton on (x, y): the reference the oracle is held to.
double paraboloid_distance(const Eigen::Vector3d& p, double a, double b, double half) {
  const auto f = [&](double x, double y) {
    return Eigen::Vector3d(x - p.x(), y - p.y(), a * x * x + b * y * y - p.z()).squaredNorm();
  };
  double bx = 0.0, by = 0.0, best = 1e300;
  const int n = 400;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double x = -half + 2.0 * half * i / n, y = -half + 2.0 * half * j / n;
      if (const double v = f(x, y); v < best) {
        best = v, bx = x, by = y;
      }
    }
  }
  double step = 2.0 * half / n;
  for (int k = 0; k < 60; ++k) { // pattern search down to 1e-12 mm
    bool moved = false;
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const double x = std::clamp(bx + dx * step, -half, half),
                   y = std::clamp(by + dy * step, -half, half);
      if (const double v = f(x, y); v < best) {
        best = v, bx = x, by = y, moved = true;
      }
    }
    if (!moved) {
      step *= 0.5;
    }
  }
  return std::sqrt(best);
}

// A closed prism over a regular n-gon (radius 12 mm, 16 mm tall): two n-gon faces and n quads,
// outward loops; with n = 3 the ends are triangles.
geometry::Cage prism_cage(int n) {
  geometry::Cage cage;
  cage.source = "prism";
  for (int level = 0; level < 2; ++level) {
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * 3.14159265358979323846 * k / n;
      cage.positions.emplace_back(12.0 * std::cos(a), 12.0 * std::sin(a), level == 0 ? -8.0 : 8.0);
    }
  }
  const auto add = [&](std::vector<int> loop) {
    cage.face_offsets.push_back(static_cast<int>(cage.face_indices.size()));
    cage.face_indices.insert(cage.face_indices.end(), loop.begin(), loop.end());
    cage.face_sizes.push_back(static_cast<int>(loop.size()));
    cage.face_lines.push_back(0);
  };
  std::vector<int> bottom, top;
  for (int k = 0; k < n; ++k) {
    bottom.push_back(n - 1 - k);
    top.push_back(n + k);
    add({k, (k + 1) % n, n + (k + 1) % n, n + k});
  }
  add(bottom);
  add(top);
  return cage;
}

} // namespace

TEST_CASE("the limit distance matches the exact distance to paraboloids", "[unit]") {
  // g = 5 on a 9 x 9 grid: interior faces span |x|, |y| <= 15, exact there. Points are
  // kept over the middle so that their nearest point lies on the exact faces.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> across(-6.0, 6.0), height(0.2, 6.0);
  for (const auto& [a, b] : {std::pair{0.0, 0.0},
                             {0.02, 0.02},
                             {-0.03, -0.03},
                             {0.04, -0.02},
                             {0.05, 0.005},
                             {-0.01, 0.06}}) {
    INFO("z = " << a << " x^2 + " << b << " y^2");
    const auto cage = subfeed::testing::grid_cage(9, 5.0, a, b);
    const auto oracle = geometry::LimitDistance::build(cage);
    REQUIRE(oracle);
    for (int k = 0; k < 40; ++k) {
      const double x = across(random), y = across(random);
      const double z = a * x * x + b * y * y + (k % 2 == 0 ? 1.0 : -1.0) * height(random);
      const Eigen::Vector3d p(x, y, z);
      const double want = paraboloid_distance(p, a, b, 14.0);
      const auto got = oracle->nearest(p, 50.0);
      REQUIRE(got);
      INFO("from " << p.transpose());
      CHECK(std::abs(got->distance - want) < 1e-7);
      CHECK(std::abs(got->on_surface.z() - (a * got->on_surface.x() * got->on_surface.x() +
                                            b * got->on_surface.y() * got->on_surface.y())) < 1e-9);
      // Nothing is claimed nearer than the limit asked.
      CHECK_FALSE(oracle->nearest(p, want - 1e-6));
    }
  }
}

TEST_CASE("the limit distance to a segment is the least over the segment", "[unit]") {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> across(-5.0, 5.0), height(0.5, 4.0);
  for (const auto& [a, b] : {std::pair{0.03, 0.03}, {-0.03, 0.01}, {0.0, 0.0}}) {
    INFO("z = " << a << " x^2 + " << b << " y^2");
    const auto cage = subfeed::testing::grid_cage(9, 5.0, a, b);
    const auto oracle = geometry::LimitDistance::build(cage);
    REQUIRE(oracle);
    for (int k = 0; k < 15; ++k) {
      const Eigen::Vector3d p(across(random), across(random), height(random) + 1.0);
      const Eigen::Vector3d q(across(random), across(random), height(random) + 1.0);
      // The least over the segment, by a fine search along it.
      double want = 1e300;
      for (int i = 0; i <= 200; ++i) {
        want = std::min(want, paraboloid_distance(p + (q - p) * i / 200.0, a, b, 14.0));
      }
      const auto got = oracle->nearest(p, q, 50.0);
      REQUIRE(got);
      INFO("segment " << p.transpose() << " to " << q.transpose());
      CHECK(got->distance <= want + 1e-7);
      CHECK(got->distance >= want - 2e-4); // the fine search's own step along the segment
      CHECK(std::abs((got->on_segment - got->on_surface).norm() - got->distance) < 1e-12);
    }
  }
}

TEST_CASE("the limit distance agrees with a fine mesh by creases, extraordinary corners and "
          "faces of three and five sides",
          "[unit]") {
  auto cube = subfeed::testing::cube_cage();
  for (auto& p : cube.positions) {
    p *= 20.0; // a 20 mm cube: corners of radius a few mm
  }
  auto cage = cube;
  SECTION("a smooth cube") {}
  SECTION("a cube with every edge creased") {
    crease_every_edge(cage, 10.0);
  }
  SECTION("a cube with semi-sharp edges") {
    crease_every_edge(cage, 2.5);
  }
  SECTION("a triangular prism") {
    cage = prism_cage(3);
  }
  SECTION("a pentagonal prism") {
    cage = prism_cage(5);
  }
  const auto oracle = geometry::LimitDistance::build(cage);
  REQUIRE(oracle);
  CHECK(oracle->largest_bound() < 0.5);
  const auto& surface = oracle->surface();
  // 256 segments an edge: chords within a micrometre or so on these shapes.
  const auto fine = geometry::mesh_surface(cage, surface, 256);
  REQUIRE(fine);
  const geometry::TriangleTree tree(fine->points, fine->triangles);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-14.0, 14.0);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random));
    const Eigen::Vector3d q = p + Eigen::Vector3d(coordinate(random), coordinate(random), 0) * 0.1;
    const auto mesh = tree.nearest(p, q, 100.0);
    REQUIRE(mesh);
    const auto exact = oracle->nearest(p, q, 100.0);
    REQUIRE(exact);
    INFO("segment " << p.transpose() << " to " << q.transpose());
    // The fine mesh lies within its chord of the surface: the two agree to that.
    CHECK(std::abs(exact->distance - mesh->distance) < 2e-3);
    // The point found is on the surface: its own face evaluates there.
    const auto at = surface.evaluate_regular(exact->face, exact->uv.x(), exact->uv.y());
    REQUIRE(at);
    CHECK((at->point - exact->on_surface).norm() < 1e-12);
  }
}

TEST_CASE("a ball lifted clear of the limit surface touches it", "[unit]") {
  const double r = 3.0;
  for (const auto& [a, b] : {std::pair{0.04, 0.04}, {-0.1, -0.1}, {0.05, -0.05}}) {
    INFO("z = " << a << " x^2 + " << b << " y^2");
    const auto cage = subfeed::testing::grid_cage(9, 5.0, a, b);
    const auto oracle = geometry::LimitDistance::build(cage);
    REQUIRE(oracle);
    for (const double x : {-4.0, -1.5, 0.0, 2.5}) {
      const Eigen::Vector3d n = Eigen::Vector3d(-2 * a * x, -2 * b * x, 1.0).normalized();
      const Eigen::Vector3d contact(x, x, a * x * x + b * x * x);
      const Eigen::Vector3d sunk = contact + 0.5 * r * n; // half a radius into the part
      const double lift = oracle->lift(sunk, n, r);
      const Eigen::Vector3d centre = sunk + lift * n;
      CHECK_FALSE(oracle->nearest(centre, r - 1e-8));
      CHECK(oracle->nearest(centre, r + 1e-6));
      // Where the surface bends less than the ball, the ball touches at its own contact.
      if (std::abs(a) < 0.5 / r && std::abs(b) < 0.5 / r) {
        CHECK(std::abs(lift - 0.5 * r) < 1e-6);
      }
    }
  }
}

// The planner sets a sunk ball on the surface by the shorter of two ways: along its
// point's normal, or out from the surface's nearest point. Beside a crease the normal is
// one side's and the ball touches the edge: the push is the short way, its answer exact on
// a cube whose edges are all sharp (its limit surface is the cube itself).
TEST_CASE("a ball pushed out from the limit surface touches it, the short way round a crease",
          "[unit]") {
  auto cage = subfeed::testing::cube_cage();
  for (auto& p : cage.positions) {
    p *= 20.0; // the cube [-10, 10]^3
  }
  crease_every_edge(cage, 10.0);
  const auto oracle = geometry::LimitDistance::build(cage);
  REQUIRE(oracle);
  for (const double r : {1.0, 3.0}) {
    for (const double y : {-6.0, 0.0, 4.5}) {
      // Past the edge x = z = 10 at angles from its top face round to its side.
      for (const double deg : {15.0, 40.0, 45.0, 60.0, 80.0}) {
        const double a = deg * std::numbers::pi / 180.0;
        const Eigen::Vector3d out(std::sin(a), 0.0, std::cos(a)); // from the edge
        const Eigen::Vector3d edge(10.0, y, 10.0);
        const Eigen::Vector3d sunk = edge + 0.4 * r * out;
        INFO("r " << r << " y " << y << " at " << deg << " deg from the top face");
        const auto pushed = oracle->pushed_clear(sunk, r);
        REQUIRE(pushed);
        CHECK((*pushed - (edge + r * out)).norm() < 1e-6);
        CHECK_FALSE(oracle->nearest(*pushed, r - 1e-8));
        // Straight up the top face's normal is the long way: it must clear the edge too.
        const double up = oracle->lift(sunk, Eigen::Vector3d::UnitZ(), r);
        CHECK((*pushed - sunk).norm() < up);
      }
    }
    // Over the top face, away from the edge, the push is the lift along its normal.
    const Eigen::Vector3d sunk(2.0, -3.0, 10.0 + 0.3 * r);
    const auto pushed = oracle->pushed_clear(sunk, r);
    REQUIRE(pushed);
    CHECK((*pushed - Eigen::Vector3d(2.0, -3.0, 10.0 + r)).norm() < 1e-6);
  }
  // A ball wider than the hollow it is pushed in settles nowhere or somewhere clear: the
  // push never answers with a ball that cuts in.
  for (const double a : {0.2, 1.0, 3.0}) {
    const auto bowl = subfeed::testing::grid_cage(9, 5.0, a, a);
    const auto deep = geometry::LimitDistance::build(bowl);
    REQUIRE(deep);
    for (const double x : {0.0, 0.3, 1.1}) {
      INFO("bowl z = " << a << " (x^2 + y^2), ball at x " << x);
      const Eigen::Vector3d sunk(x, 0.2 * x, a * x * x + 0.5);
      if (const auto pushed = deep->pushed_clear(sunk, 3.0)) {
        CHECK_FALSE(deep->nearest(*pushed, 3.0 - 1e-8));
      }
    }
  }
}
